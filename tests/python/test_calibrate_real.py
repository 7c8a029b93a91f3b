# SPDX-License-Identifier: Apache-2.0
"""calibrate on records that look like real ones: every synthetic category of a real sensor and
test (quantisation, clipping, FIFO gaps, Klipper's sweep, close, broad, cross and shifting
modes), Klipper's table vintages, and a property test over real-looking spectra: never a
refusal or a traceback on a valid record, and a pick no longer than the established tool's at
its delay."""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings, strategies as st

from smoothshaper import calibrate
from smoothshaper.calibrate import synthetic as syn
from smoothshaper.calibrate.candidates import TIE_PP, candidate_taps
from smoothshaper.cli import main

import calibrate_campaign
import klipper_pick


def _write(tmp_path, name, t, A):
    p = tmp_path / name
    syn.write_csv(p, [t, A[:, 0], A[:, 1], A[:, 2]], ["time", "accel_x", "accel_y", "accel_z"],
                  fmt="%.6f")
    return p


def _campaign(tmp_path, seeds, fs=800.0):
    """(win rate, coverage, draws) over the categories (:mod:`calibrate_campaign`): a win when
    the pick leaves no more vibration on the true plant than the established tool's pick at
    its delay, covered when the stated +-3 sd range holds the true value."""
    draws = calibrate_campaign.run(seeds, str(tmp_path), fs=fs)
    wins = sum(d.win for d in draws) / len(draws)
    cover = sum(d.covered for d in draws) / len(draws)
    print(calibrate_campaign.table(draws))
    return wins, cover, draws


def _draw(tmp_path, category, **kw):
    """(our pick, its remaining vibration on the true plant [%], the established pick's there,
    our pick's by the established tool's estimate [%], the established pick's, axis result)
    on a record of the category (seed 0, 800 Hz), our pick no longer than the established."""
    t, A, truth, shift = syn.category_record(category, 0, fs=800.0)
    p = _write(tmp_path, "raw_data_x_rec.csv", t, A)
    data = klipper_pick.load(p)
    pick = klipper_pick.best_shaper(data)
    res = calibrate.run([str(p)], max_delay=pick["duration"], **kw)
    c = res.axes[0].recommended
    assert c is not None and c.length <= pick["duration"] * (1 + 1e-9)
    Ts = res.reference.Ts
    h = candidate_taps(c, Ts)
    return (c, syn.true_remaining(h, np.arange(h.size) * Ts, truth, shift),
            syn.true_remaining(pick["A"], pick["T"], truth, shift),
            100 * klipper_pick.remaining(*klipper_pick.taps_as_impulses(h, Ts), data),
            100 * pick["vibrs"], res.axes[0])


def test_spectral_ranking_within_the_established_estimate(tmp_path):
    """Ranked on the measured spectrum alone, the pick leaves by the established tool's own
    estimate (on the PSD it computes) at most 0.1 percentage point more than its pick at its
    delay: the rule on real records. (On records with gaps or clipped samples the two tools
    score different spectra: the established tool takes the samples either side of a gap as
    adjacent and the rails as measured.)"""
    c, _, _, ours, theirs, res = _draw(tmp_path, "klipper sweep", ranking="spectrum")
    assert res.ranked_by == "measured spectrum"
    assert ours <= theirs + 0.1, (c.name, ours, theirs)


def test_campaign_every_category_once(tmp_path):
    """The acceptance campaign at test size: one record of every category (seed 0, 800 Hz),
    each written as the established tool's raw test and scored on its true plant. No refusal,
    a pick no longer than the established tool's; wins (no more vibration on the true plant
    than its pick) on at least 80 % and the stated +-3 sd range holding the true value on at
    least 95 % (here: all twelve). The figures and the ranges' widths are printed."""
    wins, cover, draws = _campaign(tmp_path, [0])
    assert len(draws) == len(syn.CATEGORIES)
    assert all(math.isfinite(d.ours) for d in draws)
    assert wins >= 0.8 and cover >= 0.95, [d.line() for d in draws
                                           if not (d.win and d.covered)]
    # where the modal fit explains the spectrum it ranks (the single clean modes, gaps and
    # clipped runs handled), and there the pick leaves less on the true plant
    assert all(d.ranked_by == "modal fit" for d in draws
               if d.category in ("klipper sweep", "fifo gaps", "clipped"))
    assert all(d.win for d in draws if d.ranked_by == "modal fit"), [d.line() for d in draws]


