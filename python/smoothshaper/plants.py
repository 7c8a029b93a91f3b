"""Validation plants (docs/analysis.md) as continuous state space, and their exact ZOH simulation.

Models (input: commanded position ``q_ref``):

* ``tracking_error(wn=, zeta=)``: one mode, ``E/Q_ref = -s^2/(s^2 + 2 zeta wn s + wn^2)``
  (seed 000 eq. 7);
* ``mode(wn=, zeta=)``: load position of one mode, ``(2 zeta wn s + wn^2)/(s^2 + 2 zeta wn s +
  wn^2)``; ``two_mass(J_l=, k_t=, b_t=)`` is this with ``wn = sqrt(k_t/J_l)``,
  ``zeta = b_t/(2 sqrt(k_t J_l))`` (seed 001 eq. 12, Table 1: wn = 260.4 rad/s);
* ``cartesian_axis(m=, d=, k=)``: ``m q'' + d q' + k q = d q_d' + k q_d`` (seed 003 Table I);
* ``series(p1, p2, ...)``: several modes in series (p1 acts first).

``simulate_zoh`` is exact for a piecewise-constant input: ``x[n+1] = Ad x[n] + Bd u[n]`` with
``[[Ad, Bd], [0, I]] = expm([[A, B], [0, 0]] Ts)`` (no Euler steps).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm
from ._checks import (finite_signal as _finite_signal, integer as _integer,
                      nonnegative as _nonnegative, positive as _positive, real_array as _real_array)
from .errors import ParameterError

__all__ = ["Plant", "tracking_error", "mode", "two_mass", "cartesian_axis", "series", "rest_state",
           "zoh_matrices", "simulate_zoh", "residual_amplitude"]


@dataclass(frozen=True)
class Plant:
    """``x' = A x + B u``, ``y = C x + D u`` (single input, single output)."""
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: float
    name: str = ""

    @property
    def order(self) -> int:
        return self.A.shape[0]

    def transfer(self, s) -> np.ndarray:
        """``C (sI - A)^-1 B + D`` at complex ``s`` (any shape)."""
        s = np.asarray(s, dtype=complex)
        eye = np.eye(self.order)
        flat = [self.C @ np.linalg.solve(v * eye - self.A, self.B) + self.D for v in s.ravel()]
        return np.array(flat, dtype=complex).reshape(s.shape)

    def poles(self) -> np.ndarray:
        return np.linalg.eigvals(self.A)


def _second_order(b1: float, b0: float, a1: float, a0: float, D: float, name: str) -> Plant:
    """D + (b1 s + b0)/(s^2 + a1 s + a0) in controllable canonical form."""
    A = np.array([[0.0, 1.0], [-a0, -a1]])
    return Plant(A, np.array([0.0, 1.0]), np.array([b0, b1]), float(D), name)


def _mode_args(wn, zeta) -> tuple[float, float]:
    wn = _positive("wn", wn)
    zeta = _nonnegative("zeta", zeta)
    if zeta >= 1:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    return wn, zeta


def tracking_error(*, wn: float, zeta: float = 0.0) -> Plant:
    """``-s^2/(s^2 + 2 zeta wn s + wn^2) = -1 + (2 zeta wn s + wn^2)/(...)``."""
    wn, zeta = _mode_args(wn, zeta)
    return _second_order(2 * zeta * wn, wn * wn, 2 * zeta * wn, wn * wn, -1.0, "tracking_error")


def mode(*, wn: float, zeta: float = 0.0) -> Plant:
    """``(2 zeta wn s + wn^2)/(s^2 + 2 zeta wn s + wn^2)``: load position of one mode."""
    wn, zeta = _mode_args(wn, zeta)
    return _second_order(2 * zeta * wn, wn * wn, 2 * zeta * wn, wn * wn, 0.0, "mode")


def two_mass(*, J_l: float, k_t: float, b_t: float) -> Plant:
    """Elastic transmission G_ml (seed 001 eq. 12): load inertia ``J_l`` [kg m^2], torsional
    stiffness ``k_t`` [N m/rad], damping ``b_t`` [N m s/rad]; must be underdamped."""
    J_l, k_t = _positive("J_l", J_l), _positive("k_t", k_t)
    b_t = _nonnegative("b_t", b_t)
    zeta = b_t / (2.0 * math.sqrt(k_t * J_l))
    if zeta >= 1:
        raise ParameterError(
            "b_t", f"b_t must give an underdamped mode (zeta < 1), got zeta = {zeta!r}")
    p = mode(wn=math.sqrt(k_t / J_l), zeta=zeta)
    return Plant(p.A, p.B, p.C, p.D, "two_mass")


