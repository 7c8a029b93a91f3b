# SPDX-License-Identifier: Apache-2.0
"""Seed 000 (damped harmonic smoother): every number of the report's section holds, and every
disagreement with the paper that the report explains is real."""
import math

import numpy as np
import pytest

from smoothshaper.report import seed000

SECTION = seed000.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_claim_holds(claim):
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} +- {claim.tol!r} ({claim.reference})")


@pytest.mark.parametrize("claim", [c for c in SECTION.claims if c.disagrees_with_paper],
                         ids=lambda c: c.key)
def test_explained_disagreements_are_real(claim):
    assert claim.note, "a disagreement with the paper needs an explanation"
    if claim.relation == "==":
        assert abs(claim.ours - claim.paper) > claim.tol
    else:
        assert claim.ours != claim.paper


def test_harmonic_closed_form_is_the_seed_formula():
    """|S(jw)| = |cos(pi w/wi)|/|1 - (w/(wi/2))^2| with wi = 2 pi/T (seed eq. after (8)),
    written out here for T = 3 pi against the module's helper."""
    r = np.array([0.2, 0.5, 0.9, 1.0, 1.6, 2.0, 3.1])
    wi = 2 * math.pi / (3 * math.pi)
    direct = 100 * np.abs(np.cos(math.pi * r / wi)) / np.abs(1 - (r / (wi / 2)) ** 2)
    assert np.allclose(seed000.harmonic_prv_closed_form(r), direct, rtol=1e-13, atol=1e-13)


def test_experiment_ratio_is_the_papers_non_integer_153_6():
    T = 1.5 * 2 * math.pi / seed000.EXP_WD
    assert T / seed000.EXP_TS == pytest.approx(153.6, abs=1e-3)
