# SPDX-License-Identifier: Apache-2.0
"""The tunings the report and the docs use for the notes' servo.

The notes give the P/PI rules of their notch example in normalised form (``T_Iv = 10/w_z``,
``w_cv = 1``, ``w_cp = 0.1`` in units of the anti-resonance ``w_z``) and no numbers for the TDO,
the poles, ``F^o`` or ``Q``/``R``; the choices below are ours, explained in docs/servo.md.
"""
from __future__ import annotations

import math

from .controllers import LQG, PID, TDO, PolePlacement
from .plant import ServoPlant, locked_frequency

__all__ = ["TS", "WF", "pid", "pid_tdo", "pole_placement", "lqg", "LQ_Q", "LQ_R",
           "TORQUE_NOISE", "LOAD_TORQUE_NOISE", "ENCODER_NOISE", "PP_POLES", "PP_OBSERVER"]

#: Sample period of the drive [s] (2 kHz position and velocity loops).
TS = 5e-4
#: Bandwidth of the reference model F^o(s) = wf^3/(s + wf)^3 [rad/s].
WF = 60.0
#: Bryson's rule: 1/(largest acceptable value)^2 for [q_m, q_m', n q_l, n q_l', x_I] and u:
#: 0.1 rad on the motor, 0.01 rad on the load (motor side; 1e-4 rad at the load), 3.2e-4 rad s
#: of integrated error, 1 N m of torque; velocities unweighted.
LQ_Q = (1e2, 0.0, 1e4, 0.0, 1e7)
LQ_R = 1.0
#: Kalman filter noise: torque ripple on the motor [N m], load torque [N m] (load side) and the
#: quantisation of a 20-bit encoder, (2 pi / 2^20)/sqrt(12) [rad].
TORQUE_NOISE = 0.01
LOAD_TORQUE_NOISE = 10.0
ENCODER_NOISE = 2.0 * math.pi / 2 ** 20 / math.sqrt(12.0)
#: Pole placement: pairs at 148.5 and 247.5 rad/s (zeta 0.707), the integrator at 30 rad/s;
#: observer about four times faster.
PP_POLES = (complex(-105, 105), complex(-105, -105), complex(-175, 175), complex(-175, -175),
            -30.0)
PP_OBSERVER = (complex(-420, 420), complex(-420, -420), -800.0, -1000.0)


def pid(plant: ServoPlant, **kw) -> PID:
    """The notes' normalised P/PI rule on ``w_z = sqrt(K_el/J_lr)``: ``w_cv = w_z``,
    ``T_Iv = 10/w_z``, ``w_cp = 0.1 w_z``.

    Parameters
    ----------
    plant : ServoPlant
        An elastic model.
    **kw
        Further :class:`PID` fields (``notch``, ``notch_at``, ``tdo``, ``J``).

    Returns
    -------
    PID

    Raises
    ------
    ParameterError
        Naming ``plant``.
    """
    wz = locked_frequency(plant)
    return PID(wcv=wz, Ti=10.0 / wz, wcp=0.1 * wz, **kw)


def pid_tdo(plant: ServoPlant, *, Tf: float = 2 * TS) -> PID:
    """:func:`pid` with a TDO on the motor's rigid model (velocity gain sized on ``J_m``).

    Parameters
    ----------
    plant : ServoPlant
        An elastic model.
    Tf : float, keyword-only
        The TDO's time constant [s] (default ``2 TS``).

    Returns
    -------
    PID

    Raises
    ------
    ParameterError
        Naming ``plant``.
    """
    return pid(plant, tdo=TDO(Tf=Tf))


def pole_placement(wf: float | None = WF) -> PolePlacement:
    """:data:`PP_POLES` and :data:`PP_OBSERVER` with the reference model of bandwidth ``wf``
    [rad/s] (None: none).

    Parameters
    ----------
    wf : float or None

    Returns
    -------
    PolePlacement

    Raises
    ------
    ParameterError
        Never here: ``wf`` is checked when a Drive is built.
    """
    return PolePlacement(poles=PP_POLES, observer_poles=PP_OBSERVER, wf=wf)


def lqg(wf: float | None = WF) -> LQG:
    """Bryson's weights :data:`LQ_Q`, :data:`LQ_R` and the noise :data:`TORQUE_NOISE`,
    :data:`LOAD_TORQUE_NOISE`, :data:`ENCODER_NOISE`, with the reference model of bandwidth
    ``wf`` [rad/s].

    Parameters
    ----------
    wf : float or None

    Returns
    -------
    LQG

    Raises
    ------
    ParameterError
        Never here: everything is checked when a Drive is built.
    """
    return LQG(Q=LQ_Q, R=LQ_R, torque_noise=TORQUE_NOISE, load_torque_noise=LOAD_TORQUE_NOISE,
               encoder_noise=ENCODER_NOISE, wf=wf)
