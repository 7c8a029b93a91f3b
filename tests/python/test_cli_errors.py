# SPDX-License-Identifier: Apache-2.0
"""Every CLI error names the argument the user gave that causes it, with readable numbers,
at once: each subcommand run with extreme, NaN, negative and huge values of each numeric
option (and of a via-point) either succeeds or fails with one line on stderr that names that
option (a via-point with its index, a stage by its spec), holds no number of 10 or more
digits, and comes back within a few seconds (sizes are refused from closed forms, before any
work)."""
import re
import time
from pathlib import Path

import pytest

from smoothshaper import cli

# Refused before any arithmetic on the bad value: an overflow or NaN warning means a value got
# into the computation first.
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
VALUES = ["1e300", "-1e300", "-1", "0", "nan", "inf", "1e-300", "1e20", "1e-20", "3"]

# (base argv, options to vary); VIA1 varies the first target of --via, "STAGE:key" a key of
# the --stage spec; --estimate keeps the accepted runs short
CASES = {
    "mode": (["design", "--kind", "zv", "--wn", "100", "--zeta", "0.05", "--Ts", "1e-3"],
             ["--wn", "--zeta", "--Ts", "--k", "--tolerance"]),
    "ei": (["design", "--kind", "ei", "--wn", "100", "--tolerance", "0.05", "--Ts", "1e-3"],
           ["--shaper-tolerance"]),
    "kinematic": (["design", "--h", "0.1", "--vmax", "1", "--amax", "10", "--jmax", "100",
                   "--Ts", "1e-3"], ["--h", "--vmax", "--amax", "--jmax", "--Ts"]),
    "generator": (["design", "generator", "--via=0,1,0.5", "--vmax", "1", "--amax", "10",
                   "--jmax", "100", "--Ts", "1e-3", "--estimate"],
                  ["--vmax", "--amax", "--jmax", "--Ts", "--hold", "VIA1"]),
    "damped": (["design", "generator", "--via=0,1,0.5", "--vmax", "1", "--amax", "10",
                "--jmax", "100", "--Ts", "1e-3", "--profile", "damped", "--wn", "50",
                "--estimate"], ["--wn", "--zeta"]),
    "multi-axis": (["design", "generator", "--via=0,0;1,2;0.5,1", "--vmax", "1,2", "--amax",
                    "10,10", "--jmax", "100,100", "--Ts", "1e-3", "--estimate"],
                   ["--vmax", "--amax", "--jmax", "--Ts", "--hold", "VIA1"]),
    "bspline": (["design", "bspline", "--via=0;1;0.5", "--T", "0.05", "--Ts", "1e-3",
                 "--estimate"], ["--T", "--Ts", "--degree", "VIA1"]),
    "bspline-wn": (["design", "bspline", "--via=0;1;0.5", "--wn", "60", "--Ts", "1e-3",
                    "--estimate"], ["--wn"]),
    "analyze": (["analyze", "--kind", "zv", "--wn", "100", "--Ts", "1e-3", "--out", "never",
                 "--estimate"], ["--wn", "--Ts", "--ratio-max", "--points", "--zeta"]),
    "identify": (["identify", str(EXAMPLES / "decay.csv"), "--no-progress"], ["--Ts", "--start"]),
    "calibrate": (["calibrate", str(EXAMPLES / "resonance_psd.csv"), "--estimate"],
                  ["--accel", "--corner-velocity", "--distance", "--spread", "--Ts",
                   "--max-delay"]),
    "stage": (["design", "--stage", "harmonic:T=0.05", "--Ts", "1e-3"],
              ["STAGE:T", "STAGE:wn", "STAGE:sigma"]),
}


def vary(argv, option, value):
    """argv with option set to value; the name the error must show."""
    argv = list(argv)
    if option == "VIA1":
        i = next(k for k, a in enumerate(argv) if a.startswith("--via="))
        sep = ";" if ";" in argv[i] and "," not in argv[i] else ","
        points = argv[i][6:].split(";") if ";" in argv[i] and sep == "," else None
        if points:      # multi-axis: the last coordinate of the first target
            first = points[1].split(",")
            first[-1] = value
            points[1] = ",".join(first)
            argv[i] = "--via=" + ";".join(points)
        else:
            parts = argv[i][6:].split(sep)
            parts[1] = value
            argv[i] = "--via=" + sep.join(parts)
        return argv, "--via"
    if option.startswith("STAGE:"):
        key = option[6:]
        spec = {"T": f"harmonic:T={value}", "wn": f"harmonic:wn={value}",
                "sigma": f"exponential:T=0.05,sigma={value}"}[key]
        argv[argv.index("--stage") + 1] = spec
        return argv, f"--stage {spec}"
    if option in argv:
        i = argv.index(option) + 1
        argv[i] = argv[i].rsplit(",", 1)[0] + "," + value if "," in argv[i] else value
    else:
        argv.append(f"{option}={value}")
    return argv, option


