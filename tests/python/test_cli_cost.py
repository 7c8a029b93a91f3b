# SPDX-License-Identifier: Apache-2.0
"""Long CLI requests: estimates before they start, refusals naming the parameter, one progress
bar over the whole work, silence when not asked for."""
import io
import re

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import analysis, cli
from smoothshaper.cli import cost as cli_cost
from smoothshaper.cli.common import Progress
from smoothshaper.reference import impulse_response


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _seconds(text):
    m = re.search(r"about ([\d.]+) (s|min)", text)
    assert m, text
    return float(m.group(1)) * (60 if m.group(2) == "min" else 1)


# -- estimates -------------------------------------------------------------------------------

def test_analyze_of_a_1e7_sample_chain_is_estimated_without_running(tmp_path, capsys):
    out_dir = tmp_path / "never"
    code, out, err = run(capsys, "analyze", "--stage", "harmonic:T=1000", "--Ts", "1e-4",
                         "--wn", "1", "--zeta", "0.05", "--out", out_dir, "--estimate")
    assert code == 0, err
    assert "10000000 samples" in out and _seconds(out) > cli_cost.ANNOUNCE_SECONDS
    assert not out_dir.exists()                       # nothing ran, nothing was written


def test_the_analyze_model_grows_with_the_chain_and_the_points():
    def total(taps, sweep, surface=0):
        return cli_cost.analyze_cost(taps=taps, sweep=sweep, band=2101, surface=surface,
                                     spectrum=4000, step=taps, plotted=10_000).seconds
    assert total(10**7, 600) > 5 * total(10**5, 600)
    assert total(10**6, 60_000) > 2 * total(10**6, 600)
    assert total(10**6, 600, surface=61 * 600) > 3 * total(10**6, 600)


def test_chain_taps_is_the_c_chain_length_without_building_it():
    stages = [sms.harmonic(T=0.05), sms.shaper("zvd", wn=100.0, zeta=0.05)]
    length = sms.Chain(stages, Ts=1e-3).length      # a delay line holds at most one more
    assert length <= cli_cost.chain_taps(stages, 1e-3) <= length + len(stages)
    with pytest.raises(sms.ParameterError) as e:           # the chain's own named error
        cli_cost.chain_taps([sms.harmonic(T=1e-4)], 1e-3)
    assert e.value.parameter == "T"


def test_a_request_beyond_the_limit_is_refused_naming_the_parameter(tmp_path, capsys):
    # 1e8 taps x (61 x 600 surface points): about 20 min of work
    code, _, err = run(capsys, "analyze", "--stage", "harmonic:T=1000", "--Ts", "1e-5",
                       "--wn", "1", "--surface", "--out", tmp_path / "x")
    assert code == cli.EXIT_ERROR
    assert err.startswith("smoothshaper: error: --Ts:") and "600 s" in err, err
    assert "raise --Ts (or reduce --points, reduce --surface-points)" in err
    assert err.count("\n") == 1
    assert not (tmp_path / "x").exists()


def test_bspline_beyond_its_size_limit_is_refused_naming_T(capsys):
    code, _, err = run(capsys, "design", "bspline", "--via", "0,0;1,2;3,1;4,4", "--T", "10000",
                       "--Ts", "1e-3")
    assert code == cli.EXIT_ERROR and "--T=1e+04:" in err and "limit of 2e+07" in err, err


def test_bspline_and_generator_estimates(capsys):
    code, out, err = run(capsys, "design", "bspline", "--via", "0,0;1,2;3,1;4,4", "--T", "10000",
                         "--Ts", "1e-2", "--csv", "never.csv", "--estimate")
    assert code == 0 and "4999998 samples" in out, err
    assert _seconds(out) > cli_cost.ANNOUNCE_SECONDS              # the csv of 5e6 rows
    code, out, err = run(capsys, "design", "generator", "--via", "0,1000", "--vmax", "1",
                         "--amax", "10", "--jmax", "100", "--Ts", "1e-3", "--estimate")
    assert code == 0 and "samples" in out and "about" in out, err


def test_announce_prints_above_the_threshold_and_refuses_above_the_limit():
    stream = io.StringIO()
    cli_cost.announce(cli_cost.Cost("x", {"a": 1.0}), stream=stream)
    assert stream.getvalue() == ""
    cli_cost.announce(cli_cost.Cost("x", {"a": 30.0, "b": 12.0}), stream=stream)
    assert stream.getvalue() == "x: this will take about 42 s (a 30 s, b 12 s)\n"
    with pytest.raises(cli.CliError, match=r"^--n: x would take about 11.0 min .*limit of 600 s"):
        cli_cost.announce(cli_cost.Cost("x", {"a": 660.0}, {"--n": "many"}), stream=stream)


