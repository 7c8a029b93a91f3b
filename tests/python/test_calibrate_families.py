# SPDX-License-Identifier: Apache-2.0
"""The candidate families calibrate ranks per firmware target: the input smoothers and the
specified-insensitivity shapers with --firmware none, the SI shapers as RepRapFirmware's
custom shaper, nothing a target cannot run."""
from __future__ import annotations

import math

import numpy as np
import pytest

from smoothshaper import for_mode, shaper
from smoothshaper.calibrate import Reference, firmware as fw
from smoothshaper.calibrate.candidates import chain_taps, continuity, duration, families
from smoothshaper.reference import shaper_impulses
from smoothshaper.stages import INPUT_SMOOTHERS

SI = {"si (n=3)", "si (n=5)", "si (n=7)"}


def test_none_ranks_input_smoothers_and_si():
    one = {f.name for f in families(1)}
    two = {f.name for f in families(2)}
    assert SI <= one and SI <= two
    assert not set(INPUT_SMOOTHERS) & one            # they join records of two modes or more
    assert set(INPUT_SMOOTHERS) <= two


@pytest.mark.parametrize("firmware", ["klipper", "marlin", "prusa"])
def test_other_targets_keep_only_their_own_shapers(firmware):
    names = [f.name for f in families(3, firmware)]
    assert names == [f"{firmware} {s.name}" for s in fw.shapers(firmware)]


def test_rrf_runs_si_as_its_custom_shaper():
    fams = families(1, "rrf")
    custom = [f for f in fams if f.shaper is not None and f.shaper.name == "custom"]
    assert [f.name for f in custom] == ["rrf custom si (n=3, 0.75 Td)",
                                        "rrf custom si (n=5, 1.5 Td)"]
    s = custom[1].shaper
    A, t = s.impulses(50.0, 0.1)
    ref_A, ref_t = shaper_impulses(shaper("si", wn=2 * math.pi * 50.0, zeta=0.1, order=5,
                                          duration=1.5))
    # the firmware's delays are whole step clocks (750 kHz), its last amplitude 1 - sum
    assert A.sum() == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(A, ref_A / ref_A.sum(), rtol=0, atol=1e-15)
    np.testing.assert_allclose(t, np.round(ref_t * 750000.0) / 750000.0, rtol=0, atol=1e-15)
    text = fw.config_text("rrf", {"x": fw.Pick(s, 50.0, 0.1, fw.max_accel(A, t))})
    assert 'M593 P"custom" H' in str(text) and text.warnings == ()
    with pytest.raises(ValueError):
        fw.rrf_si(7, 2.0)                    # seven impulses: more than the firmware holds


@pytest.mark.parametrize("kind", INPUT_SMOOTHERS)
def test_input_smoother_length_and_class(kind):
    """The tuning's length without building the taps is the taps' own, and the filtered step
    is C1 (a continuous kernel, zero at both ends)."""
    st = for_mode(kind, wn=2 * math.pi * 47.0, zeta=0.1 if kind in (
        "smooth_zv", "smooth_mzv", "smooth_ei") else 0.0)
    Ts = Reference().Ts
    h = chain_taps([st], Ts)
    assert duration([st], Ts) == pytest.approx((h.size - 1) * Ts, abs=1e-15)
    assert continuity([st]) == 1
