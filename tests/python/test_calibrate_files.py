# SPDX-License-Identifier: Apache-2.0
"""Several files of one axis (Klipper's ``calibrate_shaper.py FILE1 FILE2 ...``: a resonance
test at several points of the bed) analysed as one axis with one data set each, every filter
scored by the worst data set, as the established tool's ``fit_shaper`` scores them.

The records are built here: two Klipper PSD tables of the x axis where the pick on the sum of
the two points differs from the pick on the worst point; tables on different frequency grids;
a raw accelerometer record with a table."""
from __future__ import annotations

import numpy as np
import pytest

from smoothshaper import calibrate
from smoothshaper.calibrate import load
from smoothshaper.calibrate.records import RecordError

import calibrate_checks
import klipper_pick

#: By the established estimate, the pick may leave at most this much more [percentage points]
#: than the established pick on the worst data set (the acceptance bar of a firmware run).
VIBRATION_PP = calibrate_checks.VIBRATION_PP


def _mode(f, fn, z, w):
    """A base-excited mode's PSD under the test's excitation growing with the frequency."""
    r = f / fn
    return w * f * (1 + 4 * z * z * r * r) / ((1 - r * r) ** 2 + (2 * z * r) ** 2)


def _table(path, P, f):
    """A Klipper PSD table (``freq,psd_x,psd_y,psd_z,psd_xyz``) whose x+y+z sum is ``P``."""
    path.write_text("freq,psd_x,psd_y,psd_z,psd_xyz\n" + "".join(
        f"{a:.4f},{0.6 * b:.5e},{0.3 * b:.5e},{0.1 * b:.5e},{b:.5e}\n" for a, b in zip(f, P)))
    return str(path)


def _points(f):
    """Two test points: a strong 42 Hz mode at one, a weak one and a 68 Hz mode at the other
    (summed, the 68 Hz mode sits under a twentieth of the sum's peak)."""
    a = 50.0 + _mode(f, 42.0, 0.05, 1e4)
    b = 50.0 + _mode(f, 42.5, 0.05, 4e2) + _mode(f, 68.0, 0.04, 3e2)
    return a, b



def test_two_tables_of_one_axis_are_scored_by_the_worst(tmp_path):
    """Given as two files, the two points are one axis of two data sets: the default budget is
    the established tool's pick on both files (where the sum's pick leaves more than 0.1 point
    over it on the worst point), every Klipper shaper's figure is the established estimate over
    both files, and the pick is within 0.1 point of the established pick."""
    f = np.arange(0.0, 200.0, 1.0)
    a, b = _points(f)
    p1 = _table(tmp_path / "resonances_x_p1.csv", a, f)
    p2 = _table(tmp_path / "resonances_x_p2.csv", b, f)
    data = klipper_pick.load(p1) + klipper_pick.load(p2)
    pick = klipper_pick.best_shaper(data)
    summed = klipper_pick.best_shaper([klipper_pick.Dataset(f, data[0].psd + data[1].psd)])
    assert 100 * klipper_pick.remaining(summed["A"], summed["T"], data) > \
        100 * pick["vibrs"] + VIBRATION_PP
    cal = calibrate.run([p1, p2], firmware="klipper")   # combined by default: both name x
    assert len(cal.axes) == 1
    res = cal.axes[0]
    assert res.name == "x" and res.datasets == (0, 1)
    assert res.record.names == ["resonances_x_p1.csv", "resonances_x_p2.csv"]
    calibrate_checks.assert_held_to_pick(res, cal.reference.Ts, data, pick)


def test_when_files_are_combined(tmp_path):
    """By default files combine when each is a resonance test named for the same axis (as a
    Klipper user gives them); ``combine=True`` combines any resonance tests, ``False`` none."""
    f = np.arange(0.0, 200.0, 1.0)
    a, b = _points(f)
    x1 = load(_table(tmp_path / "resonances_x_p1.csv", a, f))
    x2 = load(_table(tmp_path / "resonances_x_p2.csv", b, f))
    y = load(_table(tmp_path / "resonances_y_p1.csv", b, f))
    anon = load(_table(tmp_path / "bed_point.csv", b, f))
    assert calibrate._combines([x1, x2], None)
    assert not calibrate._combines([x1, x2], False)
    assert not calibrate._combines([x1, y], None)       # two axes: each on its own
    assert not calibrate._combines([x1, anon], None)    # the file name does not tell
    assert calibrate._combines([x1, anon], True)
    assert not calibrate._combines([x1], True)
    with pytest.raises(ValueError, match=r"^combine"):
        calibrate.run([str(x1.path)], combine="yes")


def test_grids_are_interpolated_onto_the_first_files(tmp_path):
    """A table of 1.5625 Hz bins with one of 1 Hz bins: the data sets are on the first file's
    grid over the frequencies both cover, the second linearly interpolated (exact on a line),
    and the note names the interpolated file."""
    f1 = np.arange(0.0, 200.0, 1.0)
    f2 = np.arange(0.0, 180.0, 1.5625)
    p1 = _table(tmp_path / "resonances_x_p1.csv", 100.0 + 2.0 * f1, f1)
    p2 = _table(tmp_path / "resonances_x_p2.csv", 300.0 - f2, f2)
    rec = calibrate._combine([load(p1), load(p2)], "auto")
    assert rec.kind == "psd" and rec.signals.shape[1] == 2
    assert rec.f[0] == 0.0 and rec.f[-1] <= f2[-1] and rec.f[-1] > f2[-1] - 1.0
    np.testing.assert_allclose(rec.signals[:, 0], 100.0 + 2.0 * rec.f, rtol=1e-5)
    np.testing.assert_allclose(rec.signals[:, 1], 300.0 - rec.f, rtol=1e-5)
    assert any(n.startswith(p2) and "interpolated" in n for n in rec.notes)