def cartesian_axis(*, m: float, d: float, k: float) -> Plant:
    """One robot axis, ``(d s + k)/(m s^2 + d s + k)`` (seed 003)."""
    m, k = _positive("m", m), _positive("k", k)
    d = _nonnegative("d", d)
    return _second_order(d / m, k / m, d / m, k / m, 0.0, "cartesian_axis")


def series(*plants: Plant) -> Plant:
    """The plants in series, ``plants[0]`` first: ``G = G_last ... G_0``."""
    if not plants:
        raise ParameterError("plants", "plants must hold at least one Plant")
    out = plants[0]
    for nxt in plants[1:]:
        n1, n2 = out.order, nxt.order
        A = np.block([[out.A, np.zeros((n1, n2))], [np.outer(nxt.B, out.C), nxt.A]])
        B = np.concatenate([out.B, nxt.B * out.D])
        C = np.concatenate([nxt.D * out.C, nxt.C])
        out = Plant(A, B, C, nxt.D * out.D, "series")
    return out


def rest_state(plant: Plant, u0: float) -> np.ndarray:
    """Equilibrium ``x`` for the constant input ``u0`` (``A x + B u0 = 0``)."""
    return -np.linalg.solve(plant.A, plant.B * float(u0))


def zoh_matrices(plant: Plant, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """``(Ad, Bd)`` of the exact zero-order-hold discretisation."""
    Ts = _positive("Ts", Ts)
    n = plant.order
    M = np.zeros((n + 1, n + 1))
    M[:n, :n] = plant.A
    M[:n, n] = plant.B
    E = expm(M * Ts)
    return E[:n, :n], E[:n, n]


def simulate_zoh(plant: Plant, u, *, Ts: float, x0=None, oversample: int = 1):
    """Response to ``u[n]`` held over ``[n Ts, (n+1) Ts)``.

    Returns ``(t, y)`` with ``y`` at ``t = j Ts/oversample``, ``j = 0 .. len(u)*oversample - 1``
    (``y = C x(t) + D u``), exact up to rounding. ``x0`` is the initial state (default 0).
    """
    u = _finite_signal("u", u)
    m = _integer("oversample", oversample, 1)
    Ts = _positive("Ts", Ts)
    h = Ts / m
    Ad, Bd = zoh_matrices(plant, h)
    x = np.zeros(plant.order) if x0 is None else _real_array("x0", x0).copy()
    if x.shape != (plant.order,):
        raise ParameterError("x0", f"x0 must have shape ({plant.order},), got {x.shape}")
    uu = np.repeat(u, m)
    y = np.empty(uu.size)
    C, D = plant.C, plant.D
    for j, uj in enumerate(uu):
        y[j] = C @ x + D * uj
        x = Ad @ x + Bd * uj
    return np.arange(uu.size) * h, y


def residual_amplitude(t, y, *, wn: float, zeta: float = 0.0, t_start: float) -> float:
    """Amplitude of the mode's oscillation in ``y`` after ``t_start``, referred to t = 0.

    Least-squares fit of ``y = c + e^{sigma t} (a cos(wd t) + b sin(wd t))`` on
    ``t >= t_start`` (sigma = -zeta wn, wd = wn sqrt(1 - zeta^2)); returns ``hypot(a, b)``.
    The ratio of this for a filtered and an unfiltered step is the residual vibration
    ``|H(p)|`` of the filter (``analysis.residual_vibration``).
    """
    wn, zeta = _mode_args(wn, zeta)
    t = _real_array("t", t)
    y = _real_array("y", y)
    keep = t >= t_start
    if keep.sum() < 8:
        raise ParameterError("t_start", "t_start leaves fewer than 8 samples to fit")
    tk = t[keep]
    sigma, wd = -zeta * wn, wn * math.sqrt(1 - zeta * zeta)
    env = np.exp(sigma * tk)
    X = np.column_stack([np.ones_like(tk), env * np.cos(wd * tk), env * np.sin(wd * tk)])
    coef = np.linalg.lstsq(X, y[keep], rcond=None)[0]
    return float(math.hypot(coef[1], coef[2]))