#: The acceptance campaign's seeds in the long mode: 0 to N - 1 with
#: SMOOTHSHAPER_CAMPAIGN_SEEDS=N (default 3); each perturbs every category's modes and draws its
#: noise (N = 17 makes 204 records per sample rate).
CAMPAIGN_SEEDS = tuple(range(int(os.environ.get("SMOOTHSHAPER_CAMPAIGN_SEEDS", "3"))))


@pytest.mark.long
@pytest.mark.parametrize("fs", [800.0, 1600.0])
def test_campaign_win_rate_and_coverage(tmp_path, fs):
    """The acceptance campaign at each sample rate: every category over the seeds (36 draws at
    the default 3, about 4 min of CPU); wins >= 80 %, coverage >= 95 %, and per category the
    median width of the stated ranges relative to the true value printed (a range wide enough
    to hold anything is no answer)."""
    wins, cover, draws = _campaign(tmp_path, CAMPAIGN_SEEDS, fs=fs)
    width = float(np.median([d.relative_width for d in draws]))
    print(f"{fs:g} Hz: wins {100 * wins:.0f} %, covered {100 * cover:.0f} %, median width of "
          f"the stated ranges {width:.3g} times the true value")
    assert wins >= 0.8 and cover >= 0.95, (wins, cover, [d.line() for d in draws
                                                         if not (d.win and d.covered)])


def test_mode_uncertainty_is_calibrated(tmp_path):
    """The stated sd of each fitted mode: every true mode within 3 sd in frequency and damping
    (a mode in series behind a 20 Hz one came out 3.1 sd off in damping with a fixed tenth of a
    bin for the model's bias), and a clean single mode's frequency sd below that tenth of a bin
    (which was 5 to 30 times its error: a range that loose is no answer). The bias now grows
    with the fit's misfit (``calibrate.FREQ_BIAS_PER_MISFIT``)."""
    for category, seed in (("klipper sweep", 0), ("20 Hz belt mode", 1)):
        t, A, truth, _ = syn.category_record(category, seed, fs=800.0)
        rec = calibrate.load(str(_write(tmp_path, f"raw_data_x_{seed}.csv", t, A)))
        name, signal, cols = calibrate._analyses(rec, "auto")[0]
        res = calibrate.identify(rec, name, signal, cols)
        assert res.explains and len(res.modes) == len(truth)
        for f, z, _ in truth:
            m = min(res.modes, key=lambda m: abs(m.f_hz - f))
            assert abs(m.wn - 2 * math.pi * f) <= 3 * m.wn_std, (category, f, m)
            assert abs(m.zeta - z) <= 3 * m.zeta_std, (category, z, m)
        if category == "klipper sweep":
            assert res.modes[0].wn_std / (2 * math.pi) < 0.1 * res.resolution


