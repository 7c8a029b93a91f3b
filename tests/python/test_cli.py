# SPDX-License-Identifier: Apache-2.0
"""The smoothshaper command line: tables, plots, identification, errors, lazy subcommands."""
import math
import os
import subprocess
import sys
import types

import numpy as np
import pytest

from smoothshaper import cli


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _rows(out):
    """Data rows of the printed table as lists of cells."""
    lines = out.splitlines()
    dash = next(i for i, ln in enumerate(lines) if set(ln.replace(" ", "")) == {"-"})
    rows = []
    for ln in lines[dash + 1:]:
        if not ln.strip() or not ln.split()[0].isdigit():
            break
        rows.append(ln.split())
    return lines[dash - 1].split(), rows


# -- stage specs ----------------------------------------------------------------------------

def test_parse_stage_fields_and_mode_design():
    s = cli.parse_stage("zv:wn=100,zeta=0.05")
    assert (s.kind, s.wn, s.zeta) == ("zv", 100.0, 0.05)
    s = cli.parse_stage("harmonic:T=0.05,timing=paper")
    assert (s.kind, s.T, s.timing) == ("harmonic", 0.05, "paper")
    s = cli.parse_stage("damped_harmonic:wn=125,zeta=0.12")
    wd = 125 * math.sqrt(1 - 0.12**2)
    assert s.T == pytest.approx(3 * math.pi / wd, rel=1e-14)
    assert s.sigma == pytest.approx(-0.12 * 125, rel=1e-14)
    s = cli.parse_stage("notch:wn=200,zeta=0.02,pole_zeta=0.5")
    assert (s.kind, s.notch_pole_zeta) == ("notch_matched", 0.5)
    assert cli.parse_stage("zvn:wn=50,order=4").order == 4


@pytest.mark.parametrize("spec, word", [
    ("bogus:T=1", "kind"), ("harmonic", "T="), ("harmonic:T", "key=value"),
    ("harmonic:T=abc", "T must be a number"), ("zvn:wn=5,order=2.5", "order must be an integer"),
    ("harmonic:T=1,T=2", "twice"), ("harmonic:colour=3", "unknown key"),
    ("harmonic:wn=10,sigma=-1", "cannot be combined"), ("harmonic:T=1,k=2", "k must be odd"),
])
def test_parse_stage_errors(spec, word):
    with pytest.raises(ValueError, match=word):
        cli.parse_stage(spec)


# -- design ---------------------------------------------------------------------------------

def test_design_prints_a_table_for_a_mode(capsys):
    code, out, err = run(capsys, "design", "--kind", "harmonic", "--kind", "damped_harmonic",
                         "--kind", "zvd", "--wn", "100", "--zeta", "0.1", "--Ts", "1e-3")
    assert code == 0 and err == ""
    header, rows = _rows(out)
    assert header[:3] == ["#", "kind", "T"]
    assert [r[1] for r in rows] == ["harmonic", "damped_harmonic", "zvd"]
    wd = 100 * math.sqrt(1 - 0.01)
    assert float(rows[0][2]) == pytest.approx(3 * math.pi / wd, rel=1e-5)
    assert float(rows[1][3]) == pytest.approx(-10.0, rel=1e-5)            # sigma = -zeta wn
    assert float(rows[2][2]) == pytest.approx(2 * math.pi / wd, rel=1e-5)  # ZVD lasts Td
    # Length in samples as the exact-timing contract gives it (docs/exact-mode.md).
    from smoothshaper import reference, stages
    harmonic = stages.harmonic(T=3 * math.pi / wd)
    assert int(rows[0][-1]) == reference.impulse_response(harmonic, Ts=1e-3).size
    assert "total duration" in out and "chain FIR length" in out


def test_design_zvn_order_and_ei_tolerance(capsys):
    code, out, _ = run(capsys, "design", "--kind", "zvn", "--order", "3", "--kind", "ei",
                       "--shaper-tolerance", "0.1", "--wn", "50")
    assert code == 0
    _, rows = _rows(out)
    assert rows[0][1] == "zvn" and rows[0][7] == "3"
    assert float(rows[0][2]) == pytest.approx(3 * math.pi / 50, rel=1e-5)   # 3 half periods
    code, _, err = run(capsys, "design", "--kind", "zvn", "--order", "13", "--wn", "50")
    assert code == cli.EXIT_ERROR and err.startswith("smoothshaper: error: --order=13: order")


def test_design_from_stage_specs(capsys):
    code, out, _ = run(capsys, "design", "--stage", "rectangular:T=0.02",
                       "--stage", "ei:wn=80,zeta=0.02")
    assert code == 0
    _, rows = _rows(out)
    assert [r[1] for r in rows] == ["rectangular", "ei"]


