# SPDX-License-Identifier: Apache-2.0
"""The discrete controllers of the servo testbed, each one step of a sampled drive.

A controller reads, at sample ``k``, the motor-side position reference ``r[k]`` (``n q_l^d``)
and the measurements ``q_m[k]`` (motor encoder) and ``q_m'[k]`` (the drive's velocity; only the
P/PI cascade and the TDO read it), and returns the torque ``u[k]`` held until ``k + 1``. Every
step is linear in (state, r, q_m, q_m'), so :mod:`.loop` reads off its matrices and closes the
loop around the plant exactly. The configurations (:class:`PID`, :class:`TDO`,
:class:`PolePlacement`, :class:`LQG`) hold the tuning; :func:`build` turns one into the step.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .. import stages as _stages
from .._checks import choice as _choice, positive as _positive
from ..errors import ParameterError
from ..reference.notch import notch_coefficients
from . import design
from .plant import DiscretePlant

__all__ = ["PID", "TDO", "PolePlacement", "LQG", "Controller", "build"]


@dataclass(frozen=True)
class TDO:
    """Torque disturbance observer with ``Q(s) = 1/(1 + s Tf)`` on ``P_n = 1/(Jn s + Dn)``.

    Attributes
    ----------
    Tf : float
        Time constant of ``Q`` [s], > 0.
    Jn, Dn : float or None
        Nominal inertia [kg m^2] and friction [N m s/rad]; None: the motor's ``J_m``, ``D_m``
        (the notes' rigid nominal model).
    """
    Tf: float
    Jn: float | None = None
    Dn: float | None = None


@dataclass(frozen=True)
class PID:
    """P/PI cascade with velocity feed-forward (the notes' "PID control").

    ``v* = K_pp (r - q_m) + (r[k] - r[k-1])/Ts``, ``u = K_pv (e + (1/T_Iv) sum e Ts)`` with
    ``e = v* - q_m'`` (:func:`.design.pid_gains`). ``J`` is the inertia the velocity gain is
    sized for (default ``J_m + J_l/n^2``, or ``J_m`` behind a TDO). ``notch`` (a library notch
    stage) filters the PI output (``notch_at="loop"``) or the velocity reference
    (``"reference"``); ``tdo`` adds the torque disturbance observer.

    Attributes
    ----------
    wcv, wcp : float
        Velocity and position loop crossover [rad/s].
    Ti : float
        Velocity integral time [s].
    J : float or None
        Inertia for the velocity gain [kg m^2].
    notch : Stage or None
        A notch stage (``smoothshaper.notch``), run as its reference biquad.
    notch_at : {"loop", "reference"}
    tdo : TDO or None
    """
    wcv: float
    Ti: float
    wcp: float
    J: float | None = None
    notch: _stages.Stage | None = None
    notch_at: str = "loop"
    tdo: TDO | None = None


@dataclass(frozen=True)
class PolePlacement:
    """Observer-based pole placement with integral action and the notes' feed-forward.

    ``poles``: ``nx + 1`` continuous closed-loop poles [1/s] of the integral-action model;
    ``observer_poles``: ``nx`` poles of ``A + L C``; ``wf``: bandwidth of the reference model
    ``F^o(s) = wf^3/(s + wf)^3`` [rad/s] (None: no feed-forward, the integrator tracks ``r``).

    Attributes
    ----------
    poles : sequence of complex
        Closed-loop poles [1/s].
    observer_poles : sequence of complex
        Observer poles [1/s].
    wf : float or None
        Reference model bandwidth [rad/s].
    """
    poles: tuple
    observer_poles: tuple
    wf: float | None = None


@dataclass(frozen=True)
class LQG:
    """LQ state feedback with integral action and a steady-state Kalman predictor.

    ``Q`` (``nx + 1`` diagonal weights or a matrix) and ``R`` weight ``z' Q z + R u^2``
    (:func:`.design.lq_gain`); the noise standard deviations set the Kalman filter
    (:func:`.design.kalman_gain`); ``wf`` as :class:`PolePlacement`.

    Attributes
    ----------
    Q : sequence of float or array
        State weight of ``[q_m, q_m', n q_l, n q_l', x_I]``.
    R : float
        Torque weight [1/(N m)^2].
    torque_noise, load_torque_noise : float
        Torque noise standard deviations [N m] (motor, load side).
    encoder_noise : float
        Encoder noise standard deviation [rad].
    wf : float or None
        Reference model bandwidth [rad/s].
    """
    Q: tuple
    R: float
    torque_noise: float
    load_torque_noise: float
    encoder_noise: float
    wf: float | None = None


@dataclass
class Controller:
    """A built controller.

    Attributes
    ----------
    kind : str
        ``"pid"``, ``"pid+tdo"``, ``"pole placement"`` or ``"lqg"``.
    n_states : int
        Length of its state vector.
    step : callable
        ``step(state, r, qm, wm) -> (state, u)``: one sample (``r`` motor side [rad], ``u``
        [N m]).
    gains : dict
        The design's numbers (gains, filter coefficients, the reference model).
    """
    kind: str
    n_states: int
    step: Callable
    gains: dict = field(default_factory=dict)


def build(config, dp: DiscretePlant) -> Controller:
    """The discrete controller for ``config`` on the sampled plant ``dp``.

    Parameters
    ----------
    config : PID, PolePlacement or LQG
        The tuning.
    dp : DiscretePlant
        The sampled plant.

    Returns
    -------
    Controller

    Raises
    ------
    ParameterError
        Naming ``controller`` for an unknown configuration, or the tuning parameter at fault.
    """
    if isinstance(config, PID):
        return _pid(config, dp)
    if isinstance(config, (PolePlacement, LQG)):
        return _state_feedback(config, dp)
    raise ParameterError("controller", "controller must be a PID, PolePlacement or LQG "
                         f"configuration, got {type(config).__name__}")


def _pid(c: PID, dp: DiscretePlant) -> Controller:
    p, Ts = dp.plant.params, dp.Ts
    if c.tdo is not None and not isinstance(c.tdo, TDO):
        raise ParameterError("tdo", f"tdo must be a TDO or None, got {type(c.tdo).__name__}")
    Jdefault = p["Jm"] if c.tdo is not None else p["Jm"] + p["Jl"] / p["n"] ** 2
    g = design.pid_gains(J=Jdefault if c.J is None else c.J, wcv=c.wcv, Ti=c.Ti, wcp=c.wcp)
    Kpv, Kpp, ki = g["Kpv"], g["Kpp"], g["Kpv"] * Ts / g["Ti"]
    nb = na = None
    at = _choice("notch_at", c.notch_at, ("loop", "reference"))
    if c.notch is not None:
        if not isinstance(c.notch, _stages.Stage) or not c.notch.kind.startswith("notch"):
            raise ParameterError("notch", "notch must be a notch stage (smoothshaper.notch)")
        nb, na = notch_coefficients(c.notch, Ts=Ts)
        g.update(notch_b=nb, notch_a=na)
    tdo = None
    if c.tdo is not None:
        tdo = design.tdo_coefficients(Jn=p["Jm"] if c.tdo.Jn is None else c.tdo.Jn,
                                      Dn=p["Dm"] if c.tdo.Dn is None else c.tdo.Dn,
                                      Tf=c.tdo.Tf, Ts=Ts)
        g.update(tdo)
    # State: [r_prev, I, notch s1, notch s2, tdo d, tdo u_prev, tdo w_prev].
    inv_ts = 1.0 / Ts

    def step(s, r, qm, wm):
        s = np.array(s, dtype=float)
        out = np.zeros_like(s)
        vref = Kpp * (r - qm) + (r - s[0]) * inv_ts
        if nb is not None and at == "reference":
            vref, out[2], out[3] = _biquad(nb, na, vref, s[2], s[3])
        e = vref - wm
        u = Kpv * e + s[1]
        out[0], out[1] = r, s[1] + ki * e
        if nb is not None and at == "loop":
            u, out[2], out[3] = _biquad(nb, na, u, s[2], s[3])
        if tdo is not None:
            a, b, al = tdo["a"], tdo["b"], tdo["alpha"]
            d = al * s[4] + (1.0 - al) * (s[5] - (wm - a * s[6]) / b)
            u = u + d
            out[4], out[5], out[6] = d, u, wm
        return out, u

    return Controller("pid" if tdo is None else "pid+tdo", 7, step, g)


def _biquad(b, a, x, s1, s2):
    """Transposed direct form II, ``a[0] = 1``: returns (y, s1', s2')."""
    y = b[0] * x + s1
    return y, b[1] * x - a[1] * y + s2, b[2] * x - a[2] * y


def _state_feedback(c, dp: DiscretePlant) -> Controller:
    nx, Ts = dp.Ad.shape[0], dp.Ts
    if isinstance(c, PolePlacement):
        g = design.place(dp, poles=c.poles, observer_poles=c.observer_poles)
        kind = "pole placement"
    else:
        g = design.lq_gain(dp, Q=c.Q, R=c.R)
        g.update(design.kalman_gain(dp, torque_noise=c.torque_noise,
                                    load_torque_noise=c.load_torque_noise,
                                    encoder_noise=c.encoder_noise))
        kind = "lqg"
    K, kI, L = g["K"], g["kI"], g["L"]
    ref = None if c.wf is None else design.reference_model(dp.plant, wf=_positive("wf", c.wf),
                                                           Ts=Ts)
    m = 0 if ref is None else ref.Phi.shape[0]
    g["reference_model"] = ref
    Ad, Bu = dp.Ad, dp.Bu
    # State: [x~ (nx), x_I, xi (m)].

    def step(s, r, qm, wm):
        s = np.asarray(s, dtype=float)
        xt, xI, xi = s[:nx], s[nx], s[nx + 1:]
        if ref is None:
            xd, ud, ybar = np.zeros(nx), 0.0, r
        else:
            xd, ud = ref.M @ xi, ref.N @ xi + ref.N0 * r
            ybar = xd[0]
        u = ud + K @ (xt - xd) + kI * xI
        out = np.empty_like(s)
        out[:nx] = Ad @ xt + Bu * u + L * (xt[0] - qm)
        out[nx] = xI + Ts * (ybar - qm)
        if ref is not None:
            out[nx + 1:] = ref.Phi @ xi + ref.Gam * r
        return out, u

    return Controller(kind, nx + 1 + m, step, g)