@pytest.mark.parametrize("case", sorted(CASES))
def test_every_error_names_the_option_readably_and_at_once(case, capsys, tmp_path,
                                                          monkeypatch):
    monkeypatch.chdir(tmp_path)
    base, options = CASES[case]
    failures = []
    for option in options:
        for value in VALUES:
            argv, name = vary(base, option, value)
            start = time.process_time()
            code = cli.main(argv)
            seconds = time.process_time() - start
            _, err = capsys.readouterr()
            why = []
            if code not in (0, cli.EXIT_ERROR, cli.EXIT_USAGE):
                why.append(f"exit {code}")
            if code != 0 and (err.count("\n") != 1 or name not in err):
                why.append("does not name it on one line")
            if re.search(r"\d{10}", err):
                why.append("a number of 10 or more digits")
            if seconds > 5:
                why.append(f"{seconds:.1f} s")
            if why:
                failures.append(f"{' '.join(argv)}: {', '.join(why)}: {err.strip()}")
    assert not failures, "\n".join(failures)


def test_a_far_via_point_is_named_with_its_index(capsys):
    """A via-point 1e300 away: the error names that point (not --Ts, the old message with a
    300-digit sample count), the run's length in seconds and samples as %.3g."""
    code = cli.main(["design", "generator", "--via=0,1,1e300", "--vmax", "1", "--amax", "10",
                     "--jmax", "100", "--Ts", "1e-3"])
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR
    assert err.startswith("smoothshaper: error: --via point 2 (1e+300): the run would take "
                          "about 1e+300 s = 1e+303 samples of Ts = 0.001 s"), err
    code = cli.main(["design", "generator", "--via=0,0;1,1;2,-1e300", "--vmax", "1,1",
                     "--amax", "10", "--jmax", "100", "--Ts", "1e-3"])
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and "--via point 2 (2,-1e+300)" in err, err


def test_a_plausible_run_at_an_extreme_sample_period_names_ts(capsys):
    """The run would fit at Ts = 1 ms: the sample period is what is extreme."""
    code = cli.main(["design", "generator", "--via=0,1,2", "--vmax", "1", "--amax", "10",
                     "--jmax", "100", "--Ts", "1e-9"])
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and err.startswith("smoothshaper: error: --Ts=1e-09:"), err


def test_library_errors_name_the_option_and_the_axis(capsys):
    code = cli.main(["design", "generator", "--via=0,0;1,2", "--vmax", "1,1", "--amax",
                     "1,1e-30", "--jmax", "1,1e-300", "--Ts", "1e-3"])
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and "--jmax=1,1e-300 (axis 1)" in err, err
    code = cli.main(["design", "--kind", "zv", "--wn", "100", "--zeta", "3"])
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and err.startswith("smoothshaper: error: --zeta=3:"), err


@pytest.mark.parametrize("argv, start", [
    (["analyze", "--kind", "zv", "--wn", "100", "--Ts", "1e-3", "--out", "never", "--points",
      "2000000000"], "--points must be in 2..1000000, got 2e+09"),
    (["analyze", "--kind", "zv", "--wn", "100", "--Ts", "1e-3", "--out", "never", "--surface",
      "--surface-points", "200000"], "--surface-points: analyze would take about"),
    (["design", "bspline", "--via=0;1", "--T", "0.05", "--Ts", "1e-3", "--degree",
      "100000000000"], "--degree must be 1..7, got 1e+11"),
])
def test_counts_are_refused_naming_them_before_any_work(argv, start, capsys):
    """Counts that would allocate gigabytes (--points 2e9 was killed for memory) or run for
    hours are refused at once, naming the count, not --Ts or --T."""
    t = time.process_time()
    code = cli.main(argv)
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and err.startswith("smoothshaper: error: " + start), err
    assert time.process_time() - t < 2


def test_an_output_folder_that_is_a_file_names_out(capsys, tmp_path):
    taken = tmp_path / "taken"
    taken.write_text("")
    for argv in (["analyze", "--kind", "zv", "--wn", "100", "--out", str(taken)],
                 ["analyze", "--kind", "zv", "--wn", "100", "--out", str(taken / "sub")],
                 ["calibrate", str(EXAMPLES / "decay.csv"), "--out", str(taken)]):
        assert cli.main(argv) == cli.EXIT_ERROR
        err = capsys.readouterr().err.strip()
        assert err.startswith(f"smoothshaper: error: --out={argv[-1]}: "), err
        assert "Errno" not in err and "\n" not in err, err