def test_a_long_request_announces_itself_before_the_bar(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cli_cost, "ANNOUNCE_SECONDS", 0.0)
    code, _, err = run(capsys, "analyze", "--stage", "harmonic:wn=100", "--Ts", "1e-3",
                       "--wn", "100", "--points", "50", "--out", tmp_path, "--progress")
    assert code == 0
    assert err.startswith("analyze: this will take about")
    assert err.index("this will take") < err.index("[")


# -- progress --------------------------------------------------------------------------------

def _bar_states(err):
    """(label, percent) of every drawn state of the bar."""
    return [(m.group(1).strip(), float(m.group(2)))
            for m in re.finditer(r"\r(.{14}) \[[# ]{30}\]\s+([\d.]+)%", err)]


def test_analyze_progress_covers_every_phase_in_order(tmp_path, capsys):
    code, _, err = run(capsys, "analyze", "--stage", "harmonic:T=2", "--stage",
                       "zv:wn=10,zeta=0.05", "--Ts", "1e-4", "--wn", "10", "--points", "300",
                       "--surface", "--surface-points", "6", "--out", tmp_path, "--progress")
    assert code == 0, err
    states = _bar_states(err)
    labels = list(dict.fromkeys(label for label, _ in states))
    assert labels == ["taps", "PRV sweep", "band", "PRV surface", "spectrum", "step response",
                      "plots"]
    percents = [p for _, p in states]
    assert percents == sorted(percents) and percents[-1] == 100.0 and percents[0] < 5
    # the evaluation phases move inside themselves, not only at their ends
    assert len({p for label, p in states if label == "PRV surface"}) > 2


def test_bspline_and_generator_progress_cover_filter_csv_and_plot(tmp_path, capsys):
    code, _, err = run(capsys, "design", "bspline", "--via", "0,0;1,2;3,1;4,4", "--T", "20",
                       "--Ts", "1e-3", "--csv", tmp_path / "b.csv", "--plot",
                       tmp_path / "b.png", "--progress")
    assert code == 0, err
    states = _bar_states(err)
    assert list(dict.fromkeys(label for label, _ in states)) == ["filter", "csv", "plot"]
    assert [p for _, p in states] == sorted(p for _, p in states) and states[-1][1] == 100.0
    code, _, err = run(capsys, "design", "generator", "--via", "0,20,5", "--vmax", "250",
                       "--amax", "5000", "--jmax", "200000", "--Ts", "1e-4", "--csv",
                       tmp_path / "g.csv", "--plot", tmp_path / "g.png", "--progress")
    assert code == 0, err
    assert list(dict.fromkeys(label for label, _ in _bar_states(err))) == [
        "generator", "csv", "plot"]


def test_no_bar_when_not_asked_and_not_a_terminal(tmp_path, capsys):
    code, _, err = run(capsys, "analyze", "--stage", "harmonic:wn=100", "--Ts", "1e-3",
                       "--wn", "100", "--points", "50", "--out", tmp_path)
    assert code == 0 and err == ""


def test_phased_progress_is_monotone_and_weighted_by_the_model():
    stream = io.StringIO()
    bar = Progress.phased(cli_cost.Cost("job", {"a": 1.0, "b": 3.0}), True, stream)
    bar.phase("a", 10)
    bar.advance(10)
    assert bar.fraction == pytest.approx(0.25)
    bar.phase("b", 4)
    bar.advance(2)
    assert bar.fraction == pytest.approx(0.25 + 0.75 / 2)
    bar.advance(100)                          # never beyond its phase
    assert bar.fraction == pytest.approx(1.0)
    bar.finish()
    assert stream.getvalue().endswith("100.0%\n")


# -- the evaluation behind analyze -------------------------------------------------------------

def test_chain_response_of_a_long_fir_equals_the_direct_sum():
    """The blocked sum is the same sum as sum h[n] z^-n; on the unit circle the rounding of
    either is at most about L eps sum|h| (L = 2e5 taps: 4e-11 sum|h|)."""
    stage = sms.harmonic(T=20.0)
    h = impulse_response(stage, Ts=1e-4)
    w = np.linspace(0.01, 20.0, 37)
    got = analysis.ChainResponse(stage, Ts=1e-4)(1j * w)
    n = np.arange(h.size)
    want = np.array([np.sum(h * np.exp(-1j * wk * 1e-4 * n)) for wk in w])
    assert np.max(np.abs(got - want)) <= 2e5 * 2.2e-16 * np.sum(np.abs(h))


