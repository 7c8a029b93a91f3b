# SPDX-License-Identifier: Apache-2.0
"""Seed 001 (trigonometric blends): every number of the report's section holds, and the
erratum it explains (printed T3 = 0.0209 s) is a real disagreement."""
import math

import numpy as np
import pytest

pytest.importorskip("smoothshaper.design", reason="seed 001 needs smoothshaper.design.kinematic")
from smoothshaper.report import seed001  # noqa: E402

SECTION = seed001.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_claim_holds(claim):
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} +- {claim.tol!r} ({claim.reference})")


def test_printed_double_s_T3_is_an_erratum():
    (claim,) = [c for c in SECTION.claims if c.key == "fig9.T3.ds"]
    assert claim.disagrees_with_paper and claim.note
    assert abs(claim.ours - claim.paper) > 1e-3          # 0.0241 vs 0.0209


def test_spectrum_closed_form_vanishes_at_the_harmonic_zero():
    """|S(jw)| of seed 001 Sec. 3.1 is zero at w = 3 pi/T3; every stage has unit DC gain."""
    T = [0.16, 0.05, 0.03618868]
    w0 = 3 * math.pi / T[-1]
    assert seed001.spectrum_closed_form(T, [w0], last="harmonic")[0] < 1e-12
    w = np.array([1e-3])
    # at low frequency |V| ~ h w (unit DC gain of every stage)
    assert seed001.spectrum_closed_form(T, w, last="harmonic")[0] == pytest.approx(40e-3, rel=1e-6)
