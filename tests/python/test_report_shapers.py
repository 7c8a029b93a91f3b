# SPDX-License-Identifier: Apache-2.0
"""Beyond the seeds (shaper insensitivity): every number of the report's section holds."""
import math

import pytest

from smoothshaper.report import shapers

SECTION = shapers.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_claim_holds(claim):
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} +- {claim.tol!r} ({claim.reference})")


@pytest.mark.parametrize("kind", shapers.KINDS)
def test_closed_form_widths_match_a_brute_force_scan(kind):
    """The closed forms the report asserts against, checked against a dense scan of the
    undamped residual sum_m B_m e^{-j r 2 pi t_m} written from the published amplitudes."""
    import numpy as np
    V = 0.05
    sq = math.sqrt(2)
    X = (V * V * (math.sqrt(1 - V * V) + 1)) ** (1 / 3)
    a1 = (3 * X * X + 2 * X + 3 * V * V) / (16 * X)
    design = {"zv": ([.5, .5], [0, .5]), "zvd": ([.25, .5, .25], [0, .5, 1]),
              "ei": ([(1 + V) / 4, (1 - V) / 2, (1 + V) / 4], [0, .5, 1]),
              "mzv": ([1 - 1 / sq, sq - 1, 1 - 1 / sq], [0, .375, .75]),
              "ei2": ([a1, .5 - a1, .5 - a1, a1], [0, .5, 1, 1.5])}[kind]
    r = np.linspace(0.3, 1.7, 1_400_001)
    res = np.abs(sum(b * np.exp(-2j * np.pi * r * t) for b, t in zip(*design)))
    ok = res <= V * (1 + 1e-9)
    i = int(np.argmin(abs(r - 1)))
    lo, hi = i, i
    while ok[lo - 1]:
        lo -= 1
    while ok[hi + 1]:
        hi += 1
    assert r[hi] - r[lo] == pytest.approx(shapers.closed_form_width(kind), abs=3e-6)
