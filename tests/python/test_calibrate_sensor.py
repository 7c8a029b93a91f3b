# SPDX-License-Identifier: Apache-2.0
"""What real accelerometers do to a record: clipped samples (calibrate.clipping) are found exactly
where a signal sits on the sensor's rail and nowhere else, and reconstructed so the spectrum
keeps the resonance's energy that the rails cut off; FIFO gaps leave the Welch estimate
(calibrate.spectra.welch) where the gapless record puts it, and without gaps it is
scipy.signal.welch."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.signal

from smoothshaper.calibrate import synthetic as syn
from smoothshaper.calibrate.clipping import clipped_samples, reconstruct
from smoothshaper.calibrate.spectra import welch

FS = 1600.0
Q = 0.004               # quantisation step of the test signals (a rail at 1)


def _sine(amplitude, n=4000, f=45.0, phase=0.3):
    t = np.arange(n) / FS
    return amplitude * np.sin(2 * np.pi * f * t + phase)


def test_clipped_sine_found_exactly_and_reconstructed_within_a_step():
    y = _sine(1.4)
    yq = np.round(y / Q) * Q
    yc = np.clip(yq, -1.0, 1.0)
    mask, cols = clipped_samples(yc[:, None])
    assert cols == [0]
    np.testing.assert_array_equal(mask[:, 0], np.abs(yq) > 1.0)
    before = yc.copy()
    r = reconstruct(yc, mask[:, 0])
    np.testing.assert_array_equal(yc, before)          # the input is not changed
    np.testing.assert_array_equal(r[~mask[:, 0]], yc[~mask[:, 0]])
    # the rails are 0.4 off at the crests; a least-squares sinusoid through hundreds of
    # unclipped samples, each within Q/2 of the truth, lands well within one step
    assert np.max(np.abs(yc - y)) > 0.39
    assert np.max(np.abs(r - y)[mask[:, 0]]) < Q


@pytest.mark.parametrize("amplitude", [0.6, 1.0])
def test_unclipped_quantised_signals_are_not_taken_for_clipping(amplitude):
    """A quantised sine reaching its extremes only briefly (thinning out there), and noise."""
    rng = np.random.default_rng(1)
    y = np.round((_sine(amplitude) + rng.normal(0, 0.01, 4000)) / Q) * Q
    mask, cols = clipped_samples(np.column_stack([y, np.round(rng.normal(0, 1, 4000) / Q) * Q]))
    assert cols == [] and not mask.any()


def test_reconstruction_restores_the_resonance_energy_of_a_clipped_sweep(monkeypatch):
    """The campaign's clipped record (the resonance drives the sensor to 1.5 times its range)
    against the same record with the sensor's range lifted: the rails lose 13 % of the energy
    about the mode and spread it into harmonics; reconstructed, the loss is under 5 % and the
    harmonics within 5 % of the unclipped record's."""
    clip = np.clip
    monkeypatch.setattr(np, "clip", lambda a, lo, hi: a)
    t, A, _, _ = syn.category_record("clipped", 0)
    monkeypatch.setattr(np, "clip", clip)
    x = A[:, 0]
    xc = np.clip(x, -syn.ADXL_RANGE, syn.ADXL_RANGE)
    mask, cols = clipped_samples(xc[:, None])
    assert cols == [0]
    np.testing.assert_array_equal(mask[:, 0], np.abs(x) > syn.ADXL_RANGE)
    r = reconstruct(xc, mask[:, 0])
    Ts = float(np.median(np.diff(t)))

    def energies(y):
        s = welch(y, Ts)
        return (float(np.sum(s.P[(s.f > 30) & (s.f < 60)])),
                float(np.sum(s.P[(s.f > 70) & (s.f < 200)])))

    (e_true, h_true), (e_clip, h_clip), (e_rec, h_rec) = map(energies, (x, xc, r))
    assert e_clip < 0.9 * e_true and h_clip > 1.15 * h_true
    assert e_rec == pytest.approx(e_true, rel=0.05)
    assert h_rec == pytest.approx(h_true, rel=0.05)


def _noisy_sine(n, rng):
    return _sine(1.0, n=n) + rng.normal(0, 0.1, n)


def test_welch_without_gaps_is_scipys():
    x = _noisy_sine(20000, np.random.default_rng(2))
    s = welch(x, 1 / FS, nperseg=1024)
    f, P = scipy.signal.welch(x, FS, window="hann", nperseg=1024, noverlap=768,
                              detrend="constant")
    np.testing.assert_allclose(s.f, f, rtol=0, atol=1e-12)
    np.testing.assert_allclose(s.P, P, rtol=1e-10, atol=0)


