# SPDX-License-Identifier: Apache-2.0
"""Validation plants (docs/analysis.md) as continuous state space, and their exact ZOH simulation.

Models (input: commanded position ``q_ref``):

* ``tracking_error(wn=, zeta=)``: one mode, ``E/Q_ref = -s^2/(s^2 + 2 zeta wn s + wn^2)``
  (seed 000 eq. 7);
* ``mode(wn=, zeta=)``: load position of one mode, ``(2 zeta wn s + wn^2)/(s^2 + 2 zeta wn s +
  wn^2)``; ``two_mass(J_l=, k_t=, b_t=)`` is this with ``wn = sqrt(k_t/J_l)``,
  ``zeta = b_t/(2 sqrt(k_t J_l))`` (seed 001 eq. 12, Table 1: wn = 260.4 rad/s);
* ``cartesian_axis(m=, d=, k=)``: ``m q'' + d q' + k q = d q_d' + k q_d`` (seed 003 Table I);
* ``series(p1, p2, ...)``: several modes in series (p1 acts first).

``simulate_varying_mode`` is one mode whose frequency changes from sample to sample (a
stiffness that depends on position), exact per sample for a held command.

``simulate_zoh`` is exact for a piecewise-constant input: ``x[n+1] = Ad x[n] + Bd u[n]`` with
``[[Ad, Bd], [0, I]] = expm([[A, B], [0, 0]] Ts)`` (no Euler steps).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm
from ._checks import (complex_array as _complex_array, finite as _finite,
                      finite_signal as _finite_signal, integer as _integer,
                      nonnegative as _nonnegative, positive as _positive, real_array as _real_array,
                      representable as _representable)
from .errors import ParameterError
from .reference._checks import check_samples

__all__ = ["Plant", "tracking_error", "mode", "two_mass", "cartesian_axis", "series", "rest_state",
           "zoh_matrices", "simulate_zoh", "residual_amplitude", "simulate_varying_mode",
           "oscillation_amplitude"]


@dataclass(frozen=True)
class Plant:
    """A single-input single-output linear plant ``x' = A x + B u``, ``y = C x + D u``.

    Attributes
    ----------
    A : ndarray of float64, shape (n, n)
        State matrix [1/s].
    B : ndarray of float64, shape (n,)
        Input vector.
    C : ndarray of float64, shape (n,)
        Output vector.
    D : float
        Feed-through.
    name : str
        What the model is (for reports).
    """
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: float
    name: str = ""

    def __post_init__(self):
        # A malformed model (text, NaN, a B of the wrong length) failed later inside
        # numpy.linalg or simulated NaN; refuse it here, naming the field.
        A = _real_array("A", self.A)
        if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] == 0:
            raise ParameterError("A", f"A must be a square matrix, got shape {A.shape}")
        n = A.shape[0]
        fields = {"A": A}
        for name in ("B", "C"):
            v = _real_array(name, getattr(self, name))
            if v.shape != (n,):
                raise ParameterError(name, f"{name} must have shape ({n},), got {v.shape}")
            fields[name] = v
        for name, v in fields.items():
            if not np.all(np.isfinite(v)):
                raise ParameterError(name, f"{name} must be finite")
            object.__setattr__(self, name, v)
        object.__setattr__(self, "D", _finite("D", self.D))

    @property
    def order(self) -> int:
        """The state dimension n."""
        return self.A.shape[0]

    def transfer(self, s) -> np.ndarray:
        """``G(s) = C (sI - A)^-1 B + D`` at complex ``s``.

        Parameters
        ----------
        s : array_like of complex
            Laplace variable [1/s], any shape (not a pole).

        Returns
        -------
        ndarray of complex128
            ``G(s)``, the shape of ``s``.

        Raises
        ------
        ParameterError
            Naming ``s`` when it is not finite numbers, or where ``G(s)`` is beyond the range
            of a float.
        numpy.linalg.LinAlgError
            ``s`` is a pole of the plant (``sI - A`` is singular).
        """
        s = _complex_array("s", s)
        eye = np.eye(self.order)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            flat = [self.C @ np.linalg.solve(v * eye - self.A, self.B) + self.D
                    for v in s.ravel()]
        return _representable("s", np.array(flat, dtype=complex).reshape(s.shape), "G(s)")

    def poles(self) -> np.ndarray:
        """The eigenvalues of ``A``.

        Returns
        -------
        ndarray of complex128, shape (n,)
            The poles [1/s].
        """
        return np.linalg.eigvals(self.A)


def _second_order(b1: float, b0: float, a1: float, a0: float, D: float, name: str,
                  parameter: str) -> Plant:
    """D + (b1 s + b0)/(s^2 + a1 s + a0) in controllable canonical form; ParameterError naming
    ``parameter`` when a coefficient is beyond the range of a float."""
    if not all(math.isfinite(c) for c in (b1, b0, a1, a0)):
        raise ParameterError(parameter, f"{parameter}: the model's coefficients (b1, b0, a1, a0) = "
                             f"({b1!r}, {b0!r}, {a1!r}, {a0!r}) are beyond the range of a float")
    A = np.array([[0.0, 1.0], [-a0, -a1]])
    return Plant(A, np.array([0.0, 1.0]), np.array([b0, b1]), float(D), name)


def _check_plant(plant, parameter: str = "plant") -> "Plant":
    if not isinstance(plant, Plant):
        raise ParameterError(parameter, f"{parameter} must be a smoothshaper.plants.Plant, got "
                             f"{type(plant).__name__}")
    return plant


def _mode_args(wn, zeta) -> tuple[float, float]:
    wn = _positive("wn", wn)
    zeta = _nonnegative("zeta", zeta)
    if zeta >= 1:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    return wn, zeta


def tracking_error(*, wn: float, zeta: float = 0.0) -> Plant:
    """Tracking error of one mode, ``e/q = -s^2/(s^2 + 2 zeta wn s + wn^2)``: load position
    minus command for the command ``q`` (the error plotted by Biagiotti, Melchiorri and
    Moriello, "Damped Harmonic Smoother for Trajectory Planning and Vibration Suppression",
    2020, Fig. 6-8).

    Parameters
    ----------
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1) (default 0).

    Returns
    -------
    Plant
        The state-space model (second order, controllable canonical form).

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``zeta``.
    """
    wn, zeta = _mode_args(wn, zeta)
    return _second_order(2 * zeta * wn, wn * wn, 2 * zeta * wn, wn * wn, -1.0, "tracking_error",
                         "wn")


def mode(*, wn: float, zeta: float = 0.0) -> Plant:
    """Load position of one mode, ``(2 zeta wn s + wn^2)/(s^2 + 2 zeta wn s + wn^2)`` (a mass on
    a spring and damper driven at its base; unit DC gain).

    Parameters
    ----------
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1) (default 0).

    Returns
    -------
    Plant
        The state-space model (second order, controllable canonical form).

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``zeta``.
    """
    wn, zeta = _mode_args(wn, zeta)
    return _second_order(2 * zeta * wn, wn * wn, 2 * zeta * wn, wn * wn, 0.0, "mode", "wn")


def two_mass(*, J_l: float, k_t: float, b_t: float) -> Plant:
    """Elastic transmission from motor to load position, ``G_ml`` of Biagiotti and Melchiorri,
    "Online Planning of Multi-Segment Trajectories with Trigonometric Blends", 2011, eq. 12:
    ``wn = sqrt(k_t/J_l)``, ``zeta = b_t / (2 sqrt(k_t J_l))``.

    Parameters
    ----------
    J_l : float, keyword-only
        Load inertia [kg m^2], > 0.
    k_t : float, keyword-only
        Torsional stiffness [N m/rad], > 0.
    b_t : float, keyword-only
        Torsional damping [N m s/rad], >= 0, giving an underdamped mode.

    Returns
    -------
    Plant
        The state-space model (second order, controllable canonical form).

    Raises
    ------
    ParameterError
        Naming ``J_l``, ``k_t`` or ``b_t`` (also when the mode would not be underdamped).
    """
    J_l, k_t = _positive("J_l", J_l), _positive("k_t", k_t)
    b_t = _nonnegative("b_t", b_t)
    zeta = b_t / (2.0 * math.sqrt(k_t * J_l))
    if zeta >= 1:
        raise ParameterError(
            "b_t", f"b_t must give an underdamped mode (zeta < 1), got zeta = {zeta!r}")
    p = mode(wn=math.sqrt(k_t / J_l), zeta=zeta)
    return Plant(p.A, p.B, p.C, p.D, "two_mass")


def cartesian_axis(*, m: float, d: float, k: float) -> Plant:
    """One axis of a Cartesian robot, ``(d s + k)/(m s^2 + d s + k)`` (Biagiotti and
    Melchiorri, "Input Shaping via B-spline Filters for 3-D Trajectory Planning", 2011).

    Parameters
    ----------
    m : float, keyword-only
        Moving mass [kg], > 0.
    d : float, keyword-only
        Damping [N s/m], >= 0.
    k : float, keyword-only
        Stiffness [N/m], > 0.

    Returns
    -------
    Plant
        The state-space model (second order, controllable canonical form).

    Raises
    ------
    ParameterError
        Naming ``m``, ``d`` or ``k``.
    """
    m, k = _positive("m", m), _positive("k", k)
    d = _nonnegative("d", d)
    return _second_order(d / m, k / m, d / m, k / m, 0.0, "cartesian_axis", "m")


def series(*plants: Plant) -> Plant:
    """Plants in series, ``plants[0]`` first: ``G = G_last ... G_0``.

    Parameters
    ----------
    *plants : Plant
        At least one plant.

    Returns
    -------
    Plant
        The series connection (order: the sum of the orders).

    Raises
    ------
    ParameterError
        Naming ``plants`` when none is given or one is not a Plant.
    """
    if not plants:
        raise ParameterError("plants", "plants must hold at least one Plant")
    for p in plants:
        _check_plant(p, "plants")
    out = plants[0]
    for nxt in plants[1:]:
        n1, n2 = out.order, nxt.order
        A = np.block([[out.A, np.zeros((n1, n2))], [np.outer(nxt.B, out.C), nxt.A]])
        B = np.concatenate([out.B, nxt.B * out.D])
        C = np.concatenate([nxt.D * out.C, nxt.C])
        out = Plant(A, B, C, nxt.D * out.D, "series")
    return out


def rest_state(plant: Plant, u0: float) -> np.ndarray:
    """Equilibrium state for a constant input: ``A x + B u0 = 0``.

    Parameters
    ----------
    plant : Plant
        A plant with a non-singular ``A`` (no integrator).
    u0 : float
        The constant input.

    Returns
    -------
    ndarray of float64, shape (n,)
        The rest state ``x``.

    Raises
    ------
    ParameterError
        Naming ``plant`` when it is not a Plant.
    numpy.linalg.LinAlgError
        ``A`` is singular.
    """
    plant = _check_plant(plant)
    u0 = _finite("u0", u0)
    with np.errstate(over="ignore", invalid="ignore"):
        x = -np.linalg.solve(plant.A, plant.B * u0)
    return _representable("u0", x, "the rest state")


def zoh_matrices(plant: Plant, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """``(Ad, Bd)`` of the exact zero-order-hold discretisation, from the matrix exponential of
    ``[[A, B], [0, 0]] Ts``.

    Parameters
    ----------
    plant : Plant
        The plant.
    Ts : float
        Sample period [s], > 0.

    Returns
    -------
    Ad : ndarray of float64, shape (n, n)
        ``e^(A Ts)``.
    Bd : ndarray of float64, shape (n,)
        ``int_0^Ts e^(A t) dt B``.

    Raises
    ------
    ParameterError
        Naming ``plant`` or ``Ts``.
    """
    plant = _check_plant(plant)
    Ts = _positive("Ts", Ts)
    n = plant.order
    M = np.zeros((n + 1, n + 1))
    M[:n, :n] = plant.A
    M[:n, n] = plant.B
    with np.errstate(over="ignore", invalid="ignore"):
        E = expm(M * Ts)
    _representable("Ts", E, "e^(A Ts)")
    return E[:n, :n], E[:n, n]


def simulate_zoh(plant: Plant, u, *, Ts: float, x0=None, oversample: int = 1):
    """Response of the plant to the command ``u[n]`` held over ``[n Ts, (n+1) Ts)``, exact up to
    rounding (zero-order-hold discretisation).

    Parameters
    ----------
    plant : Plant
        The plant.
    u : array_like of float, shape (N,)
        The command, finite.
    Ts : float, keyword-only
        Sample period of the command [s], > 0.
    x0 : array_like of float, shape (n,), keyword-only
        Initial state (default 0).
    oversample : int, keyword-only
        Output points per command sample (>= 1, default 1).

    Returns
    -------
    t : ndarray of float64, shape (N * oversample,)
        Times ``j Ts / oversample`` [s].
    y : ndarray of float64, shape (N * oversample,)
        The output ``C x(t) + D u`` at those times.

    Raises
    ------
    ParameterError
        Naming ``plant``, ``u``, ``Ts``, ``x0`` (wrong shape) or ``oversample``.
    """
    plant = _check_plant(plant)
    u = _finite_signal("u", u)
    m = _integer("oversample", oversample, 1)
    check_samples("oversample", u.size * m, "the simulated output")
    Ts = _positive("Ts", Ts)
    h = Ts / m
    Ad, Bd = zoh_matrices(plant, h)
    x = np.zeros(plant.order) if x0 is None else _real_array("x0", x0).copy()
    if x.shape != (plant.order,):
        raise ParameterError("x0", f"x0 must have shape ({plant.order},), got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ParameterError("x0", "x0 must be finite")
    uu = np.repeat(u, m)
    y = np.empty(uu.size)
    C, D = plant.C, plant.D
    for j, uj in enumerate(uu):
        y[j] = C @ x + D * uj
        x = Ad @ x + Bd * uj
    return np.arange(uu.size) * h, y


def residual_amplitude(t, y, *, wn: float, zeta: float = 0.0, t_start: float) -> float:
    """Amplitude of the mode's oscillation in ``y`` after ``t_start``, referred to t = 0.

    Least-squares fit of ``y = c + e^(sigma t) (a cos(wd t) + b sin(wd t))`` on
    ``t >= t_start`` (``sigma = -zeta wn``, ``wd = wn sqrt(1 - zeta^2)``). The ratio of this
    for a filtered and an unfiltered step is the residual vibration ``|H(p)|`` of the filter
    (:func:`smoothshaper.analysis.residual_vibration`).

    Parameters
    ----------
    t : array_like of float, shape (N,)
        Times [s].
    y : array_like of float, shape (N,)
        The response at those times.
    wn : float, keyword-only
        Natural frequency of the mode [rad/s], > 0.
    zeta : float, keyword-only
        Its damping ratio, in [0, 1) (default 0).
    t_start : float, keyword-only
        Start of the fit [s] (after the command has settled).

    Returns
    -------
    float
        ``hypot(a, b)`` [units of y].

    Raises
    ------
    ParameterError
        Naming ``wn``, ``zeta``, ``t``, ``y`` or ``t_start`` (fewer than 8 samples left).
    """
    wn, zeta = _mode_args(wn, zeta)
    t = _finite_signal("t", t)
    y = _finite_signal("y", y)
    if y.shape != t.shape:
        raise ParameterError("y", f"y must have the shape of t {t.shape}, got {y.shape}")
    t_start = _finite("t_start", t_start)
    keep = t >= t_start
    if keep.sum() < 8:
        raise ParameterError("t_start", "t_start leaves fewer than 8 samples to fit")
    tk = t[keep]
    sigma, wd = -zeta * wn, wn * math.sqrt(1 - zeta * zeta)
    env = np.exp(sigma * tk)
    X = np.column_stack([np.ones_like(tk), env * np.cos(wd * tk), env * np.sin(wd * tk)])
    coef = np.linalg.lstsq(X, y[keep], rcond=None)[0]
    return float(math.hypot(coef[1], coef[2]))


def simulate_varying_mode(u, *, wn, zeta: float, Ts: float, x0=None) -> tuple[np.ndarray, np.ndarray]:
    """Load of one mode whose natural frequency changes from sample to sample (a stiffness
    that depends on where the machine is), exact for a command held over each sample.

    ``x'' = -wn[n]^2 (x - u[n]) - 2 zeta wn[n] x'`` on ``[n Ts, (n+1) Ts)``: within a sample
    the mode is fixed, so each step is the exact zero-order-hold transition of that sample's
    mode (a damped rotation about the held command); the frequency ``wn[n]`` is the caller's,
    e.g. the stiffness at the commanded position ``u[n]``.

    Parameters
    ----------
    u : array_like of float, shape (N,)
        The command, finite.
    wn : array_like of float, shape (N,)
        The natural frequency in each sample [rad/s], > 0.
    zeta : float, keyword-only
        The damping ratio, in [0, 1).
    Ts : float, keyword-only
        Sample period [s], > 0.
    x0 : (float, float) or None, keyword-only
        Initial position and velocity (default: at rest at ``u[0]``).

    Returns
    -------
    x, v : ndarray of float64, shape (N + 1,)
        Position and velocity at ``n Ts``, ``n = 0 .. N``.

    Raises
    ------
    ParameterError
        Naming ``u``, ``wn`` (shape, not > 0), ``zeta``, ``Ts`` or ``x0``.
    """
    u = _finite_signal("u", u)
    w = np.asarray(_real_array("wn", wn), dtype=np.float64)
    if w.shape != u.shape or not np.all(w > 0) or not np.all(np.isfinite(w)):
        raise ParameterError("wn", f"wn must be finite, > 0 and of the shape of u {u.shape}")
    _mode_args(float(w[0]) if w.size else 1.0, zeta)
    Ts = _positive("Ts", Ts)
    pos, vel = (float(u[0]) if u.size else 0.0, 0.0) if x0 is None else (
        _finite("x0", x0[0]), _finite("x0", x0[1]))
    wd = w * math.sqrt(1.0 - zeta * zeta)
    s = zeta * w
    e = np.exp(-s * Ts)
    c, sn = np.cos(wd * Ts), np.sin(wd * Ts)
    xs, vs = np.empty(u.size + 1), np.empty(u.size + 1)
    xs[0], vs[0] = pos, vel
    for n in range(u.size):
        d = pos - u[n]
        pos, vel = (u[n] + e[n] * (d * (c[n] + s[n] / wd[n] * sn[n]) + vel * sn[n] / wd[n]),
                    e[n] * (vel * (c[n] - s[n] / wd[n] * sn[n]) - d * w[n] * w[n] / wd[n] * sn[n]))
        xs[n + 1], vs[n + 1] = pos, vel
    return xs, vs


def oscillation_amplitude(x: float, v: float, *, rest: float, wn: float, zeta: float = 0.0) -> float:
    """Amplitude of the free oscillation of one mode about ``rest`` from position ``x`` and
    velocity ``v``: ``hypot(x - rest, (v + zeta wn (x - rest))/wd)``.

    Parameters
    ----------
    x, v : float
        Position and velocity.
    rest : float, keyword-only
        The equilibrium.
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1).

    Returns
    -------
    float
        The amplitude of ``e^{-zeta wn t}(a cos wd t + b sin wd t)`` at ``t = 0``.

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``zeta``.
    """
    wn, zeta = _mode_args(wn, zeta)
    wd = wn * math.sqrt(1.0 - zeta * zeta)
    d = float(x) - float(rest)
    return math.hypot(d, (float(v) + zeta * wn * d) / wd)