def test_jmax_without_amax_names_both(capsys):
    assert cli.main(["design", "--h", "1", "--vmax", "1", "--jmax", "1"]) == cli.EXIT_ERROR
    err = capsys.readouterr().err
    assert "--jmax needs --amax" in err, err


def _decay_rows():
    lines = (EXAMPLES / "decay.csv").read_text().splitlines()
    return lines[:2], lines[2:]


def _malformed(tmp_path):
    """(file name, text, what the one-line error must contain) of broken data files."""
    head, rows = _decay_rows()
    swapped = rows[:]
    swapped[200], swapped[201] = rows[201], rows[200]          # data row 202 is line 204
    return [
        ("swapped.csv", head + swapped, "row 204, column 0: time 0.2 s does not increase"),
        ("single.csv", head + rows[:1], "a single data row"),
        ("wide_cell.csv", head + rows[:10] + ["0.01," + "1" * 200_000] + rows[11:],
         "row 13: cannot split the line"),
        ("long_header.csv", ["time_s," + "y" * 300_000] + rows, "row 1: cannot split the line"),
        ("huge_values.csv", head + [r.split(",")[0] + ",1e200" for r in rows],
         "row 3, column 1: value 1e+200 is beyond 1e+150"),
        ("long_text.csv", head + rows[:5] + ["0.005," + "x" * 5000] + rows[6:],
         "row 8, column 1: non-numeric value 'xxx"),
        # a NaN or an infinity anywhere reaches the table's min or max: the row is still named
        ("nan_value.csv", head + rows[:3] + [rows[3].split(",")[0] + ",nan"] + rows[4:],
         "row 6, column 1: non-finite value (nan)"),
        ("minus_inf.csv", head + rows[:40] + [rows[40].split(",")[0] + ",-inf"] + rows[41:],
         "row 43, column 1: non-finite value (-inf)"),
        ("huge_negative.csv", head + rows[:9] + [rows[9].split(",")[0] + ",-2e150"] + rows[10:],
         "row 12, column 1: value -2e+150 is beyond 1e+150"),
    ]


@pytest.mark.parametrize("command", [["identify"], ["identify", "--method", "peaks"],
                                     ["calibrate"]])
def test_malformed_data_files_name_the_file_and_row(command, capsys, tmp_path):
    """A field over csv's 131072-character limit raised csv.Error with a traceback; a time
    column that does not increase named no row (identify); values near 1e306 went on to a NaN
    spectrum and 'no resonance'; a text cell was quoted whole in the message."""
    for name, lines, expected in _malformed(tmp_path):
        path = tmp_path / name
        path.write_text("\n".join(lines) + "\n")
        argv = [command[0], str(path), "--no-progress", *command[1:]]
        if command[0] == "calibrate":
            argv += ["--out", str(tmp_path / "out")]
        t = time.process_time()
        code = cli.main(argv)
        err = capsys.readouterr().err
        assert code == cli.EXIT_ERROR, (name, code, err)
        assert f"{path}, {expected}" in err or (expected.startswith("a single")
                                               and f"{path}:" in err), (name, err)
        assert err.count("\n") == 1 and len(err) < 400, (name, err[:500])
        assert time.process_time() - t < 2, name


@pytest.mark.parametrize("argv, start", [
    (["design", "bspline", "--via=0;1", "--T", "0.05", "--Ts", "1e-3", "--degree", "9" * 400],
     "--degree must be 1..7, got inf"),
    (["analyze", "--kind", "zv", "--wn", "100", "--Ts", "1e-3", "--out", "never", "--points",
      "9" * 400], "--points must be in 2..1000000, got inf"),
    (["design", "--stage", "x" * 100_000], "--stage=xxxx"),
])
def test_huge_counts_and_long_arguments_give_one_short_line(argv, start, capsys):
    """A count of 400 digits raised OverflowError from '%.3g' (a traceback); a 100 kB --stage
    was echoed whole, twice, in the error line."""
    code = cli.main(argv)
    err = capsys.readouterr().err
    assert code == cli.EXIT_ERROR and err.startswith("smoothshaper: error: " + start), err[:300]
    assert err.count("\n") == 1 and len(err) <= 700, len(err)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
@pytest.mark.parametrize("command", ["identify", "calibrate"])
def test_a_device_is_refused_not_read_until_memory_runs_out(command, capsys):
    """identify /dev/zero read the endless device into memory (a hang, then the OOM killer)."""
    t = time.process_time()
    assert cli.main([command, "/dev/zero", "--no-progress"]) == cli.EXIT_ERROR
    err = capsys.readouterr().err
    assert err == "smoothshaper: error: /dev/zero: not a file of records but a device\n", err
    assert time.process_time() - t < 2
