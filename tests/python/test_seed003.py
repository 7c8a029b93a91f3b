# SPDX-License-Identifier: Apache-2.0
"""Seed 003 (B-spline filters as input shapers): every number of the report's section holds."""
import math

import numpy as np
import pytest

from smoothshaper.report import seed003

SECTION = seed003.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_claim_holds(claim):
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} +- {claim.tol!r} ({claim.reference})")


def test_r5_is_where_the_cubic_sinc_crosses_five_percent():
    r5 = seed003.r5_closed_form()
    assert 100 * abs(np.sinc(r5)) ** 3 == pytest.approx(5.0, abs=1e-9)
    # |sinc(r)| <= 1/(pi r) < 0.05^(1/3) beyond r = 1/(pi 0.05^(1/3)): the band is unbounded
    assert 1 / (math.pi * 0.05 ** (1 / 3)) < 1.0


def test_robot_parameters_give_the_papers_modes():
    for axis, (m, d, k) in seed003.ROBOT.items():
        wn, delta = seed003.ROBOT_PAPER[axis]
        assert math.sqrt(k / m) == pytest.approx(wn, abs=0.05)
        assert d / (2 * math.sqrt(k * m)) == pytest.approx(delta, abs=5e-4)


def test_robot_via_points_are_equally_spaced_and_three_dimensional():
    from smoothshaper.report import seed003_robot
    via = seed003_robot.via_points()
    steps = np.linalg.norm(np.diff(via[:, :2], axis=0), axis=1)
    assert via.shape[1] == 3 and via.shape[0] >= 20
    assert np.ptp(via[:, 2]) > 0                  # z moves too
    # chords of a path sampled equally in arc length: equal on straight parts, shorter on bends
    assert steps.max() == pytest.approx(seed003_robot.SPACING, rel=0.01)
    assert steps.min() > 0.95 * seed003_robot.SPACING