def test_design_writes_precomputed_coefficients(capsys, tmp_path):
    path = tmp_path / "axis.c"
    code, out, err = run(capsys, "design", "--stage", "harmonic:wn=100",
                         "--stage", "zv:wn=100,zeta=0.05", "--Ts", "1e-3",
                         "--c-coeffs", str(path), "--c-name", "axis_y")
    assert code == 0 and err == ""
    assert f"wrote {path}" in out
    text = path.read_text()
    assert text.startswith("/* Written by: smoothshaper design ")
    assert "const sms_stage_coeffs axis_y[2]" in text and "const size_t axis_y_stages = 2u;" in text
    code, _, err = run(capsys, "design", "--stage", "zv:wn=100", "--c-coeffs", str(path))
    assert code == cli.EXIT_ERROR and "--c-coeffs needs --Ts" in err
    code, _, err = run(capsys, "design", "--stage", "zv:wn=100", "--Ts", "1e-3",
                       "--c-coeffs", str(path), "--c-name", "9lives")
    assert code == cli.EXIT_ERROR and "name must be a C identifier" in err


def test_design_kinematic_limits(capsys):
    from smoothshaper import design  # noqa: F401 - fails loudly if the module is missing
    code, out, err = run(capsys, "design", "--h", "40", "--vmax", "250", "--amax", "5000",
                         "--jmax", "200000")
    assert code == 0, err
    _, rows = _rows(out)
    durations = [float(r[2]) for r in rows]
    assert durations == pytest.approx([0.16, 0.05, 0.025], rel=1e-6)     # 2011a paper values
    assert "0.235" in out


# -- analyze --------------------------------------------------------------------------------

