# SPDX-License-Identifier: Apache-2.0
"""The tuning loop's remembered impulses and ZV spans are the reference design's, bit for bit."""
import math

import numpy as np
import pytest

from smoothshaper import shaper
from smoothshaper.calibrate.design_memo import impulses, zv_span
from smoothshaper.reference import shaper_impulses


def _stages():
    rng = np.random.default_rng(7)
    for kind, kw in (("zv", {}), ("mzv", {}), ("zvd", {}), ("ei", {}), ("ei2", {}),
                     ("zvn", {"order": 4}), ("gmzv", {"order": 5, "duration": 1.3})):
        for wn, zeta in zip(rng.uniform(20.0, 2000.0, 20), rng.uniform(0.0, 0.6, 20)):
            yield shaper(kind, wn=float(wn), zeta=float(zeta), **kw)


@pytest.mark.parametrize("stage", list(_stages()), ids=lambda s: f"{s.kind}-{s.wn:.0f}-{s.zeta:.3f}")
def test_same_as_reference(stage):
    A, t = impulses(stage)
    A_ref, t_ref = shaper_impulses(stage)
    np.testing.assert_array_equal(A, A_ref)
    np.testing.assert_array_equal(t, t_ref)
    assert impulses(stage) is impulses(stage)            # one computation per stage
    assert not A.flags.writeable and not t.flags.writeable
    assert zv_span(stage) == float(shaper_impulses(stage.with_(kind="zv"))[1][-1])


def _transfer_per_term(q, a):
    """The input smoothers' transfer as a loop over the series' terms and NumPy's polynomial
    routines (the form the faster one must equal bit for bit)."""
    from numpy.polynomial import polynomial as P
    from smoothshaper.reference.input_smoothers import _SERIES_LIMIT

    def _moment(q, m):       # int u^m P(u) du over [-1/2, 1/2], term by term
        return sum(c * (0.5 ** (m + j) / (m + j + 1)) for j, c in enumerate(q)
                   if (m + j) % 2 == 0)
    a = np.asarray(a, dtype=complex)
    out = np.empty(a.shape, dtype=complex)
    small = np.abs(a) <= _SERIES_LIMIT
    x = a[small]
    total, term, m = np.zeros(x.shape, dtype=complex), np.ones(x.shape, dtype=complex), 0
    while x.size and (m <= 20 or np.max(np.abs(term)) > 1e-18):
        total += term * _moment(q, m)
        m += 1
        term = term * (-x / m)
    out[small] = total * np.exp(-x / 2)
    x = a[~small]
    acc, deriv, power = np.zeros(x.shape, dtype=complex), q.astype(float), x.copy()
    while deriv.size:
        acc += (P.polyval(0.5, deriv) * np.exp(-x) - P.polyval(-0.5, deriv)) / power
        deriv = P.polyder(deriv) if deriv.size > 1 else np.array([])
        power = power * x
    out[~small] = -acc
    return out


def test_smoother_transfer_same_floats_as_per_term_loop():
    from smoothshaper.reference.input_smoothers import _transfer
    rng = np.random.default_rng(5)
    for trial in range(300):
        q = rng.normal(size=int(rng.integers(1, 16)))
        n = int(rng.integers(0, 400))
        r = rng.uniform(0.0, (14.0, 60.0)[trial % 2], n)
        a = r * np.exp(1j * rng.uniform(-np.pi, np.pi, n))
        assert _transfer(q, a).tobytes() == _transfer_per_term(q, a).tobytes()


@pytest.mark.parametrize("kind", ["smooth_zv", "smooth_mzv", "smooth_ei", "smooth_ei2",
                                  "smooth_zvd_ei", "smooth_si"])
