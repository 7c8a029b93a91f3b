# SPDX-License-Identifier: Apache-2.0
"""Checks shared by the calibrate tests that hold a pick to the established tool's."""
from __future__ import annotations

import pytest

from smoothshaper.calibrate.candidates import candidate_taps

import klipper_pick

#: The acceptance margin over the established pick's remaining vibration [percentage points].
VIBRATION_PP = 0.1


def estimate(c, Ts, data):
    """What the candidate leaves by the established estimate [%]: a firmware's shaper by its
    own impulses (the firmware runs them in continuous time), else the exact taps."""
    if c.firmware is not None:
        shaper, freq, damping = c.firmware
        A, T = shaper.impulses(freq, damping)
    else:
        A, T = klipper_pick.taps_as_impulses(candidate_taps(c, Ts), Ts)
    return 100.0 * klipper_pick.remaining(A, T, data)


def assert_held_to_pick(res, Ts, data, pick):
    """The default budget is the established pick, every firmware candidate's figure is the
    established estimate on ``data``, and the recommendation leaves at most the pick's
    remaining vibration + VIBRATION_PP."""
    assert res.default_limit.shaper == f"klipper {pick['name']}"
    assert res.default_limit.freq == pytest.approx(pick["freq"], abs=0.1)
    for c in res.candidates:
        if c.firmware is not None:
            assert c.vibration_established == pytest.approx(estimate(c, Ts, data), abs=1e-3)
    assert estimate(res.recommended, Ts, data) <= 100 * pick["vibrs"] + VIBRATION_PP
