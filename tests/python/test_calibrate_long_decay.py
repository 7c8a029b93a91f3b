# SPDX-License-Identifier: Apache-2.0
"""Long free decays: the fit on the decimated record finds the modes the full-rate fit finds,
within the uncertainty it states, and identify's spline onto the grid in pieces equals the
whole record's spline."""
import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from smoothshaper.calibrate import decay_decimation as dd
from smoothshaper.calibrate.modes import decay_modes
from smoothshaper.cli import identify as cli_identify


def _decay(n, fs, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    x = 0.7 + 2.0 * np.exp(-0.004 * 2 * np.pi * 10 * t) * np.cos(2 * np.pi * 10 * t + 0.3)
    return x + rng.normal(0.0, 0.01, n)


def test_long_decay_is_decimated_and_fits_the_true_mode():
    fs, n = 8000.0, 3 * dd.FIT_SAMPLES
    x = _decay(n, fs)
    idx, y, q = dd.fit_rate(x, 1 / fs)
    assert q == 3 and y.size == idx.size and y.size < n / 2
    modes, r2 = decay_modes(x, 1 / fs, path="mem", column="x")
    m = modes[0]
    wn_true = 2 * math.pi * 10 / math.sqrt(1 - 0.004 ** 2)    # the signal has wd = 2 pi 10
    # the true mode lies within 4 stated sd (the fit's covariance is that of the decimated
    # samples' noise, which the low-pass makes s^2 / q)
    assert abs(m.wn - wn_true) < 4 * m.wn_std
    assert abs(m.zeta - 0.004) < 4 * m.zeta_std
    # R^2 is over every sample: the noise variance 1e-4 against the signal's
    var = float(np.var(x))
    assert r2 == pytest.approx(1 - 1e-4 / var, abs=5e-4)


def test_decimated_uncertainty_matches_the_full_rate_fit():
    fs, n = 8000.0, 3 * dd.FIT_SAMPLES
    x = _decay(n, fs, seed=1)
    full_rate = dd.FIT_SAMPLES
    try:
        dd.FIT_SAMPLES = 10 ** 9            # no decimation: the reference fit
        ref, _ = decay_modes(x, 1 / fs, path="mem", column="x")
    finally:
        dd.FIT_SAMPLES = full_rate
    dec, _ = decay_modes(x, 1 / fs, path="mem", column="x")
    assert dec[0].wn_std == pytest.approx(ref[0].wn_std, rel=0.15)
    assert dec[0].zeta_std == pytest.approx(ref[0].zeta_std, rel=0.15)
    assert abs(dec[0].wn - ref[0].wn) < 2 * ref[0].wn_std


def test_short_records_are_not_decimated():
    x = _decay(dd.FIT_SAMPLES, 8000.0)
    assert dd.fit_rate(x, 1 / 8000.0)[2] == 1


def test_chunked_spline_equals_the_whole_spline(monkeypatch):
    rng = np.random.default_rng(2)
    n, Ts = 5000, 1e-3
    t = np.arange(n) * Ts + rng.uniform(0.0, 0.3 * Ts, n)
    t -= t[0]
    x = np.sin(2 * np.pi * 7 * t) + 0.01 * rng.normal(size=n)
    monkeypatch.setattr(cli_identify, "_SPLINE_CHUNK", 700)
    whole = CubicSpline(t, x)(np.arange(n) * Ts)
    pieces = cli_identify._spline_onto_grid(CubicSpline, t, x, Ts)
    np.testing.assert_allclose(pieces, whole, rtol=0, atol=1e-12)