def test_smoother_kernel_same_floats_as_numpy_polynomials(kind):
    """The kernel's coefficients and area by Horner on floats equal NumPy's polyval/polyint."""
    from numpy.polynomial import polynomial as P
    from smoothshaper.reference import input_smoothers as ism
    from smoothshaper.stages import Stage
    rng = np.random.default_rng(9)
    for _ in range(100):
        stage = Stage(kind=kind, wn=float(rng.uniform(10.0, 3000.0)),
                      zeta=float(rng.uniform(0.0, 0.25)))
        z = ism._zeta(stage)
        if kind in ism._CUBIC:
            t, rows = ism._CUBIC[kind]
            q, span = np.array([P.polyval(z, r) for r in rows]), P.polyval(z, t)
        else:
            span, high_first = ism._CONSTANT[kind]
            q = np.array(high_first[::-1])
        area = P.polyval(0.5, P.polyint(q)) - P.polyval(-0.5, P.polyint(q))
        q_fast, T_fast = ism.smoother_kernel(stage)
        assert (q / area).tobytes() == q_fast.tobytes()
        assert span * 2.0 * math.pi / stage.wn == T_fast


@pytest.mark.parametrize("d", range(6))
def test_si_chebyshev_composition_same_floats_as_numpy_polynomials(d):
    """T_d of a line by series arithmetic equals NumPy's Chebyshev-of-Polynomial, bit for bit
    (the SI design's ripple polynomial)."""
    from numpy.polynomial import Chebyshev, Polynomial
    from smoothshaper.reference.shapers import _chebyshev_of_linear, _trimmed
    rng = np.random.default_rng(13)
    for k in range(500):
        line = np.array([0.0 if k % 50 == 0 else rng.normal() * 10 ** rng.uniform(-3, 3),
                         rng.normal() * 10 ** rng.uniform(-3, 3)])
        tol = float(rng.uniform(1e-3, 0.9))
        ref = (tol * Chebyshev.basis(d)(Polynomial(line))).coef
        got = _trimmed(np.convolve(np.array([tol]), _chebyshev_of_linear(d, line)))
        assert got.tobytes() == ref.tobytes()


def _taps_linear_polyval(q, T, Ts, L):
    """The linear-interpolation taps written with NumPy's polyval (the form the faster one
    must equal bit for bit)."""
    from numpy.polynomial import polynomial as P
    h = np.zeros(L)
    derivs = [q]
    while derivs[-1].size > 1:
        derivs.append(P.polyder(derivs[-1]))
    for k in range(int(math.ceil(T / Ts - 1e-12))):
        a, b = k * Ts, min((k + 1) * Ts, T)
        if b <= a:
            continue
        u0, du = a / T - 0.5, (b - a) / T
        whole = ramp = 0.0
        fact = 1.0
        for j, d in enumerate(derivs):
            pj = P.polyval(u0, d) / fact
            whole += pj * du ** (j + 1) / (j + 1)
            ramp += pj * du ** (j + 2) / (j + 2)
            fact *= j + 1
        ramp *= T / Ts
        h[k] += whole - ramp
        if k + 1 < L:
            h[k + 1] += ramp
    return h


@pytest.mark.parametrize("kind", ["smooth_zv", "smooth_mzv", "smooth_ei", "smooth_ei2",
                                  "smooth_zvd_ei", "smooth_si"])
def test_smoother_taps_same_floats_as_numpy_polyval(kind):
    from smoothshaper.reference import input_smoothers as ism
    from smoothshaper.stages import Stage
    rng = np.random.default_rng(11)
    for _ in range(10):
        stage = Stage(kind=kind, wn=float(rng.uniform(100.0, 3000.0)),
                      zeta=float(rng.uniform(0.0, 0.25)))
        q, T = ism.smoother_kernel(stage)
        Ts = float(rng.uniform(2e-5, 2e-4))
        L = int(math.ceil(T / Ts)) + 1
        assert ism._taps_linear(q, T, Ts, L).tobytes() == _taps_linear_polyval(q, T, Ts, L).tobytes()


def test_si_poly2cheb_same_floats_as_numpy():
    """The SI design's power-to-Chebyshev conversion equals NumPy's poly2cheb, bit for bit."""
    from smoothshaper.reference.shapers import _poly2cheb
    rng = np.random.default_rng(17)
    for k in range(500):
        n = int(rng.integers(1, 12))
        pol = rng.normal(size=n) * 10.0 ** rng.uniform(-6, 6, n)
        pol[rng.random(n) < 0.2] = 0.0          # exact zeros, trailing ones included
        if k % 97 == 0:
            pol[:] = 0.0
        ref = np.polynomial.chebyshev.poly2cheb(pol)
        assert _poly2cheb(pol).tobytes() == ref.tobytes(), pol
