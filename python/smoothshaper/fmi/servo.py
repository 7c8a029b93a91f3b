# SPDX-License-Identifier: Apache-2.0
"""The ServoDrive FMU from Python: its parameters as the servo testbed's configuration
(:mod:`smoothshaper.servo`), runs in fmpy and libcosim, and the comparison of the two.

Timing. Tick ``n`` of the FMU is the drive's sample at ``(n - 1) Ts``: the reference and load
torque it holds are the inputs set at the last communication point before ``n Ts``
(:func:`~smoothshaper.fmi.timing.tick_inputs`), and after it the FMU reports the plant at
``n Ts`` and the torque of sample ``n - 1``. The testbed's
:meth:`~smoothshaper.servo.Drive.simulate` fed the same per-sample inputs reports the plant at
``k Ts`` and the torque of sample ``k``, so the FMU after tick ``n`` is the testbed's row ``n``
(positions, velocities) and row ``n - 1`` (torque); before the first tick both rest at the
inputs of initialization.

Tolerance. The FMU designs its controller in C (Pade matrix exponential, eigenvector pole
placement, doubling Riccati solver; fmu/README.md) and the testbed in scipy, and each sums in
its own order, so they agree to the loop's sensitivity to rounding, not bit for bit.
:func:`rounding_floor` measures that sensitivity on the testbed: how far each output moves when
every coefficient of the closed loop is perturbed by ``N u`` relative (``N`` the loop's order,
``u = 2^-53``, random signs, three fixed seeds); :func:`compare` allows :data:`FLOOR_FACTOR`
times the largest of those moves.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from .. import _optional, servo as _servo
from ..errors import ParameterError
from ..stages import notch as _notch
from .timing import tick_inputs

__all__ = ["TS", "CONTROLLERS", "OUTPUTS", "FLOOR_FACTOR", "default_parameters", "testbed",
           "reference_input", "expected", "simulate_servo", "rounding_floor", "ServoComparison",
           "compare", "VALIDATION_CASES"]

#: The FMU's default sample period [s] (the testbed's, servo.presets.TS).
TS = _servo.presets.TS
#: The ``controller`` codes, in order.
CONTROLLERS = ("pid", "pid_tdo", "pole_placement", "lqg")
#: The FMU's outputs.
OUTPUTS = ("q_m", "w_m", "q_l", "w_l", "tau_m")
#: The comparison's margin over the loop's rounding sensitivity (:func:`rounding_floor`).
FLOOR_FACTOR = 10.0

#: The cases ``smoothshaper validate`` compares: name and the parameters set on the defaults.
VALIDATION_CASES = (
    ("pid", {"controller": 0}),
    ("pid, notch on the torque (Tustin)", {"controller": 0, "notch.at": 1,
                                           "notch.discretization": 1}),
    ("pid, notch on the velocity reference", {"controller": 0, "notch.at": 2,
                                              "notch.wn": 60.0, "notch.zeta": 0.3,
                                              "notch.pole_zeta": 1.0}),
    ("pid_tdo", {"controller": 1}),
    ("pole_placement", {"controller": 2}),
    ("pole_placement, no feed-forward", {"controller": 2, "wf": 0.0}),
    ("lqg", {"controller": 3}),
)


def default_parameters(fmu) -> dict:
    """The FMU's parameters at their start values, from its model description.

    Parameters
    ----------
    fmu : str or Path
        Path of ServoDrive.fmu (FMI 2.0 or 3.0).

    Returns
    -------
    dict
        Name -> start value (int for the Integer choices, float otherwise).

    Raises
    ------
    ImportError
        fmpy is not installed.
    """
    _optional.require("fmpy", "ServoDrive's default parameters")
    from fmpy import read_model_description
    out = {}
    for v in read_model_description(str(fmu)).modelVariables:
        if v.causality == "parameter":
            out[v.name] = int(v.start) if v.type in ("Integer", "Int32") else float(v.start)
    return out


def _pair(wn: float, zeta: float) -> tuple[complex, complex]:
    # the FMU's own conversion, operation for operation
    p = complex(-zeta * wn, wn * math.sqrt(1.0 - zeta * zeta))
    return p, p.conjugate()


def testbed(values: dict) -> _servo.Drive:
    """The testbed drive the FMU runs with the parameters ``values``.

    Parameters
    ----------
    values : dict
        Every parameter of the FMU (:func:`default_parameters`, then any overrides).

    Returns
    -------
    smoothshaper.servo.Drive

    Raises
    ------
    ParameterError
        Naming the controller code or the parameter the testbed refuses.
    """
    v = values
    code = v["controller"]
    if code not in range(len(CONTROLLERS)):
        raise ParameterError("controller", f"controller must be 0..3, got {code!r}")
    plant = _servo.elastic_servo(Jm=v["Jm"], Jl=v["Jl"], n=v["n"], Dm=v["Dm"], Kel=v["Kel"],
                                 Del=v["Del"])
    wf = v["wf"] if v["wf"] > 0 else None
    if code <= 1:
        notch = None
        at = ("loop", "loop", "reference")[v["notch.at"]]
        if v["notch.at"]:
            notch = _notch(wn=v["notch.wn"], zeta=v["notch.zeta"],
                           notch_pole_zeta=v["notch.pole_zeta"],
                           discretization=("matched", "tustin")[v["notch.discretization"]])
        tdo = _servo.TDO(Tf=v["tdo.Tf"], Jn=v["tdo.Jn"], Dn=v["tdo.Dn"]) if code == 1 else None
        cfg = _servo.PID(wcv=v["pid.wcv"], Ti=v["pid.Ti"], wcp=v["pid.wcp"],
                         J=v["pid.J"] if v["pid.J"] > 0 else None, notch=notch, notch_at=at,
                         tdo=tdo)
    elif code == 2:
        poles = (*_pair(v["place.wn[0]"], v["place.zeta[0]"]),
                 *_pair(v["place.wn[1]"], v["place.zeta[1]"]), -v["place.real"])
        observer = (*_pair(v["observer.wn"], v["observer.zeta"]), -v["observer.real[0]"],
                    -v["observer.real[1]"])
        cfg = _servo.PolePlacement(poles=poles, observer_poles=observer, wf=wf)
    else:
        cfg = _servo.LQG(Q=tuple(v[f"lq.Q[{i}]"] for i in range(5)), R=v["lq.R"],
                         torque_noise=v["kalman.torque_noise"],
                         load_torque_noise=v["kalman.load_torque_noise"],
                         encoder_noise=v["kalman.encoder_noise"], wf=wf)
    return _servo.Drive(plant, cfg, Ts=v["Ts"])


def reference_input(t: np.ndarray, *, move: float = 0.5, t_move: float = 0.05,
                    torque: float = 5.0, t_torque: float = 1.0, Ts: float = TS):
    """The comparison's inputs: a load move of ``move`` [rad] from ``t_move`` shaped by two
    moving averages (0.3 s and 0.05 s: a trapezoidal velocity), and a load torque step of
    ``torque`` [N m] at ``t_torque``.

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s].
    move, t_move, torque, t_torque : float, keyword-only
        The move and the torque step.
    Ts : float, keyword-only
        Sample period of the shaping [s] (the drive's).

    Returns
    -------
    q_ref, tau_load : ndarray of float64, shape (K,)

    Raises
    ------
    ParameterError
        ``t`` is not finite.
    """
    from .. import Chain, rectangular
    from .._checks import finite_array
    t = finite_array("t", t)
    grid = np.arange(int(math.ceil(t[-1] / Ts)) + 2) * Ts
    shaped = Chain([rectangular(T=0.3), rectangular(T=0.05)], Ts=Ts).process(
        np.where(grid >= t_move - 1e-9 * Ts, move, 0.0))
    q_ref = shaped[np.minimum(np.floor(t / Ts + 1e-6).astype(np.int64), grid.size - 1)]
    return q_ref, np.where(t >= t_torque - 1e-9 * Ts, torque, 0.0)


def _rest(drive: _servo.Drive, q0: float, tau0: float) -> np.ndarray:
    return np.linalg.solve(np.eye(drive.order) - drive.A, drive.B @ np.array([q0, tau0]))


def expected(drive: _servo.Drive, t: np.ndarray, q_ref: np.ndarray, tau_load: np.ndarray) -> dict:
    """What the FMU reports at the communication points, from the testbed (module docstring).

    Parameters
    ----------
    drive : smoothshaper.servo.Drive
        :func:`testbed` of the FMU's parameters.
    t : ndarray of float64, shape (K,)
        Communication points [s].
    q_ref, tau_load : ndarray of float64, shape (K,)
        Inputs set at them.

    Returns
    -------
    dict of str to ndarray of float64, shape (K,)
        :data:`OUTPUTS`.

    Raises
    ------
    ParameterError
        Invalid points or inputs.
    """
    xq, n_at = tick_inputs(t, q_ref, Ts=drive.Ts)
    xt, _ = tick_inputs(t, tau_load, Ts=drive.Ts)
    # one more sample: the plant after the last tick (its torque is never read)
    X0 = _rest(drive, float(q_ref[0]), float(tau_load[0]))
    y = drive.simulate(np.r_[xq, q_ref[-1]], tau_load=np.r_[xt, tau_load[-1]], x0=X0)
    rest_tau = float(drive.C[4] @ X0 + drive.D[4] @ np.array([q_ref[0], tau_load[0]]))
    out = {name: y[name][n_at] for name in OUTPUTS[:4]}
    out["tau_m"] = np.where(n_at > 0, y["tau_m"][np.maximum(n_at - 1, 0)], rest_tau)
    return out


def _signal(t, q_ref, tau_load):
    sig = np.zeros(t.size, dtype=[("time", float), ("q_ref", float), ("tau_load", float)])
    sig["time"], sig["q_ref"], sig["tau_load"] = t, q_ref, tau_load
    return sig


def simulate_servo(fmu, t: np.ndarray, q_ref: np.ndarray, tau_load: np.ndarray,
                   start_values: dict, *, importer: str = "fmpy") -> dict:
    """The FMU in fmpy (default settings, ``output_interval`` = the communication step) or in
    libcosim (the second importer: the inputs overridden before every step, row 0 NaN because
    libcosim observes only after steps).

    Parameters
    ----------
    fmu : str or Path
        Path of ServoDrive.fmu.
    t : ndarray of float64, shape (K,)
        Communication points [s], equally spaced from 0.
    q_ref, tau_load : ndarray of float64, shape (K,)
        Inputs set at them.
    start_values : dict
        Parameters to set (name -> value; int values are Integers).
    importer : {"fmpy", "libcosim"}, keyword-only

    Returns
    -------
    dict of str to ndarray of float64, shape (K,)
        :data:`OUTPUTS` at ``t``.

    Raises
    ------
    ParameterError
        Naming ``importer``.
    RuntimeError
        The importer failed or fmpy returned other points than ``t``.
    """
    from .._checks import choice
    if choice("importer", importer, ("fmpy", "libcosim")) == "libcosim":
        from .simulate import simulate_libcosim
        y = simulate_libcosim(str(fmu), t, np.column_stack([q_ref, tau_load]),
                              dict(start_values), input_name=("q_ref", "tau_load"),
                              outputs=OUTPUTS)
        return {name: y[:, i] for i, name in enumerate(OUTPUTS)}
    _optional.require("fmpy", "running ServoDrive in fmpy")
    import fmpy
    step = float(t[1] - t[0])
    r = fmpy.simulate_fmu(str(fmu), start_values=dict(start_values),
                          input=_signal(t, q_ref, tau_load), start_time=0.0,
                          stop_time=float(t[-1]), output_interval=step, output=list(OUTPUTS),
                          validate=False)
    if r.size != t.size or not np.allclose(r["time"], t, rtol=0, atol=1e-9 * step):
        raise RuntimeError(f"fmpy returned {r.size} samples, expected {t.size}")
    return {name: np.asarray(r[name], dtype=float) for name in OUTPUTS}


def rounding_floor(drive: _servo.Drive, t: np.ndarray, q_ref: np.ndarray, tau_load: np.ndarray,
                   *, seeds=(1, 2, 3)) -> dict:
    """How far each output of :func:`expected` moves when every coefficient of the testbed's
    closed loop (``A, B, C, D``) is perturbed by ``N u`` relative (random signs; ``N`` the
    loop's order, ``u = 2^-53``): the largest move over ``seeds``.

    Parameters
    ----------
    drive : smoothshaper.servo.Drive
    t : ndarray of float64, shape (K,)
        Communication points [s].
    q_ref, tau_load : ndarray of float64, shape (K,)
        Inputs set at them.
    seeds : sequence of int, keyword-only
        Seeds of the signs.

    Returns
    -------
    dict of str to float
        :data:`OUTPUTS` -> largest absolute move.

    Raises
    ------
    ParameterError
        Invalid inputs.
    """
    base = expected(drive, t, q_ref, tau_load)
    eps = drive.order * np.finfo(float).eps / 2
    floor = dict.fromkeys(OUTPUTS, 0.0)
    for seed in seeds:
        rng = np.random.default_rng(seed)
        p = copy.copy(drive)
        p.A, p.B, p.C, p.D = [M * (1.0 + eps * rng.choice([-1.0, 1.0], M.shape))
                              for M in (drive.A, drive.B, drive.C, drive.D)]
        moved = expected(p, t, q_ref, tau_load)
        for name in OUTPUTS:
            floor[name] = max(floor[name], float(np.max(np.abs(moved[name] - base[name]))))
    return floor


@dataclass
class ServoComparison:
    """One FMU run against the testbed.

    Attributes
    ----------
    t : ndarray
        Communication points [s].
    q_ref, tau_load : ndarray
        The inputs.
    fmu, reference : dict of str to ndarray
        The FMU's outputs and the testbed's.
    error : dict of str to float
        ``max |FMU - testbed|`` per output.
    tolerance : dict of str to float
        :data:`FLOOR_FACTOR` times :func:`rounding_floor`.
    scale : dict of str to float
        ``max |testbed|`` per output (for relative figures).
    """
    t: np.ndarray
    q_ref: np.ndarray
    tau_load: np.ndarray
    fmu: dict
    reference: dict
    error: dict
    tolerance: dict
    scale: dict

    @property
    def passed(self) -> bool:
        """Every output within its tolerance."""
        return all(self.error[n] <= self.tolerance[n] for n in OUTPUTS)

    @property
    def worst_ratio(self) -> float:
        """max over the outputs of error / tolerance."""
        return max(self.error[n] / self.tolerance[n] for n in OUTPUTS)


def compare(fmu, overrides: dict | None = None, *, step: float = TS,
            stop_time: float = 1.5) -> ServoComparison:
    """The FMU in fmpy against the testbed with the same parameters.

    Parameters
    ----------
    fmu : str or Path
        Path of ServoDrive.fmu.
    overrides : dict or None
        Parameters set on the defaults (name -> value).
    step : float, keyword-only
        Communication step [s] (any multiple or fraction of Ts).
    stop_time : float, keyword-only
        Length of the run [s].

    Returns
    -------
    ServoComparison

    Raises
    ------
    RuntimeError
        fmpy failed.
    """
    from .timing import communication_points
    values = {**default_parameters(fmu), **(overrides or {})}
    t = communication_points(step=step, stop_time=stop_time)
    q_ref, tau_load = reference_input(t, Ts=values["Ts"])
    drive = testbed(values)
    ref = expected(drive, t, q_ref, tau_load)
    got = simulate_servo(fmu, t, q_ref, tau_load, overrides or {})
    floor = rounding_floor(drive, t, q_ref, tau_load)
    tiny = np.finfo(float).tiny
    error = {n: float(np.max(np.abs(got[n] - ref[n]))) for n in OUTPUTS}
    tolerance = {n: max(FLOOR_FACTOR * floor[n], tiny) for n in OUTPUTS}
    scale = {n: float(np.max(np.abs(ref[n]))) for n in OUTPUTS}
    return ServoComparison(t, q_ref, tau_load, got, ref, error, tolerance, scale)
