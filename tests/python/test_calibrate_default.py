# SPDX-License-Identifier: Apache-2.0
"""calibrate with no limit given: the delay budget is the length of the shaper the
established tool's trade-off picks on the record's own spectrum (calibrate.default_limit),
so the pick is never longer than the established tool's pick (to one sample of Ts, the exact
discrete filters' grid) and leaves, by the established tool's own estimate (our
re-implementation, klipper_pick), at most 0.1 percentage point more.

Real records: every CSV file of the folder named by SMOOTHSHAPER_REAL_RECORDS (public
resonance tests are not shipped with the repository); the synthetic ones run always."""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest

from smoothshaper import calibrate
from smoothshaper.calibrate import default_limit as dl
from smoothshaper.calibrate import firmware as fw
from smoothshaper.calibrate import synthetic as syn
from smoothshaper.calibrate.candidates import candidate_taps
from smoothshaper.cli import main

import klipper_pick

#: The pick's delay may exceed the established pick's by one sample of the filters' period
#: (the exact discrete filters span whole samples): a factor 1 + Ts / duration, at most 1.01
#: for a pick of 10 ms or more at the default Ts = 1e-4 s.
DELAY_SAMPLES = 1
#: Remaining vibration by the established tool's estimate: at most its pick's + 0.1 point.
VIBRATION_PP = 0.1


def _compare(path, **kw):
    """(our recommendation, the established pick, our pick's remaining vibration by the
    established tool's estimate [%], its own [%], the axis result, Ts)."""
    data = klipper_pick.load(path)
    pick = klipper_pick.best_shaper(data)
    cal = calibrate.run([str(path)], **kw)
    res = cal.axes[0]
    c = res.recommended
    Ts = cal.reference.Ts
    h = candidate_taps(c, Ts)
    ours = 100 * klipper_pick.remaining(*klipper_pick.taps_as_impulses(h, Ts), data)
    return c, pick, ours, 100 * pick["vibrs"], res, Ts


def _assert_as_good(c, pick, ours, theirs, Ts):
    assert c.length <= pick["duration"] + DELAY_SAMPLES * Ts + 1e-12, (c.name, c.length,
                                                                       pick["duration"])
    assert ours <= theirs + VIBRATION_PP, (c.name, ours, theirs)


def _real_records():
    folder = os.environ.get("SMOOTHSHAPER_REAL_RECORDS")
    if not folder:
        return []
    return sorted(Path(folder).glob("*.csv"))


REAL = _real_records()


@pytest.mark.skipif(not REAL, reason="SMOOTHSHAPER_REAL_RECORDS names no folder of records")
@pytest.mark.parametrize("path", REAL, ids=[p.name for p in REAL])
def test_real_record_default_pick_as_good_as_the_established(path):
    """No options: a pick at most one sample longer than the established tool's, leaving by
    its estimate at most 0.1 point more; the budget is the established pick's own length."""
    c, pick, ours, theirs, res, Ts = _compare(path)
    print(f"{path.name}: {c.name} {1e3 * c.length:.2f} ms {ours:.3f} % | established "
          f"{pick['name']} {pick['freq']:.1f} Hz {1e3 * pick['duration']:.2f} ms {theirs:.3f} %")
    _assert_as_good(c, pick, ours, theirs, Ts)
    assert res.default_limit is not None
    assert res.default_limit.max_delay <= pick["duration"] + Ts + 1e-12


@pytest.mark.skipif(len(REAL) < 2, reason="SMOOTHSHAPER_REAL_RECORDS names no folder of "
                    "records")
def test_real_records_default_picks_leave_less_in_sum():
    ours = theirs = 0.0
    for path in REAL:
        _, _, o, t, _, _ = _compare(path)
        ours, theirs = ours + o, theirs + t
    assert ours <= theirs, (ours, theirs)


def _psd_table(tmp_path, modes, df=1.0, floor=1e2):
    """A Klipper PSD table (freq,psd_x,psd_y,psd_z,psd_xyz) of base-excited modes
    [(f Hz, zeta, weight)] under a test's excitation growing with the frequency."""
    f = np.arange(5.0, 200.0 + df / 2, df)
    P = np.full(f.size, floor)
    for fn, z, w in modes:
        r = f / fn
        P += w * f * (1 + 4 * z * z * r * r) / ((1 - r * r) ** 2 + (2 * z * r) ** 2)
    p = tmp_path / "resonances_x_20240101_000000.csv"
    p.write_text("freq,psd_x,psd_y,psd_z,psd_xyz\n" + "".join(
        f"{a:.2f},{0.7 * b:.5e},{0.2 * b:.5e},{0.1 * b:.5e},{b:.5e}\n" for a, b in zip(f, P)))
    return p


def _true(c, Ts, truth, shift=0.0):
    h = candidate_taps(c, Ts)
    return syn.true_remaining(h, np.arange(h.size) * Ts, truth, shift)


