# SPDX-License-Identifier: Apache-2.0
"""Seed 002 (Damped-Jerk profile): every number of the report's section holds."""
import math

import pytest

from smoothshaper.report import seed002

SECTION = seed002.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_claim_holds(claim):
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} +- {claim.tol!r} ({claim.reference})")


def test_profiles_are_time_optimal_compliant():
    """T1 >= T2 + T3 and T2 >= T3 (seed 000 eq. 3): the example respects the limits."""
    prof, Td = seed002.profiles()
    T = [s.T for s in prof["jerk-limited"]]
    assert T[0] >= T[1] + T[2] and T[1] >= T[2]
    assert T[2] == pytest.approx(2 * math.pi / (seed002.WN * math.sqrt(1 - seed002.ZETA ** 2)))


def test_jerk_limited_leaves_a_residual_the_damped_jerk_does_not():
    c = {x.key: x.ours for x in SECTION.claims}
    assert c["sim.jerk-limited"] > 1.0          # per cent
    assert c["sim.Damped-Jerk"] < 1e-8
