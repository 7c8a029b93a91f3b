# SPDX-License-Identifier: Apache-2.0
"""The report machinery: claims, markdown assembly, figures, failure reporting."""
import math

import pytest

from smoothshaper import report
from smoothshaper.report import claims as cl


def test_claim_relations():
    assert cl.Claim("a", "x", 1.0, 1.05, 0.1, "r").holds
    assert not cl.Claim("a", "x", 1.0, 1.2, 0.1, "r").holds
    assert cl.Claim("a", "x", 1.05, 1.0, 0.1, "r", relation="<=").holds
    assert not cl.Claim("a", "x", 1.2, 1.0, 0.1, "r", relation="<=").holds
    assert cl.Claim("a", "x", 0.95, 1.0, 0.1, "r", relation=">=").holds
    assert not cl.Claim("a", "x", 0.8, 1.0, 0.1, "r", relation=">=").holds
    assert not cl.Claim("a", "x", math.nan, 1.0, 0.1, "r").holds


def test_claim_rejects_bad_relation_and_tolerance():
    with pytest.raises(ValueError, match="relation"):
        cl.Claim("a", "x", 1.0, 1.0, 0.1, "r", relation="<")
    with pytest.raises(ValueError, match="tol"):
        cl.Claim("a", "x", 1.0, 1.0, -1.0, "r")


def test_disagreement_flag_and_table_note():
    c = cl.Claim("k", "T3", 0.0241, 0.0241, 1e-6, "closed form", paper=0.0209, note="typo")
    assert c.disagrees_with_paper
    table = cl.claims_table([c])
    assert "[note 1]" in table and "typo" in table and "0.0209" in table


def test_section_rejects_duplicate_keys():
    sec = cl.Section("s", "t", "c", "cmd")
    sec.add(cl.Claim("a", "x", 1.0, 1.0, 0.0, "r"))
    with pytest.raises(ValueError, match="duplicate"):
        sec.add(cl.Claim("a", "y", 1.0, 1.0, 0.0, "r"))


def test_unknown_section_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="only"):
        report.run("unused", only=["nope"])
    with pytest.raises(ValueError, match="section"):
        report.build_section("nope")


def test_run_writes_readme_and_readable_figures(tmp_path):
    readme = report.run(tmp_path, only=["seed004", "shapers"])
    text = readme.read_text()
    assert text.startswith("# smoothshaper: reproduction of the seed papers")
    for key in ("seed004", "shapers"):
        section = report.build_section(key)
        for claim in section.claims:
            assert claim.what.replace("|", "\\|") in text
    pngs = sorted((tmp_path / "figures").rglob("*.png"))
    assert len(pngs) >= 4
    for png in pngs:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert f"]({png.relative_to(tmp_path).as_posix()})" in text
    assert "**NO**" not in text


def test_a_failing_claim_fails_the_run(tmp_path, monkeypatch):
    from smoothshaper.report import seed004
    real = seed004.build

    def drifted(fig_dir=None):
        sec = real(fig_dir)
        sec.add(cl.Claim("drift", "a number that drifted", 2.0, 1.0, 0.1, "paper"))
        return sec

    monkeypatch.setattr(seed004, "build", drifted)
    with pytest.raises(RuntimeError, match="drift"):
        report.run(tmp_path, only=["seed004"])
    assert "**NO**" in (tmp_path / "README.md").read_text()


def test_figure_without_axis_labels_is_refused(tmp_path):
    from smoothshaper.report.figures import figure
    out = []
    with pytest.raises(ValueError, match="labels"):
        with figure(tmp_path / "bad.png", "bad", out) as (fig, ax):
            ax.plot([0, 1], [0, 1], label="line")
    assert out == []


def test_pipes_in_claim_text_do_not_split_table_cells():
    c = cl.Claim("k", "|H(p)| at the mode", 0.0, 0.0, 1e-12, "closed form |S(p)|")
    row = cl.claims_table([c]).splitlines()[2]
    assert row.count(" | ") == 5          # six cells: what, paper, ours, asserted, tol, ok
    assert "\\|H(p)\\|" in row


def test_links_the_fmu_validation_report_when_present(tmp_path):
    (tmp_path / "validation").mkdir()
    (tmp_path / "validation" / "README.md").write_text("# validation\n")
    readme = report.run(tmp_path / "report", only=["shapers"])
    assert "](../validation/README.md)" in readme.read_text()