def test_chain_response_reports_its_work_and_is_reused_by_the_analysis_functions():
    seen = []
    resp = analysis.ChainResponse([sms.harmonic(T=1.0)], Ts=1e-3, progress=seen.append)
    ratio = np.linspace(0.5, 2.0, 600)
    assert np.array_equal(analysis.prv_curve(resp, wn_hat=10.0, ratio=ratio),
                          analysis.prv_curve([sms.harmonic(T=1.0)], wn_hat=10.0, ratio=ratio,
                                             Ts=1e-3))
    assert sum(seen) == 600 * resp.taps and len(seen) == 3         # blocks of 256 points
    with pytest.raises(sms.ParameterError) as e:
        analysis.prv(resp, wn=10.0, Ts=2e-3)
    assert e.value.parameter == "Ts"


# -- records, report, validate ------------------------------------------------------------------

EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[2] / "examples"


def test_identify_calibrate_report_validate_estimates_do_not_run(tmp_path, capsys):
    for argv, head in (
            (["identify", EXAMPLES / "decay.csv"], "identify: a record of"),
            (["calibrate", EXAMPLES / "resonance_xy.csv", "--out", tmp_path / "c"],
             "calibrate: 1 file(s)"),
            (["report", "--out", tmp_path / "r"], "report: all sections"),
            (["validate", "--out", tmp_path / "v"], "validate: the FMUs to build first")):
        code, out, err = run(capsys, *argv, "--estimate")
        assert code == 0 and out.startswith(head) and "about" in out, (argv, out, err)
    assert not any(tmp_path.iterdir())                          # nothing ran
    # validate without a build costs the CMake build on top
    assert (cli_cost.validate_cost(built=False).seconds
            > cli_cost.validate_cost(built=True).seconds + 30)


def test_a_huge_record_is_refused_naming_the_file():
    # reading is the part that grows without bound (a long decay's fit costs at most a
    # fixed amount): 20 GB of records
    cost = cli_cost.record_cost("identify", nbytes=2 * 10**10)
    with pytest.raises(cli.CliError, match=r"^FILE: identify would take .*2e\+04 MB of records\); use a shorter"):
        cli_cost.announce(cost)


def test_calibrate_and_report_progress_cover_their_phases(tmp_path, capsys):
    code, _, err = run(capsys, "calibrate", EXAMPLES / "resonance_xy.csv", "--axis", "x",
                       "--progress")
    assert code == 0, err
    states = _bar_states(err)
    assert list(dict.fromkeys(label for label, _ in states)) == ["read and fit", "tune"]
    assert [p for _, p in states] == sorted(p for _, p in states) and states[-1][1] == 100.0
    code, out, err = run(capsys, "report", "--only", "seed004", "shapers", "--out", tmp_path,
                         "--progress")
    assert code == 0, err
    states = _bar_states(err)
    assert list(dict.fromkeys(label for label, _ in states)) == ["seed004", "shapers"]
    assert states[-1][1] == 100.0 and err.endswith("100.0%\n")


# -- the scales of the figures ---------------------------------------------------------------

def test_percent_scales_keep_1_5_20_100_apart():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from smoothshaper._plotting import PRV_CONTOURS, percent_axis, prv_map
    fig, (a, b, c) = plt.subplots(1, 3)
    percent_axis(a, top=110.0)
    ticks = list(a.get_yticks())
    assert {1, 5, 20, 100} <= set(ticks) and a.get_yscale() == "symlog"
    # on the axis, 1 %, 5 %, 20 % and 100 % are at least a tenth of the height apart
    pos = [a.transLimits.transform(a.transScale.transform((0, v)))[1] for v in (1, 5, 20, 100)]
    assert min(b - a_ for a_, b in zip(pos, pos[1:])) > 0.1
    percent_axis(b, top=1e20)
    assert 3 <= len(b.get_yticks()) <= 9
    x, y = np.linspace(0.5, 2, 30), np.linspace(0, 0.3, 20)
    cs = prv_map(c, x, y, 150 * np.abs(np.subtract.outer(y, x - 1)) * 3)
    assert {1, 5, 20, 100} <= set(cs.levels) and len(c.collections or c.get_children()) > 0
    assert set(PRV_CONTOURS) == {1, 5, 20, 100}
    plt.close(fig)


def test_every_report_section_has_a_cost():
    """smoothshaper report models every section before it starts: a section without a
    measured time stopped the whole command with a KeyError before it wrote anything."""
    from smoothshaper.cli.cost import REPORT_SECONDS, report_cost
    from smoothshaper.report import SECTIONS
    assert set(REPORT_SECONDS) == set(SECTIONS)
    assert report_cost(list(SECTIONS)).seconds == pytest.approx(sum(REPORT_SECONDS.values()))
