# SPDX-License-Identifier: Apache-2.0
"""`smoothshaper design generator --via "x,y,z;..."`: multi-axis via-points end to end."""
import csv
import math

import numpy as np
import pytest

from smoothshaper import cli
from smoothshaper.trajectory import MultiAxisGenerator, phase_duration

VIA = "0,0,0;100,50,20;100,120,-20;20,80,40;0,0,0"
LIMITS = ["--vmax", "250,200,100", "--amax", "5000,3000,2000", "--jmax", "2e5,1e5,5e4"]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def segment_rows(out):
    lines = out.splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("#  target"))
    rows = []
    for ln in lines[i + 2:]:
        if not ln.strip() or not ln.split()[0].isdigit():
            break
        rows.append(ln.split())
    return rows


def test_three_axes_until_reached(capsys, tmp_path):
    png, path_csv = tmp_path / "m.png", tmp_path / "m.csv"
    code, out, err = run(capsys, "design", "generator", "--via", VIA, *LIMITS, "--Ts", "1e-3",
                         "--plot", png, "--csv", path_csv)
    assert code == 0, err
    assert "every axis within its limits at every sample: yes" in out
    rows = segment_rows(out)
    via = np.array([[float(x) for x in p.split(",")] for p in VIA.split(";")])
    v, a, j = (np.array([float(x) for x in s.split(",")]) for s in LIMITS[1::2])
    assert len(rows) == 4
    for i, r in enumerate(rows):
        T = phase_duration(via[i + 1] - via[i], vmax=v, amax=a, jmax=j)
        # from rest: the time-optimal straight move rounded up to the 1 ms grid
        assert float(r[4]) == pytest.approx(math.ceil(T / 1e-3 - 1e-9) * 1e-3, rel=1e-5)
        assert float(r[5]) == pytest.approx(T, rel=1e-5)
        assert max(float(x) for x in r[6:9]) <= 1 + 1e-9
        assert float(r[9]) <= 1e-12  # straight segments
    assert png.read_bytes()[:8] == PNG_MAGIC
    with open(path_csv) as f:
        data = list(csv.reader(f))
    header = data[0]
    assert header[:4] == ["time", "target_x", "target_y", "target_z"]
    last = dict(zip(header, map(float, data[-1])))
    assert (last["x_q"], last["y_q"], last["z_q"]) == (0.0, 0.0, 0.0)
    # the CSV is the generator's own output
    q = np.array([[float(x) for x in row[4::4]] for row in data[1:]])
    gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=1e-3)
    targets = np.array([[float(x) for x in row[1:4]] for row in data[1:]])
    np.testing.assert_array_equal(gen.process(targets)[:, :, 0], q)


def test_hold_blends_corners_within_limits(capsys, tmp_path):
    code, out, err = run(capsys, "design", "generator", "--via", "0,0;100,50;100,120;20,80;0,0",
                         "--vmax", "250,200", "--amax", "5000,3000", "--jmax", "2e5,1e5",
                         "--Ts", "1e-3", "--hold", "0.3", "--plot", tmp_path / "h.png")
    assert code == 0, err
    assert "not reached before the next point (--hold): segment 1, 2, 3" in out
    rows = segment_rows(out)
    assert rows[-1][3] != "-"
    assert max(float(r[9]) for r in rows) > 0.01  # the blended corners leave the lines
    assert "every axis within its limits at every sample: yes" in out


def test_independent_axes_arrive_separately(capsys):
    code, out, _ = run(capsys, "design", "generator", "--via", "0,0;10,1", "--vmax", "1",
                       "--amax", "10", "--jmax", "100", "--Ts", "1e-3", "--sync", "independent")
    assert code == 0
    assert float(segment_rows(out)[0][9]) > 1e-3  # the short axis arrives first: a bent path


@pytest.mark.parametrize("argv, message", [
    (["--via", "0,0;1"], "same number of coordinates"),
    (["--via", "0,0;1,1", "--vmax", "1,2,3"], "--vmax: give one value or one per axis (2)"),
    (["--via", "0,0;1,1", "--amax", "1,-2"], "--amax: every limit must be > 0"),
    (["--via", "0,0;1,x"], "--via must be comma-separated numbers"),
])
def test_bad_input(capsys, argv, message):
    args = dict(zip(["--vmax", "--amax", "--jmax"], ["1", "1", "1"]))
    for k in range(0, len(argv), 2):
        args[argv[k]] = argv[k + 1]
    flat = [x for kv in args.items() for x in kv]
    code, out, err = run(capsys, "design", "generator", *flat, "--Ts", "1e-3")
    assert code != 0
    assert message in err


def test_position_limits_per_axis(capsys, tmp_path):
    """--qmin/--qmax one per axis: the samples (--csv) equal MultiAxisGenerator with the same
    limits, every q inside; a limit list of the wrong length is refused naming the option."""
    path_csv = tmp_path / "q.csv"
    args = ["design", "generator", "--via", "0,0;0.9,0.1;0.6,0.3", "--vmax", "1,2", "--amax",
            "10,4", "--jmax", "100,50", "--Ts", "1e-3", "--qmin=-0.1,-0.1", "--qmax", "1,0.8"]
    code, out, err = run(capsys, *args, "--csv", path_csv)
    assert code == 0, err
    with open(path_csv) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    g = MultiAxisGenerator(vmax=[1, 2], amax=[10, 4], jmax=[100, 50], Ts=1e-3, q0=[0, 0],
                           qmin=[-0.1, -0.1], qmax=[1, 0.8])
    header = rows[0]
    qx, qy = data[:, header.index("x_q")], data[:, header.index("y_q")]
    assert np.all((qx >= -0.1) & (qx <= 1) & (qy >= -0.1) & (qy <= 0.8))
    first = np.flatnonzero(np.abs(qx - 0.9) + np.abs(qy - 0.1) == 0)[0]
    ref = g.process(np.tile([0.9, 0.1], (first + 1, 1)))
    assert np.array_equal(ref[:, :, 0], np.c_[qx[:first + 1], qy[:first + 1]])
    code, out, err = run(capsys, *args[:-3], "--qmin=-1,-1,-1", "--qmax", "1,1")
    assert code != 0 and "--qmin: give one value or one per axis (2), got 3" in err, err