def test_grids_that_barely_overlap_are_refused_naming_the_file(tmp_path, capsys):
    f1 = np.arange(0.0, 200.0, 1.0)
    f2 = np.arange(0.0, 60.0, 1.0)
    a, b = _points(f1)
    p1 = _table(tmp_path / "resonances_x_p1.csv", a, f1)
    p2 = _table(tmp_path / "resonances_x_p2.csv", b[:f2.size], f2)
    with pytest.raises(RecordError, match="overlap") as exc:
        calibrate.run([p1, p2])
    assert str(exc.value).startswith(p2)
    assert exc.value.path == p2
    # on their own they are read (the refusal is of the combination, not of the file)
    assert calibrate._combines([load(p1), load(p2)], False) is False


def test_a_calibration_table_with_a_resonance_test_is_refused(tmp_path):
    """A table already divided by the frequency (``shapers:`` marker) and an unprocessed one
    score different spectra: refused, naming the odd file."""
    f = np.arange(0.0, 200.0, 1.0)
    a, b = _points(f)
    p1 = _table(tmp_path / "resonances_x_p1.csv", a, f)
    p2 = tmp_path / "calibration_data_x_p2.csv"
    p2.write_text("freq,x,shapers:,zv\n" + "".join(f"{x:.1f},{v:.5e},,1.0\n"
                                                   for x, v in zip(f, b / (f + 0.1))))
    with pytest.raises(RecordError, match="shapers:") as exc:
        calibrate.run([p1, str(p2)], combine=True)
    assert exc.value.path == str(p2)


def test_a_raw_record_combines_with_a_table(tmp_path):
    """A raw record (white base noise through a 42 Hz mode, 8 s at 800 Hz) with a table: the
    raw record's data set is its x+y+z PSD at the established tool's resolution (0.5 s
    segments, the density Klipper computes from the file), the table is on its grid, and the
    default budget is the established tool's pick on both files."""
    rng = np.random.default_rng(4)
    fs, n = 800.0, 6400
    t = np.arange(n) / fs
    from scipy import signal
    wn, z = 2 * np.pi * 42.0, 0.05
    sys = signal.cont2discrete(([wn * wn], [1.0, 2 * z * wn, wn * wn]), 1 / fs)
    x = signal.lfilter(np.ravel(sys[0]), np.ravel(sys[1]), rng.standard_normal(n))
    raw = tmp_path / "raw_data_x_p1.csv"
    raw.write_text("#time,accel_x,accel_y,accel_z\n" + "".join(
        f"{a:.6f},{p:.5f},{0.2 * p:.5f},{0.05 * p:.5f}\n" for a, p in zip(t, x)))
    f = np.arange(0.0, 200.0, 1.0)
    a, b = _points(f)
    table = _table(tmp_path / "resonances_x_p2.csv", b, f)
    rec = calibrate._combine([load(str(raw)), load(table)], "auto")
    ref = klipper_pick.raw_psd(np.loadtxt(raw, comments="#", delimiter=","))
    # the same bins: Klipper's sample rate is N / span, ours 1 / median step (N / (N - 1) apart)
    assert rec.f[1] - rec.f[0] == pytest.approx(ref[0][1] - ref[0][0], rel=2.0 / n)
    # the raw data set at the established tool's bins (its own PSD, to the Welch estimator's
    # window difference: a Hann window here, a Kaiser there, about 20 % on a bin)
    peak = int(np.argmax(rec.signals[:, 0]))
    assert rec.f[peak] == pytest.approx(42.0, abs=2.0)
    kp = int(np.argmax(ref[1]))
    assert ref[0][kp] == pytest.approx(rec.f[peak], abs=2.0)
    assert rec.signals[peak, 0] == pytest.approx(ref[1][kp], rel=0.3)
    np.testing.assert_allclose(rec.signals[:, 1], np.interp(rec.f, f, b), rtol=1e-5)
    assert calibrate._combines([load(str(raw)), load(table)], None)
    # scored as one axis: the default budget is the established tool's pick on both files
    pick = klipper_pick.best_shaper(klipper_pick.load(raw) + klipper_pick.load(table))
    res = calibrate.run([str(raw), table], firmware="klipper").axes[0]
    assert res.datasets == (0, 1)
    assert res.default_limit.shaper == f"klipper {pick['name']}"
    assert res.default_limit.freq == pytest.approx(pick["freq"], abs=0.1)


def test_cli_combine_and_separate(tmp_path, capsys):
    """``--combine`` / ``--separate`` reach ``run`` (default: None, decided from the files); a
    refused combination is one line on stderr naming the file."""
    from smoothshaper.cli import build_parser, main
    from smoothshaper.cli.common import CliError
    parser = build_parser()
    assert parser.parse_args(["calibrate", "a.csv", "b.csv"]).combine is None
    assert parser.parse_args(["calibrate", "a.csv", "b.csv", "--combine"]).combine is True
    assert parser.parse_args(["calibrate", "a.csv", "b.csv", "--separate"]).combine is False
    with pytest.raises(CliError, match="not allowed with"):
        parser.parse_args(["calibrate", "a.csv", "--combine", "--separate"])
    capsys.readouterr()
    f1, f2 = np.arange(0.0, 200.0, 1.0), np.arange(0.0, 60.0, 1.0)
    a, b = _points(f1)
    p1 = _table(tmp_path / "resonances_x_p1.csv", a, f1)
    p2 = _table(tmp_path / "resonances_x_p2.csv", b[:f2.size], f2)
    code = main(["calibrate", p1, p2, "--no-progress"])
    err = capsys.readouterr().err
    assert code == 1 and err.count("\n") == 1 and "Traceback" not in err
    assert f"{p2}: its frequencies" in err, err