def test_fifo_gaps_leave_the_spectrum_where_the_gapless_record_puts_it():
    """3 % of the samples missing in gaps of 10-50 ms: the windows keep their length (the
    resolution) and the peak its bin; each window is normalised by the window energy on the
    samples it holds, so the total power is the gapless record's (zero-filled gaps would take
    3 % off it). A window with a gap has sharp edges inside it: a little of the peak's power
    leaks out of its +-3 bins (at most the missing share, 3 %) onto the floor, which at 60 dB
    below the peak rises by about a tenth."""
    rng = np.random.default_rng(3)
    n = 48000
    x = _noisy_sine(n, rng)
    keep = np.ones(n, dtype=bool)
    while np.count_nonzero(~keep) < 0.03 * n:
        a = int(rng.integers(0, n))
        keep[a: a + int(rng.uniform(0.010, 0.050) * FS)] = False
    idx = np.flatnonzero(keep)
    cut = np.flatnonzero(np.diff(idx) > 1)
    starts = np.r_[0, cut + 1]
    stops = np.r_[cut + 1, idx.size]
    segments = list(zip(starts.tolist(), stops.tolist()))
    grid = idx[starts].tolist()
    full = welch(x, 1 / FS, nperseg=2048)
    gapped = welch(x[keep], 1 / FS, segments=segments, starts=grid, nperseg=2048)
    assert gapped.f.size == full.f.size
    peak = np.argmax(full.P)
    assert np.argmax(gapped.P) == peak
    band = slice(peak - 3, peak + 4)
    assert np.sum(gapped.P) == pytest.approx(np.sum(full.P), rel=0.005)
    assert np.sum(gapped.P[band]) == pytest.approx(np.sum(full.P[band]), rel=0.03)
    floor = (full.f > 100) & (full.f < 700)
    assert np.mean(gapped.P[floor]) == pytest.approx(np.mean(full.P[floor]), rel=0.15)


@pytest.mark.parametrize("category", ["fifo gaps", "clipped"])
def test_the_band_and_the_modes_do_not_depend_on_the_sample_rate(tmp_path, category):
    """The same test sampled at 800 Hz and 1.6 kHz: the excited band ends at the sweep's end
    (133 Hz) at both rates and the fit finds the one true mode at both. The quiet floor is a
    percentile of the whole spectrum, so at 1.6 kHz it sat lower and the sweep's harmonics
    above 133 Hz counted as excited (the band reached 200 Hz with FIFO gaps, 500 Hz clipped);
    the fit then took the sweep's cliff for a broad mode near 113 Hz and moved the true one."""
    from smoothshaper import calibrate
    from smoothshaper.calibrate import identify, records
    tops = []
    for fs in (800.0, 1600.0):
        t, A, truth, _ = syn.category_record(category, 0, fs=fs)
        path = tmp_path / f"raw_data_x_{int(fs)}.csv"
        syn.write_csv(path, [t, A[:, 0], A[:, 1], A[:, 2]],
                      ["time", "accel_x", "accel_y", "accel_z"], fmt="%.6f")
        rec = records.load(str(path), "auto")
        name, signal, cols = calibrate._analyses(rec, "auto")[0]
        res = identify(rec, name, signal, cols)
        assert 130.0 <= res.hull_hi <= 140.0, (fs, res.hull_hi)
        tops.append(res.hull_hi)
        (f_true, z_true, _), = truth
        assert len(res.modes) == 1, (fs, [(m.f_hz, m.zeta) for m in res.modes])
        m = res.modes[0]
        # within 3 sd, or 0.5 % (the sweep's softening-free plant, the 0.39 Hz bins)
        assert abs(m.f_hz - f_true) <= max(3 * m.wn_std / (2 * np.pi), 0.005 * f_true), (fs, m)
        assert res.explains
    # the band's top moves by at most 5 % between rates (at 1.6 kHz the clipped record holds
    # the third harmonic of its 45 Hz mode, 135 Hz, at the cliff's foot)
    assert abs(tops[0] - tops[1]) <= 0.05 * tops[0]


def test_two_modes_2_hz_apart_are_resolved(tmp_path):
    """Two modes 2 Hz apart in series, each about as wide as their distance, make one flat-topped
    peak with no dip between them: a single mode fitted it 48.7 Hz with zeta 0.004 (too narrow,
    and the fit then explained 55 % of the spectrum). The pair is now tried for every mode and
    kept where it lowers the sum of squares by far more than the noise (an F test): both modes
    within 3 sd of the truth and the fit explains the spectrum."""
    from smoothshaper import calibrate
    from smoothshaper.calibrate import identify, records
    t, A, truth, _ = syn.category_record("two modes 2 Hz apart", 0, fs=800.0)
    path = tmp_path / "raw_data_x_0.csv"
    syn.write_csv(path, [t, A[:, 0], A[:, 1], A[:, 2]], ["time", "accel_x", "accel_y", "accel_z"],
                  fmt="%.6f")
    rec = records.load(str(path), "auto")
    res = identify(rec, *calibrate._analyses(rec, "auto")[0])
    assert len(res.modes) == 2, [(m.f_hz, m.zeta) for m in res.modes]
    found = sorted(res.modes, key=lambda m: m.wn)
    for m, (f, z, _) in zip(found, sorted(truth)):
        assert abs(m.f_hz - f) <= max(3 * m.wn_std / (2 * np.pi), 0.02), (m, f)
        assert abs(m.zeta - z) <= max(3 * m.zeta_std, 0.1 * z), (m, z)
    assert res.explains
