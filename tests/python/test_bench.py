# SPDX-License-Identifier: Apache-2.0
"""The benchmark command runs end to end (a smoke test: --quick, no timing is asserted) and
writes every table the docs quote."""
import shutil

import pytest

from smoothshaper import bench
from smoothshaper.bench import suite
from fmu_builds import fmu_build_dir


@pytest.mark.skipif(suite._compiler() is None, reason="needs a C compiler")
def test_quick_run_writes_every_table(tmp_path, capsys):
    out = tmp_path / "benchmarks.md"
    args = ["--quick", "--output", str(out), "--fmu-build-dir", str(fmu_build_dir())]
    if shutil.which("cmake") is None:
        args.append("--no-fmu")
    assert bench.main(args) == 0
    text = out.read_text()
    for title in ("C per-sample cost against the plain realisation",
                  "C one call per sample (step) against the plain form called the same way",
                  "C per-sample cost of stages that follow the machine, next to the fixed stage",
                  "C trajectory paths",
                  "Python call floor", "Python throughput", "Python peak memory",
                  "Design cost of a chain", "Kinematic design against ruckig",
                  "Multi-axis duration against ruckig"):
        assert f"## {title}" in text
    multi = text.split("## Multi-axis duration against ruckig")[1].split("\n## ")[0]
    assert multi.count("| yes |") == 2, multi      # the same durations as ruckig
    for path in ("rectangular", "harmonic", "damped harmonic", "exponential", "notch",
                 "ZV shaper", "generator step", "vmax reached", "oaconvolve",
                 "ZVD shaper, retunable", "rectangular, retunable", "ZVD shaper, scheduled"):
        assert f"| {path}" in text
    assert "| n/a" not in text.split("## Python call floor")[0]   # every C figure measured
    if shutil.which("cmake") is not None:   # the state load, from the raw C host
        load = text.split("## FMU state load (DeSerializeFMUstate)")[1].split("\n## ")[0]
        row = [r for r in load.splitlines() if r.startswith("| SmoothShaper")]
        assert len(row) == 1 and "n/a" not in row[0], load
    printed = capsys.readouterr().out
    assert "wrote" in printed


def test_hand_written_part_is_kept(tmp_path):
    out = tmp_path / "benchmarks.md"
    assert suite._hand_written(out) == ""                 # no file yet
    out.write_text("# Benchmarks\n\n## old table\n\n" + suite.HAND_WRITTEN
                   + "\n\n## By hand\n\ntext\n")
    assert suite._hand_written(out) == suite.HAND_WRITTEN + "\n\n## By hand\n\ntext\n"
    out.write_text("# Benchmarks\n\n## old table\n")   # no marker: nothing is kept
    assert suite._hand_written(out) == ""