def test_modal_range_is_the_joint_three_sd_disc():
    """One mode, one shaper: the range's ends are the residual's extremes over the joint
    +-3 sd disc of (wn, zeta), which reaches +-3 sd along each axis and stops short of the
    box's corners (4.2 sd out); the range holds the value it is stated with, and its least is
    0 where the shaper's zero lies inside the disc (a grid's least had stated 0.0185 % where
    the campaign's true plant was left with 0.009 %)."""
    from types import SimpleNamespace
    from smoothshaper.calibrate.objectives import ModalObjective, impulses_R2
    wn, zeta = 2 * math.pi * 40.0, 0.05
    mode = SimpleNamespace(wn=wn, zeta=zeta, wn_std=0.01 * wn, zeta_std=0.2 * zeta, weight=1.0,
                           weight_rsd=0.05)
    obj = ModalObjective([mode])
    K = math.exp(-zeta * math.pi / math.sqrt(1 - zeta ** 2))
    A = np.array([1.0, K]) / (1 + K)
    t = np.array([0.0, math.pi / (wn * math.sqrt(1 - zeta ** 2))])     # ZV on the mode

    def R(u, v):                # residual [%] at (wn, zeta) + (u, v) sd, from the filter's end
        p = complex(-(zeta + v * mode.zeta_std) * (wn + u * mode.wn_std),
                    (wn + u * mode.wn_std) * math.sqrt(1 - (zeta + v * mode.zeta_std) ** 2))
        return 100 * math.sqrt(float(impulses_R2(A, t, np.array([p]))[0])) * math.exp(p.real * t[-1])
    lo, hi = obj.range(impulses_R2(A, t, obj.box), t[-1])
    value = obj.value(impulses_R2(A, t, obj.poles), t[-1])
    assert lo <= value <= hi
    on_axes = max(R(3, 0), R(-3, 0), R(0, 3), R(0, -3))
    corners = max(R(a, b) for a in (-3, 3) for b in (-3, 3))
    assert on_axes <= hi * (1 + 1e-9) and hi < corners
    # the disc's rim at 32 points under-reads a residual linear in (u, v) by at most 0.5 %
    rim = max(R(3 * math.cos(a), 3 * math.sin(a)) for a in np.linspace(0, 2 * math.pi, 721))
    assert hi <= rim * (1 + 1e-9) and hi >= rim * (1 - 0.005)
    # the shaper's zero lies inside: the least is 0, not the grid's least
    assert lo == 0.0
    # a ZV tuned 5 sd above the mode: no zero inside, the least is on the rim (the residual is
    # the modulus of a function analytic in the pole), within the rim's sampling
    wz = wn * (1 + 5 * 0.01)
    tz = np.array([0.0, math.pi / (wz * math.sqrt(1 - zeta ** 2))])
    lo, hi = obj.range(impulses_R2(A, tz, obj.box), tz[-1])

    def Rz(u, v):
        p = complex(-(zeta + v * mode.zeta_std) * (wn + u * mode.wn_std),
                    (wn + u * mode.wn_std) * math.sqrt(1 - (zeta + v * mode.zeta_std) ** 2))
        return 100 * math.sqrt(float(impulses_R2(A, tz, np.array([p]))[0])) * math.exp(p.real * tz[-1])
    fine = min(Rz(r * math.cos(a), r * math.sin(a)) for r in np.linspace(0, 3, 31)
               for a in np.linspace(0, 2 * math.pi, 181))
    assert 0 < lo and fine * (1 - 0.005) <= lo <= fine * (1 + 0.005)


@pytest.mark.parametrize("seed", [0, 2])
def test_a_weak_mode_on_a_larger_ones_tail_is_resolved(tmp_path, seed):
    """The campaign's three modes (35, 56 and 94 Hz, the last with a hundredth of the energy):
    the weak one never falls to half its peak on the 56 Hz mode's tail, so its half-power width
    reached that mode and the fit went there (94 Hz was not found). Its window now ends at the
    valleys either side. Every mode is found within a quarter of a bin, and each one's share of
    the energy within its stated +-3 sd (the power law of a window is taken at its peak: carried
    out to a third and three times the frequency it had moved the 35/56 Hz shares to 1 : 0.85
    where the plant holds 1 : 0.53)."""
    t, A, truth, _ = syn.category_record("three modes", seed, fs=800.0)
    rec = calibrate.load(str(_write(tmp_path, "raw_data_x_rec.csv", t, A)))
    name, signal, cols = calibrate._analyses(rec, "auto")[0]
    res = calibrate.identify(rec, name, signal, cols)
    assert len(res.modes) == 3, [(m.f_hz, m.zeta) for m in res.modes]
    true_total = sum(w for _, _, w in truth)
    total = sum(m.weight for m in res.modes)
    for f, z, w in truth:
        m = min(res.modes, key=lambda m: abs(m.f_hz - f))
        assert abs(m.f_hz - f) <= 0.25 * res.resolution, (m.f_hz, f)
        share, true_share = m.weight / total, w / true_total
        assert abs(math.log(share / true_share)) <= 3 * m.weight_rsd, (f, share, true_share)


def test_klipper_sweep_is_a_square_wave_rising_one_hz_a_second():
    u = syn.klipper_sweep(3200.0, sweeping_period=0)
    assert u.size == pytest.approx(3200 * 128.0, rel=0.01)       # 5 -> 133 Hz at 1 Hz/s
    assert set(np.unique(np.sign(u))) == {-1.0, 1.0}
    assert np.max(np.abs(u)) == pytest.approx(60 * 133, rel=0.01)