def test_analyze_writes_pngs_and_a_summary(tmp_path, capsys):
    out_dir = tmp_path / "plots"
    code, out, err = run(capsys, "analyze", "--stage", "harmonic:wn=100", "--stage",
                         "zv:wn=100,zeta=0.05", "--Ts", "1e-3", "--out", str(out_dir),
                         "--points", "200", "--surface", "--surface-points", "8", "--progress")
    assert code == 0, err
    for name in ("prv.png", "spectrum.png", "step.png", "prv_surface.png"):
        data = (out_dir / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000, name
    assert "100.0%" in err                                     # the progress bar ran to the end
    prv_line = next(ln for ln in out.splitlines() if ln.startswith("PRV at the nominal mode"))
    # Both stages put a zero exactly on the sampled mode: PRV is rounding noise.
    assert float(prv_line.split(":")[1].split()[0]) < 1e-9
    assert "step response: final value 1" in out


def test_analyze_needs_a_mode(tmp_path, capsys):
    code, _, err = run(capsys, "analyze", "--stage", "rectangular:T=0.02", "--out",
                       str(tmp_path))
    assert code == cli.EXIT_ERROR and "--wn" in err and err.count("\n") == 1


# -- identify -------------------------------------------------------------------------------

def _decay_csv(path, wn=60.0, zeta=0.03, Ts=2e-3, n=1500, header=True, noise=0.0, offset=0.0):
    t = np.arange(n) * Ts
    wd = wn * math.sqrt(1 - zeta**2)
    x = 1.3 * np.exp(-zeta * wn * t) * np.cos(wd * t - 0.4)
    x += offset + noise * np.random.default_rng(0).normal(size=n)
    with open(path, "w") as f:
        if header:
            f.write("time,position\n")
        for ti, xi in zip(t, x):
            f.write(f"{ti:.9f},{xi:.17g}\n")


def _mode_from(out):
    """(wn, zeta, wd, sigma, Td): the value row under identify's header and dashes."""
    lines = out.splitlines()
    dash = next(i for i, ln in enumerate(lines) if set(ln.replace(" ", "")) == {"-"})
    return [float(v) for v in lines[dash + 1].split()]


def test_identify_recovers_the_mode_from_a_csv(tmp_path, capsys):
    path = tmp_path / "decay.csv"
    _decay_csv(path, offset=5.0)                 # settling at 5: the fit absorbs the offset
    code, out, err = run(capsys, "identify", str(path))
    assert code == 0, err
    wn, zeta = _mode_from(out)[:2]
    assert wn == pytest.approx(60.0, rel=1e-6)
    assert zeta == pytest.approx(0.03, rel=1e-5)
    assert "damped_harmonic:wn=" in out


@pytest.mark.parametrize("offset", [0.0, 5.0])
def test_identify_from_two_peaks(tmp_path, capsys, offset):
    path = tmp_path / "decay.csv"
    _decay_csv(path, offset=offset)              # peaks are measured about the final value
    code, out, err = run(capsys, "identify", str(path), "--method", "peaks")
    assert code == 0, err
    wn, zeta = _mode_from(out)[:2]
    # Parabolic peak refinement at ~52 samples per period: timing error O((wd Ts)^2) ~ 1e-4.
    assert wn == pytest.approx(60.0, rel=1e-3)
    assert zeta == pytest.approx(0.03, rel=2e-2)


def test_identify_single_column_with_Ts_and_noise(tmp_path, capsys):
    path = tmp_path / "decay.txt"
    _decay_csv(path, header=False, noise=1e-3)
    data = np.loadtxt(path, delimiter=",")[:, 1]
    np.savetxt(path, data)
    code, out, err = run(capsys, "identify", str(path), "--Ts", "2e-3")
    assert code == 0, err
    wn, zeta = _mode_from(out)[:2]
    # 0.1 % noise on a unit decay: the least-squares fit keeps wn within 0.1 %, zeta within 5 %.
    assert wn == pytest.approx(60.0, rel=1e-3)
    assert zeta == pytest.approx(0.03, rel=5e-2)


@pytest.mark.parametrize("content, args, word", [
    (None, [], "cannot read"),
    ("t,x\n0,1\n0.1,abc\n", [], "non-numeric"),
    ("1\n2\n3\n", [], "--Ts"),
    ("t,x\n0,1\n0.1,0.5\n0.05,0.2\n", [], "increase"),
    ("t,x\n0,1\n0.1,0.5\n", ["--column", "y"], "no column"),
    ("t,x\n" + "".join(f"{i * 1e-3},1.0\n" for i in range(50)), [], "record"),
])
def test_identify_errors_are_one_line(tmp_path, capsys, content, args, word):
    path = tmp_path / "bad.csv"
    if content is not None:
        path.write_text(content)
    code, out, err = run(capsys, "identify", str(path), *args)
    assert code == cli.EXIT_ERROR
    assert word in err and err.count("\n") == 1 and "Traceback" not in err


# -- errors and lazy subcommands ------------------------------------------------------------

@pytest.mark.parametrize("argv, word", [
    (["design", "--stage", "zv:wn=5000", "--Ts", "1e-3"], "wn"),
    (["design", "--kind", "harmonic", "--wn", "100", "--k", "2"], "k"),
    (["design", "--kind", "zv"], "--wn"),
    (["design", "--wn", "abc"], "invalid float"),
    (["design"], "nothing to design"),
    (["analyze", "--stage", "zv:wn=100", "--Ts", "-1"], "Ts"),
    (["frobnicate"], "invalid choice"),
    ([], "required"),
])
def test_errors_are_one_line_with_nonzero_exit(capsys, argv, word):
    code, out, err = run(capsys, *argv)
    assert code != 0
    assert word in err and err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize("command, module", [("validate", "fmi"), ("report", "report")])
def test_lazy_subcommand_unavailable(monkeypatch, capsys, command, module):
    monkeypatch.setitem(sys.modules, f"smoothshaper.{module}", None)   # import fails
    code, _, err = run(capsys, command, "--out", "x")
    assert code == cli.EXIT_UNAVAILABLE
    assert "unavailable" in err and err.count("\n") == 1


@pytest.mark.parametrize("command, module", [("validate", "fmi"), ("report", "report")])
def test_lazy_subcommand_calls_run(monkeypatch, capsys, tmp_path, command, module):
    calls = []
    fake = types.ModuleType(f"smoothshaper.{module}")
    fake.run = lambda out_dir: calls.append(out_dir)
    monkeypatch.setitem(sys.modules, f"smoothshaper.{module}", fake)
    code, out, _ = run(capsys, command, "--out", str(tmp_path / "o"))
    assert code == 0 and calls == [str(tmp_path / "o")]
    fake.run = lambda out_dir: 4                               # a failing run is an error exit
    assert cli.main([command, "--out", "o"]) == cli.EXIT_ERROR


def test_python_dash_m_runs_the_cli_without_traceback():
    env = dict(os.environ)
    ok = subprocess.run([sys.executable, "-m", "smoothshaper", "design", "--kind", "zv",
                         "--wn", "10"], capture_output=True, text=True, env=env, timeout=60)
    assert ok.returncode == 0 and "zv" in ok.stdout
    bad = subprocess.run([sys.executable, "-m", "smoothshaper", "design", "--stage",
                          "zv:wn=-3"], capture_output=True, text=True, env=env, timeout=60)
    assert bad.returncode == cli.EXIT_ERROR
    assert bad.stderr.count("\n") == 1
    assert bad.stderr.startswith("smoothshaper: error: --stage zv:wn=-3: wn")


def test_console_script_is_declared():
    from importlib.metadata import entry_points
    scripts = {ep.name: ep.value for ep in entry_points(group="console_scripts")}
    assert scripts.get("smoothshaper") == "smoothshaper.cli:main"
