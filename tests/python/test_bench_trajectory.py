"""Smoke run of the trajectory benchmark (its figures are not asserted: they are for reading)."""
import pytest

pytest.importorskip("ruckig")


def test_quick_run_prints_every_figure(capsys):
    from smoothshaper import bench_trajectory
    assert bench_trajectory.main(["--quick"]) == 0
    out = capsys.readouterr().out
    for line in ("target changed mid-motion", "rest to rest", "Generator.process, double",
                 "Generator.process, float", "kinematic design", "grid price, 3 bound(s)"):
        assert line in out