def test_gaps_and_clipping_are_excluded_and_stated(tmp_path):
    t, A, _, _ = syn.category_record("fifo gaps", 1)
    rec = calibrate.load(str(_write(tmp_path, "g.csv", t, A)))
    assert rec.gaps > 0 and 0.015 < rec.excluded < 0.05 and len(rec.segments) > 1
    assert any("gaps" in n for n in rec.notes)
    t, A, _, _ = syn.category_record("clipped", 1)
    rec = calibrate.load(str(_write(tmp_path, "c.csv", t, A)))
    assert rec.clipped > 0 and any("clipped" in n for n in rec.notes)
    assert calibrate.run([str(tmp_path / "c.csv")]).axes[0].recommended is not None


def test_quiet_quantised_axis_is_not_taken_for_clipping(tmp_path):
    """A resting z axis of a 3.9 mg/LSB sensor holds a few levels: no clipping."""
    t, A, _, _ = syn.category_record("adxl345 quantised", 2)
    A[:, 2] = np.round((9806.65 + np.random.default_rng(0).normal(0, 20, t.size))
                       / syn.ADXL_LSB) * syn.ADXL_LSB
    rec = calibrate.load(str(_write(tmp_path, "q.csv", t, A)))
    assert rec.clipped == 0


def _table(f, P, header="freq,psd_x,psd_y,psd_z,psd_xyz", extra=""):
    rows = [header + extra]
    for fi, pi in zip(f, P):
        rows.append(f"{fi:.1f},{0.6 * pi:.3e},{0.3 * pi:.3e},{0.1 * pi:.3e},{pi:.3e}"
                    + ("," + ",".join("0.100" for _ in range(extra.count("(")))
                       if extra and "shapers:" not in extra else
                       ",," + ",".join("0.100" for _ in range(extra.count("("))) if extra else ""))
    return "\n".join(rows) + "\n"


@pytest.mark.parametrize("extra", ["", ",zv(39.2),mzv(36.4)", ",shapers:,zv(39.2),mzv(36.4)"],
                         ids=["plain", "old shaper columns", "shapers: marker"])
def test_every_klipper_table_vintage_is_read(tmp_path, extra):
    f = np.arange(0, 200, 1.5)
    P = 1e3 + 1e5 * syn.plant([(2 * math.pi * 45, 0.05)]).magnitude(2 * math.pi * f) ** 2 \
        if hasattr(syn.plant([(1.0, 0.1)]), "magnitude") else \
        1e3 + 1e5 / ((1 - (f / 45) ** 2) ** 2 + (0.1 * f / 45) ** 2)
    p = tmp_path / "resonances_y_20220101_000000.csv"
    p.write_text(_table(f, P, extra=extra))
    res = calibrate.run([str(p)]).axes[0]
    assert res.name == "y" and res.signal.startswith("x+y+z")
    assert res.record.normalized == bool(extra) and res.record.marked == ("shapers:" in extra)
    assert res.recommended is not None
    assert abs(res.modes[0].f_hz - 45) < 1.5


#: The property test's draws: a third of the full dozen in the default suite (about 10 s of CPU
#: each), all of them in the long mode (SMOOTHSHAPER_LONG=1 ... -m long).
NEVER_REFUSED_DRAWS = 12 if os.environ.get("SMOOTHSHAPER_LONG") == "1" else 4


@pytest.mark.long
def test_real_looking_spectra_never_refused_full_draw(tmp_path_factory):
    """The property test below in the long mode (``-m long`` selects this one): all twelve
    draws, as SMOOTHSHAPER_LONG=1 sizes it."""
    test_real_looking_spectra_never_refused(tmp_path_factory)


@settings(max_examples=NEVER_REFUSED_DRAWS, deadline=None)
# a peak no higher than the floor at the table's start: its single fit came out broader than
# its frequency and the close-pair refit started a mode below 0 Hz (math domain error)
@example(n_bins=60, df=1.5, peaks=[(20.0, 0.015139623193049453, 0.0)], floor=0.0, flat=False,
         lo=0.0)
