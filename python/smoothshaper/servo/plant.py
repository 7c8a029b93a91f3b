# SPDX-License-Identifier: Apache-2.0
"""The servomechanism of Bascetta, "Motion control: advanced control techniques" (Politecnico di
Milano lecture notes), as continuous state space, and its exact zero-order-hold discretisation.

Elastic model (the notes' section "State space design"): state
``x = [q_m, q_m', n q_l, n q_l']`` (motor angle, motor velocity, load angle and velocity referred
to the motor side), inputs the motor torque ``tau_m`` and the load torque ``tau_l`` (on the load
side, opposing motion)::

    J_m  q_m''      = tau_m - D_m q_m' - K_el (q_m - n q_l) - D_el (q_m' - n q_l')
    J_lr (n q_l)''  = K_el (q_m - n q_l) + D_el (q_m' - n q_l') - tau_l / n,   J_lr = J_l / n^2

The notes print ``+D_el/J_lr`` in the last entry of ``A``; the physics (and a stable model:
with the printed sign ``A`` has an eigenvalue at +2.4 1/s) needs ``-D_el/J_lr`` (docs/errata.md).

Rigid model (the notes' section "Torque disturbance observer"): the motor alone,
``P(s) = 1/(J_m s + D_m)`` from torque to velocity, state ``[q_m, q_m']``; the load torque acts
on the motor as ``-tau_l / n`` (the notes' ``tau_c``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from .._checks import nonnegative as _nonnegative, positive as _positive
from ..errors import ParameterError

__all__ = ["NOTES", "ServoPlant", "DiscretePlant", "elastic_servo", "rigid_servo",
           "servo_from_modes", "discretize", "locked_frequency"]

#: The parameter table of the notes (torque constant, inertias, ratio, friction, stiffness).
NOTES = {"Kt": 1.6, "Jm": 0.00015, "Jl": 2.7, "n": 100.0, "Dm": 0.0034, "Kel": 3.1,
         "Del": 0.0022}


@dataclass(frozen=True)
class ServoPlant:
    """A servomechanism ``x' = A x + B_u tau_m + B_d tau_l`` with its physical parameters.

    Attributes
    ----------
    A : ndarray, shape (nx, nx)
        State matrix [1/s]; ``nx`` is 4 (elastic) or 2 (rigid).
    B_u : ndarray, shape (nx,)
        Motor torque input [per N m].
    B_d : ndarray, shape (nx,)
        Load torque input (load side) [per N m].
    outputs : ndarray, shape (4, nx)
        Rows giving ``q_m`` [rad], ``q_m'`` [rad/s], ``q_l`` [rad], ``q_l'`` [rad/s] (load side).
    params : dict
        ``Kt, Jm, Jl, n, Dm, Kel, Del`` (``Kel``, ``Del``, ``Jl`` are 0 for the rigid model).
    kind : str
        ``"elastic"`` or ``"rigid"``.
    """
    A: np.ndarray
    B_u: np.ndarray
    B_d: np.ndarray
    outputs: np.ndarray
    params: dict
    kind: str

    @property
    def order(self) -> int:
        """The state dimension ``nx`` (4 elastic, 2 rigid)."""
        return self.A.shape[0]

    def modes(self) -> dict:
        """Modal quantities of the elastic model (the notes' table lists measured ones).

        Returns
        -------
        dict
            ``w_z`` [rad/s] and ``zeta_z``: the anti-resonance (zeros of ``q_m/tau_m``, equal to
            the locked-motor frequency ``sqrt(K_el/J_lr)``); ``w_p`` [rad/s] and ``zeta_p``: the
            resonance (complex poles); ``real_pole`` [rad/s]: the real non-zero pole.
        """
        if self.kind != "elastic":
            raise ParameterError("plant", "plant: modes are defined for the elastic model only")
        p = self.params
        Jr = p["Jl"] / p["n"] ** 2
        zeros = np.roots([Jr, p["Del"], p["Kel"]])
        poles = np.linalg.eigvals(self.A)
        cplx = poles[np.argmax(np.abs(poles.imag))]
        real = poles[(np.abs(poles.imag) == 0) & (np.abs(poles) > 1e-9 * abs(cplx))]
        return {"w_z": float(abs(zeros[0])), "zeta_z": float(-zeros[0].real / abs(zeros[0])),
                "w_p": float(abs(cplx)), "zeta_p": float(-cplx.real / abs(cplx)),
                "real_pole": float(-real[0].real) if real.size else 0.0}


def _params(Kt, Jm, Jl, n, Dm, Kel, Del) -> dict:
    return {"Kt": _positive("Kt", Kt), "Jm": _positive("Jm", Jm), "Jl": _positive("Jl", Jl),
            "n": _positive("n", n), "Dm": _nonnegative("Dm", Dm), "Kel": _positive("Kel", Kel),
            "Del": _nonnegative("Del", Del)}


def elastic_servo(*, Kt: float = NOTES["Kt"], Jm: float = NOTES["Jm"], Jl: float = NOTES["Jl"],
                  n: float = NOTES["n"], Dm: float = NOTES["Dm"], Kel: float = NOTES["Kel"],
                  Del: float = NOTES["Del"]) -> ServoPlant:
    """The elastic servomechanism (motor, elastic transmission, inertial load).

    Defaults are the notes' parameter table. ``Kt`` [N m/A] converts the drive's current to
    torque; the models take torque as input and keep ``Kt`` for reports.

    Parameters
    ----------
    Kt : float, keyword-only
        Torque constant [N m/A], > 0.
    Jm, Jl : float, keyword-only
        Motor and load inertia [kg m^2], > 0.
    n : float, keyword-only
        Transmission ratio (motor turns per load turn), > 0.
    Dm : float, keyword-only
        Motor viscous friction [N m s/rad], >= 0.
    Kel : float, keyword-only
        Transmission stiffness [N m/rad] (motor side), > 0.
    Del : float, keyword-only
        Transmission damping [N m s/rad] (motor side), >= 0.

    Returns
    -------
    ServoPlant
        The four-state model of the module docstring.

    Raises
    ------
    ParameterError
        Naming the parameter that is not finite or out of range.
    """
    p = _params(Kt, Jm, Jl, n, Dm, Kel, Del)
    Jm, Jr, n = p["Jm"], p["Jl"] / p["n"] ** 2, p["n"]
    K, D, Dm = p["Kel"], p["Del"], p["Dm"]
    A = np.array([[0.0, 1.0, 0.0, 0.0],
                  [-K / Jm, -(Dm + D) / Jm, K / Jm, D / Jm],
                  [0.0, 0.0, 0.0, 1.0],
                  [K / Jr, D / Jr, -K / Jr, -D / Jr]])
    if not np.all(np.isfinite(A)):
        raise ParameterError("Jl", "Jl / n^2: the model's coefficients are beyond the range of "
                             "a float")
    B_u = np.array([0.0, 1.0 / Jm, 0.0, 0.0])
    B_d = np.array([0.0, 0.0, 0.0, -1.0 / (n * Jr)])
    outputs = np.array([[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0 / n, 0], [0, 0, 0, 1.0 / n]])
    return ServoPlant(A, B_u, B_d, outputs, p, "elastic")


def rigid_servo(*, Kt: float = NOTES["Kt"], Jm: float = NOTES["Jm"], n: float = NOTES["n"],
                Dm: float = NOTES["Dm"]) -> ServoPlant:
    """The motor alone, ``q_m'/tau_m = P(s) = 1/(J_m s + D_m)`` (the notes' TDO section).

    Parameters
    ----------
    Kt, Jm, n, Dm : float, keyword-only
        As :func:`elastic_servo` (``Jm`` is the whole inertia the torque sees).

    Returns
    -------
    ServoPlant
        State ``[q_m, q_m']``; the load torque enters the motor as ``-tau_l/n``; the load angle
        is ``q_m/n``.

    Raises
    ------
    ParameterError
        Naming the parameter.
    """
    p = _params(Kt, Jm, 1.0, n, Dm, 1.0, 0.0)
    p.update(Jl=0.0, Kel=0.0, Del=0.0)
    A = np.array([[0.0, 1.0], [0.0, -p["Dm"] / p["Jm"]]])
    B_u = np.array([0.0, 1.0 / p["Jm"]])
    B_d = np.array([0.0, -1.0 / (p["n"] * p["Jm"])])
    outputs = np.array([[1.0, 0], [0, 1.0], [1.0 / p["n"], 0], [0, 1.0 / p["n"]]])
    return ServoPlant(A, B_u, B_d, outputs, p, "rigid")


def servo_from_modes(*, wz: float, rho: float, zeta_z: float, Jm: float = 1.0, n: float = 1.0,
                     Dm: float = 0.0) -> ServoPlant:
    """The elastic servo given by its anti-resonance: ``wz = sqrt(K_el/J_lr)``, inertia ratio
    ``rho = J_lr/J_m`` and ``zeta_z = D_el/(2 sqrt(K_el J_lr))`` (the notes' notch example:
    ``wz = 200 rad/s, rho = 1, zeta_z = 0.1``); resonance ``wp = wz sqrt(1 + rho)``.

    Parameters
    ----------
    wz : float, keyword-only
        Anti-resonance (locked) frequency [rad/s], > 0.
    rho : float, keyword-only
        Load-to-motor inertia ratio ``J_l/(n^2 J_m)``, > 0.
    zeta_z : float, keyword-only
        Damping of the anti-resonance, in [0, 1).
    Jm, n, Dm : float, keyword-only
        Motor inertia [kg m^2] (default 1: the notes' example is normalised), ratio, friction.

    Returns
    -------
    ServoPlant

    Raises
    ------
    ParameterError
        Naming ``wz``, ``rho``, ``zeta_z``, ``Jm``, ``n`` or ``Dm``.
    """
    wz, rho = _positive("wz", wz), _positive("rho", rho)
    zeta_z = _nonnegative("zeta_z", zeta_z)
    if zeta_z >= 1:
        raise ParameterError("zeta_z", f"zeta_z must be in [0, 1), got {zeta_z!r}")
    Jm, n = _positive("Jm", Jm), _positive("n", n)
    Jr = rho * Jm
    return elastic_servo(Kt=1.0, Jm=Jm, Jl=Jr * n * n, n=n, Dm=Dm, Kel=wz * wz * Jr,
                         Del=2.0 * zeta_z * wz * Jr)


@dataclass(frozen=True)
class DiscretePlant:
    """Exact ZOH discretisation: ``x[k+1] = Ad x[k] + Bu tau_m[k] + Bd tau_l[k]``.

    Attributes
    ----------
    Ad : ndarray, shape (nx, nx)
    Bu, Bd : ndarray, shape (nx,)
    Ts : float
        Sample period [s].
    plant : ServoPlant
        The continuous model.
    """
    Ad: np.ndarray
    Bu: np.ndarray
    Bd: np.ndarray
    Ts: float
    plant: ServoPlant


def discretize(plant: ServoPlant, *, Ts: float) -> DiscretePlant:
    """Zero-order-hold discretisation of both inputs, from one matrix exponential
    ``expm([[A, B_u, B_d], [0, 0, 0]] Ts)`` (exact up to rounding).

    Parameters
    ----------
    plant : ServoPlant
    Ts : float, keyword-only
        Sample period [s], > 0 and small enough that ``|A| Ts`` stays below 50 (beyond, the
        fastest mode is far above the Nyquist frequency).

    Returns
    -------
    DiscretePlant

    Raises
    ------
    ParameterError
        Naming ``plant`` or ``Ts``.
    """
    if not isinstance(plant, ServoPlant):
        raise ParameterError("plant", f"plant must be a ServoPlant, got {type(plant).__name__}")
    Ts = _positive("Ts", Ts)
    nx = plant.order
    if np.max(np.abs(plant.A)) * Ts > 50:
        raise ParameterError("Ts", f"Ts = {Ts!r} is too long for this plant: its fastest "
                             f"coefficient times Ts is {np.max(np.abs(plant.A)) * Ts:.3g} (> 50)")
    M = np.zeros((nx + 2, nx + 2))
    M[:nx, :nx] = plant.A
    M[:nx, nx] = plant.B_u
    M[:nx, nx + 1] = plant.B_d
    E = expm(M * Ts)
    return DiscretePlant(E[:nx, :nx], E[:nx, nx].copy(), E[:nx, nx + 1].copy(), Ts, plant)


def locked_frequency(plant: ServoPlant) -> float:
    """``sqrt(K_el / J_lr)`` [rad/s]: the load's mode when the motor is held still (the
    anti-resonance of ``q_m / tau_m``).

    Parameters
    ----------
    plant : ServoPlant
        An elastic model.

    Returns
    -------
    float
        The locked frequency [rad/s].

    Raises
    ------
    ParameterError
        Naming ``plant`` when it is not an elastic ServoPlant.
    """
    if not isinstance(plant, ServoPlant) or plant.kind != "elastic":
        raise ParameterError("plant", "plant must be an elastic ServoPlant")
    p = plant.params
    return math.sqrt(p["Kel"] * p["n"] ** 2 / p["Jl"])