@pytest.mark.parametrize("modes", [
    [(45.0, 0.06, 1e4)],
    [(58.0, 0.05, 1e4), (89.0, 0.04, 3e3)],
], ids=["one mode", "two modes"])
def test_psd_table_budget_is_the_established_pick(tmp_path, modes):
    """On a PSD table both tools score the same spectrum: the budget's shaper, frequency and
    duration are the established tool's pick's (to its 0.2 Hz grid). The modal fit explains
    these spectra and ranks: the pick, no longer than the established one, leaves no more on
    the true plant (the established estimate takes the worst of dampings 0.075 to 0.15 where
    the fit knows the plant's 0.04 to 0.06, so it is not the figure to judge the pick by
    here)."""
    p = _psd_table(tmp_path, modes)
    c, pick, ours, theirs, res, Ts = _compare(p)
    lim = res.default_limit
    assert res.ranked_by == "modal fit"
    assert lim.shaper == f"klipper {pick['name']}"
    assert lim.freq == pytest.approx(pick["freq"], abs=0.1)
    assert lim.duration == pytest.approx(pick["duration"], rel=1e-9)
    assert lim.vibration == pytest.approx(theirs, abs=1e-6)
    assert c.length <= pick["duration"] + DELAY_SAMPLES * Ts + 1e-12
    # the table's modes by their energy in the normalised spectrum (area ~ w fn / zeta)
    truth = [(f, z, w * f / z) for f, z, w in modes]
    assert _true(c, Ts, truth) <= syn.true_remaining(pick["A"], pick["T"], truth)


def test_raw_record_default_pick_as_good_as_the_established(tmp_path):
    """A raw sweep (our Welch spectrum, the established tool's own): no longer than its pick,
    and no more left on the true plant."""
    t, A, truth, shift = syn.category_record("klipper sweep", 0, fs=800.0)
    p = tmp_path / "raw_data_x_rec.csv"
    syn.write_csv(p, [t, A[:, 0], A[:, 1], A[:, 2]], ["time", "accel_x", "accel_y", "accel_z"],
                  fmt="%.6f")
    c, pick, ours, theirs, res, Ts = _compare(p)
    assert c.length <= pick["duration"] + DELAY_SAMPLES * Ts + 1e-12
    assert _true(c, Ts, truth, shift) <= syn.true_remaining(pick["A"], pick["T"], truth, shift)


#: The longest budget a printer's record can get: the longest of the trade-off's shapers at
#: its lowest frequency (3hump_ei at 48 Hz, 41.7 ms).
def _longest_budget():
    out = 0.0
    for s in dl.trade_off_shapers("none"):
        _, t = s.impulses(s.suggested_min_freq, dl.DESIGN_DAMPING)
        out = max(out, float(t[-1]))
    return out


def test_budget_is_never_absurd():
    """3hump_ei at 48 Hz: 41.7 ms; a printer's test never gets a longer default budget unless
    a mode lies below every shaper's lowest frequency (21 Hz)."""
    assert _longest_budget() == pytest.approx(0.0417, abs=5e-4)


def test_limits_given_replace_the_default(tmp_path):
    p = _psd_table(tmp_path, [(45.0, 0.06, 1e4)])
    res = calibrate.run([str(p)], max_delay=0.02).axes[0]
    assert res.default_limit is None and res.recommended.length <= 0.02
    res = calibrate.run([str(p)], max_smoothing=1.0).axes[0]
    assert res.default_limit is None
    res = calibrate.run([str(p)]).axes[0]
    assert res.default_limit is not None
    assert res.recommended.length <= res.default_limit.max_delay * (1 + 1e-9)
    assert res.default_limit.max_delay <= _longest_budget() + 1e-4


def test_a_mode_below_every_shaper_gets_a_budget_that_reaches_it(tmp_path):
    """An oscillation at 8 Hz (below ZV's lowest 21 Hz): the scans start at half the slowest
    mode, so the budget is long enough for a shaper at the mode and the pick is tuned there."""
    p = tmp_path / "rec.csv"
    p.write_text("time,accel_x\n" + "".join(
        f"{0.001 * i},{math.sin(2 * math.pi * 8 * 0.001 * i) * math.exp(-0.3 * i / 1000)}\n"
        for i in range(4000)))
    res = calibrate.run([str(p)]).axes[0]
    lim = res.default_limit
    assert lim is not None and lim.freq < 21.0
    assert lim.max_delay >= 0.5 / 8.0 * 0.95        # at least about a ZV at the mode
    assert res.recommended.design[0][0] == pytest.approx(8.0, rel=0.15)


@pytest.mark.parametrize("firmware", ["marlin", "rrf", "prusa"])
def test_other_firmware_budget_from_its_own_shapers(tmp_path, firmware):
    """With another firmware the trade-off is taken over that firmware's shapers; the pick is
    one of them, within the budget."""
    p = _psd_table(tmp_path, [(58.0, 0.05, 1e4), (89.0, 0.04, 3e3)])
    res = calibrate.run([str(p)], firmware=firmware).axes[0]
    lim = res.default_limit
    assert lim.shaper.split()[0] == firmware
    assert lim.shaper.split(maxsplit=1)[1] in {s.name for s in fw.shapers(firmware)}
    assert res.recommended.firmware[0].firmware == firmware
    assert res.recommended.length <= lim.max_delay * (1 + 1e-9)


def test_the_report_and_json_state_the_default(tmp_path, capsys):
    p = _psd_table(tmp_path, [(45.0, 0.06, 1e4)])
    js = tmp_path / "out.json"
    assert main(["calibrate", str(p), "--no-progress", "--json", str(js)]) == 0
    out = capsys.readouterr().out
    assert "no --max-delay or --max-smoothing: the delay is limited to" in out
    assert "the default: the established trade-off's klipper" in out
    import json
    doc = json.loads(js.read_text())
    lim = doc["axes"][0]["default_limit"]
    assert lim["shaper"].startswith("klipper ") and lim["max_delay"] > 0
    assert doc["recommended"]["delay"]["length"] <= lim["max_delay"] * (1 + 1e-9)