@given(n_bins=st.integers(20, 140), df=st.sampled_from([0.5, 1.5, 3.0]),
       peaks=st.lists(st.tuples(st.floats(20, 120), st.floats(0.003, 0.3), st.floats(0, 6)),
                      min_size=0, max_size=3),
       floor=st.floats(-3, 3), flat=st.booleans(), lo=st.floats(0, 40))
def test_real_looking_spectra_never_refused(tmp_path_factory, n_bins, df, peaks, floor, flat,
                                            lo):
    """Narrow bands, one or two bins per peak, flat tops, huge dynamic range: always a
    recommendation (exit 0), never a traceback."""
    f = lo + np.arange(n_bins) * df
    P = np.full(n_bins, 10.0 ** floor)
    for fc, z, height in peaks:
        P += 10.0 ** height / (1 + ((f - fc) / (z * fc)) ** 2)
    if flat:
        P = np.minimum(P, np.percentile(P, 80))
    p = tmp_path_factory.mktemp("spec") / "resonances_x_1.csv"
    p.write_text(_table(f, P))
    res = calibrate.run([str(p)]).axes[0]
    assert res.recommended is not None
    assert all(math.isfinite(c.vibration) for c in res.candidates)


# ------------------------------------------------ records that once crashed calibrate

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("rows", [64, 100, 200, 450])
def test_short_free_decays_calibrate(tmp_path, capsys, rows):
    """The first rows of the shipped decay (what `identify` fits) once ended in a NumPy
    broadcast error between a 27-tap smoothing kernel and the 17 bins of so short a record."""
    lines = (ROOT / "examples" / "decay.csv").read_text().splitlines()
    p = tmp_path / "decay.csv"
    p.write_text("\n".join(lines[: 2 + rows]) + "\n")
    assert main(["calibrate", str(p), "--no-progress"]) == 0
    assert "recommended" in capsys.readouterr().out


@pytest.mark.parametrize("df,zeta", [(1.72, 0.03), (1.0, 0.015), (0.25, 0.004)])
def test_psd_tables_with_a_narrow_peak_calibrate(tmp_path, df, zeta):
    """Clean single-peak tables whose peak spans a dozen or two frequencies were refused as
    too few to fit a mode, or crashed on a smoothing kernel longer than the band."""
    fc = 58.0
    f = np.arange(5.0, 200.0, df)
    P = 1e2 + 1e5 / (1 + ((f - fc) / (zeta * fc)) ** 2)
    p = tmp_path / "resonances_x_20230101_000000.csv"
    p.write_text("freq,psd_x,psd_y,psd_z,psd_xyz\n" + "".join(
        f"{a:.3f},{b:.4e},{0.01 * b:.4e},{0.01 * b:.4e},{1.02 * b:.4e}\n" for a, b in zip(f, P)))
    res = calibrate.run([str(p)]).axes[0]
    assert res.recommended is not None
    assert res.band[0] <= fc <= res.band[1]
    assert abs(res.modes[0].f_hz - fc) < df


