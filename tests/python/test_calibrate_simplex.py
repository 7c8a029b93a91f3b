# SPDX-License-Identifier: Apache-2.0
"""The tuning's Nelder-Mead search steps as SciPy's does: the same points asked in the same
order and the same result, bit for bit, so replacing it changed no recommendation."""
import math

import numpy as np
import pytest

from smoothshaper.calibrate.candidates import _nelder_mead

minimize = pytest.importorskip("scipy.optimize").minimize


def _cost(kind, c, w):
    def f(x):
        if kind == "quadratic":
            return float(np.sum(w * (x - c) ** 2))
        if kind == "rosenbrock":
            return float(100 * (x[1] - x[0] ** 2) ** 2 + (1 - x[0]) ** 2 + np.sum(x[2:] ** 2))
        if kind == "plateau":          # ties and a penalty wall, as the tuning's costs have
            v = float(np.sum(np.abs(x - c)))
            return 1e3 if v > 2 else round(v, 2)
        return float(np.sum(w * np.abs(x - c) ** 1.5) + 0.1 * math.sin(5 * x[0]))
    return f


@pytest.mark.parametrize("kind", ["quadratic", "rosenbrock", "plateau", "rough"])
@pytest.mark.parametrize("xatol", [1e-8, 1e-4, 1e-3])
def test_same_steps_as_scipy(kind, xatol):
    rng = np.random.default_rng(11)
    for _ in range(25):
        n = int(rng.integers(2, 6))
        f = _cost(kind, rng.normal(size=n), rng.uniform(0.1, 3.0, n))
        x0, steps = rng.normal(size=n), rng.uniform(0.01, 0.5, n)
        simplex = np.array([x0] + [x0 + np.eye(n)[j] * steps[j] for j in range(n)])
        asked_ref, asked = [], []
        ref = minimize(lambda x: asked_ref.append(x.copy()) or f(x), x0, method="Nelder-Mead",
                       options={"initial_simplex": simplex, "xatol": xatol, "fatol": 1e-4,
                                "maxiter": 30 * n})
        x, fx = _nelder_mead(lambda x: asked.append(x.copy()) or f(x), simplex, xatol=xatol,
                             fatol=1e-4, maxiter=30 * n)
        assert len(asked) == len(asked_ref) == ref.nfev
        for a, b in zip(asked, asked_ref):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(x, ref.x)
        assert fx == float(ref.fun)


def test_stops_at_tolerance_and_iterations():
    """A quadratic bowl: the result within xatol of the minimum, and a one-iteration budget
    asks only the simplex's own points."""
    c = np.array([0.3, -0.2])
    f = _cost("quadratic", c, np.ones(2))
    simplex = np.array([[1.0, 1.0], [1.5, 1.0], [1.0, 1.5]])
    x, fx = _nelder_mead(f, simplex, xatol=1e-9, fatol=1e-14, maxiter=10_000)
    assert np.max(np.abs(x - c)) < 1e-8 and fx < 1e-15
    asked = []
    x, fx = _nelder_mead(lambda v: asked.append(v) or f(v), simplex, xatol=0.0, fatol=0.0,
                         maxiter=1)
    assert len(asked) == 3 and fx == min(f(p) for p in simplex)
