# SPDX-License-Identifier: Apache-2.0
"""calibrate.schedule_table and ``smoothshaper calibrate --schedule``: one synthetic free-decay
record per position of a machine whose mode moves along its travel (simulated exactly), the
table of the dominant modes against the true ones (to the fit's resolution), usable by a
ScheduledShaper; refusals naming the option."""
import math

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper.calibrate import schedule as calibrate
from smoothshaper.calibrate import synthetic as syn
from smoothshaper.cli import main

POSITIONS = (0.0, 0.5, 1.0)
TRUE = {p: (2 * math.pi * 25.0 * math.sqrt(1 + p), 0.03) for p in POSITIONS}


@pytest.fixture(scope="module")
def records(tmp_path_factory):
    out = tmp_path_factory.mktemp("schedule")
    paths = []
    for i, p in enumerate(POSITIONS):
        t, x = syn.decay_record([TRUE[p]], snr_db=40.0, seed=i)
        path = out / f"decay_at_{p}.csv"
        syn.write_csv(path, [t, x], ["time", "x"])
        paths.append(str(path))
    return paths


def test_table_has_the_true_modes(records):
    table = calibrate.schedule_table(list(reversed(records)), list(reversed(POSITIONS)),
                                     axis="x", kind="decay")
    assert np.array_equal(table[:, 0], POSITIONS)                  # sorted by value
    for (p, wn, zeta) in table:
        true_wn, true_zeta = TRUE[p]
        assert wn == pytest.approx(true_wn, rel=5e-3)               # the decay fit's accuracy
        assert zeta == pytest.approx(true_zeta, rel=0.1)
    shaper = sms.ScheduledShaper("zv", table, Ts=1e-3)
    assert shaper.mode(0.5)[0] == pytest.approx(table[1, 1], rel=1e-12)


def test_cli_prints_and_writes_the_table(records, tmp_path, capsys):
    assert main(["calibrate", *records, "--kind", "decay", "--axis", "x", "--schedule",
                 ",".join(map(str, POSITIONS)), "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "schedule table" in text and "wrote" in text
    rows = np.loadtxt(tmp_path / "schedule.csv", delimiter=",", skiprows=1)
    assert rows.shape == (3, 3) and np.array_equal(rows[:, 0], POSITIONS)


def test_refusals(records, capsys):
    with pytest.raises(sms.ParameterError) as e:
        calibrate.schedule_table(records, [0.0, 0.5])
    assert e.value.parameter == "values"
    with pytest.raises(sms.ParameterError) as e:
        calibrate.schedule_table(records, [0.0, 0.0, 1.0])
    assert e.value.parameter == "values"
    assert main(["calibrate", *records, "--schedule", "0,1"]) != 0
    assert "--schedule" in capsys.readouterr().err
    assert main(["calibrate", *records, "--schedule", "0,a,1"]) != 0
    assert "--schedule" in capsys.readouterr().err