def test_every_axis_of_a_raw_record_calibrates(capsys):
    """`--axis all` on a raw record once ended in OverflowError (math range error) in the
    joint fit of the axes."""
    path = ROOT / "examples" / "resonance_xy.csv"
    assert main(["calibrate", str(path), "--axis", "all", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "== axis x" in out and "== axis y" in out and out.count("recommended") >= 2


def _one_mode_table(tmp_path, fc=41.0, zeta=0.08, name="resonances_y_20221026_004455.csv"):
    """A Klipper PSD table of one mode on a floor, 1.5 Hz bins to 200 Hz (what the test of an
    axis of a CoreXY printer writes)."""
    f = np.arange(0.0, 200.0, 1.5)
    P = 1e2 + 1e4 / ((1 - (f / fc) ** 2) ** 2 + (2 * zeta * f / fc) ** 2)
    p = tmp_path / name
    p.write_text(_table(f, P))
    return p


@pytest.mark.parametrize("firmware", ["marlin", "prusa", "rrf", "klipper"])
def test_firmware_damping_up_to_one_raises_no_overflow(tmp_path, firmware):
    """Marlin and Prusa accept a shaper damping ratio up to 1: there the shaper lasts seconds,
    and the one-shaper scan's e^{zeta wn t} at the plant's poles overflowed (a RuntimeWarning
    on every real table). Such scales are infeasible, and the run warns of nothing."""
    import warnings
    p = _one_mode_table(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = calibrate.run([str(p)], firmware=firmware).axes[0]
    c = res.recommended
    assert c is not None and c.firmware is not None
    assert c.length <= res.default_limit.max_delay * (1 + 1e-9)
    assert math.isfinite(c.vibration) and 0 <= c.vibration < 100


def _floor_table(tmp_path, seed, floor, fc=64.0, zeta=0.08, df=1.28):
    """A Klipper PSD table of one mode over a rough floor that stands, once normalised to the
    test's excitation, at ``floor`` times the peak at every frequency to 200 Hz (a sensor whose
    whole spectrum lies above the estimate's twentieth of the peak, as some real tables do)."""
    rng = np.random.default_rng(seed)
    f = np.arange(0.0, 200.0, df)
    mode = 1.0 / ((1 - (f / fc) ** 2) ** 2 + (2 * zeta * f / fc) ** 2)
    P = 1e5 * (mode + floor * mode.max() / (fc + 0.1) * (f + 0.1)
               * rng.lognormal(0.0, 0.3, f.size))
    p = tmp_path / f"resonances_x_2022010{seed}_000000.csv"
    p.write_text(_table(f, P))
    return p


@pytest.mark.parametrize("firmware", ["none", "klipper"])
@pytest.mark.parametrize("seed,floor", [(0, 0.1), (1, 0.15)])
def test_a_floor_above_the_threshold_keeps_the_established_budget_and_estimate(
        tmp_path, seed, floor, firmware):
    """A floor above a twentieth of the peak out to 200 Hz: the estimate cut at 1.5 times the
    excited band's top had moved the trade-off pick (a budget of 10.8 ms where the established
    tool's pick lasts 13.5 ms), and the modal ranking's ZV notch, which explains the band,
    left 3.9 to 9.2 points more of the spectrum by the established estimate. Now the budget is
    that tool's pick and ours leaves by its estimate at most 0.1 point more (the rule on real
    records)."""
    p = _floor_table(tmp_path, seed, floor)
    data = klipper_pick.load(p)
    pick = klipper_pick.best_shaper(data)
    cal = calibrate.run([str(p)], firmware=firmware)
    res = cal.axes[0]
    lim = res.default_limit
    assert lim.shaper == f"klipper {pick['name']}"
    assert lim.freq == pytest.approx(pick["freq"], abs=1e-9)
    assert lim.duration == pytest.approx(pick["duration"], rel=1e-12)
    c = res.recommended
    assert c.length <= lim.max_delay * (1 + 1e-9)
    Ts = cal.reference.Ts
    ours = klipper_pick.remaining(*klipper_pick.taps_as_impulses(candidate_taps(c, Ts), Ts),
                                  data)
    assert 100 * ours <= 100 * pick["vibrs"] + 0.1, (c.name, ours, pick)
    # the trade-off pick is among the candidates, and nothing leaving more meets the limits
    assert any(k.name.endswith("(trade-off pick)") and k.meets for k in res.candidates)
    assert all(k.vibration_established <= 100 * pick["vibrs"] + TIE_PP + 1e-6
               for k in res.candidates if k.meets)


def test_a_mode_above_a_firmwares_range_still_gets_its_shapers(tmp_path):
    """Prusa's shapers run from 10 to 100 Hz: with the largest mode at 122 Hz (a Voron belt
    sweep's) no design existed at the mode, every scan of a Prusa shaper came back empty and
    calibrate ended in an IndexError. The scans now start at the nearest frequency the
    firmware accepts; every pick is within its range."""
    p = _one_mode_table(tmp_path, fc=122.0, zeta=0.06, name="resonances_x_20231128_221505.csv")
    res = calibrate.run([str(p)], firmware="prusa").axes[0]
    c = res.recommended
    assert c is not None and c.firmware is not None
    shaper, freq, damping = c.firmware
    assert shaper.min_freq <= freq <= shaper.max_freq == 100.0
    assert sum(k.firmware is not None for k in res.candidates) >= 3
