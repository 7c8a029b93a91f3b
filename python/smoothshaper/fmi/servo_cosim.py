# SPDX-License-Identifier: Apache-2.0
"""System co-simulation of a shaped reference into a drive in closed loop, run in libcosim and
fmpy (``python -m smoothshaper.cosim`` runs it after ShapedMotion).

The system (``ShapedServo.ssp``, SSP 1.0)::

    target --> Generator (TrajectoryGenerator) --q--> Shaper (SmoothShaper) --y-->
        Drive (ServoDrive)

A jerk-limited load move of 40 deg (the notes' first experiment's size, limits of the same
order) goes through a ZV shaper on the drive's locked-motor mode (107.2 rad/s, zeta 0.038), or
through a shaper with every stage ``none``, into ServoDrive with its default controller, the
P/PI cascade with velocity feed-forward of Bascetta's motion-control notes. The reference is
the NumPy generator and shaper (:func:`~smoothshaper.fmi.ssp.generator_shaper_reference`) and
the servo testbed's drive (:mod:`smoothshaper.servo`) with the one-step delay of each
connection; the drive agrees with the testbed to ten times the loop's rounding sensitivity
(:func:`smoothshaper.fmi.servo.rounding_floor`), the command to 1e-12 of the move.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _optional, servo as _servo
from .._checks import finite_array as _finite_array, integer as _integer
from ..errors import ParameterError
from ..reference._checks import check_samples
from . import servo as _fs
from . import ssp as _ssp

__all__ = ["TS", "STOP_TIME", "T_MOVE", "MOVE", "LIMITS", "shaper_mode", "target_signal",
           "SYSTEM", "write_ssp", "reference", "ServoRun", "run_all", "plot", "section"]

#: Sample period of every FMU and the communication step [s] (the drive's).
TS = _fs.TS
#: Length of a run [s], time of the move [s] and its height (load side) [rad].
STOP_TIME = 1.2
T_MOVE = 0.02
MOVE = math.radians(40.0)
#: The generator's limits, load side (rad/s, rad/s^2, rad/s^3): the notes' 1200 rad/s^2 at the
#: motor is 12 at the load.
LIMITS = {"vmax": 2.2, "amax": 12.0, "jmax": 1200.0}
KIND_ZV, KIND_NONE = 4, -1


def shaper_mode() -> tuple[float, float]:
    """The drive's locked-motor mode (the anti-resonance of the notes' plant).

    Returns
    -------
    tuple of float
        ``wn = sqrt(K_el/J_lr)`` [rad/s] and ``zeta = D_el / (2 sqrt(K_el J_lr))``.
    """
    p = _servo.NOTES
    Jr = p["Jl"] / p["n"] ** 2
    return math.sqrt(p["Kel"] / Jr), p["Del"] / (2.0 * math.sqrt(p["Kel"] * Jr))


def target_signal(t: np.ndarray) -> np.ndarray:
    """The system input: 0, then MOVE from T_MOVE on.

    Parameters
    ----------
    t : array_like of float
        Times [s].

    Returns
    -------
    ndarray of float64, the shape of ``t``

    Raises
    ------
    ParameterError
        Naming ``t`` when it is not finite.
    """
    return np.where(_finite_array("t", t) >= T_MOVE - 1e-9 * TS, MOVE, 0.0)


def _parameters() -> dict:
    wn, zeta = shaper_mode()
    shaper = {"Ts": TS, "stage[0].kind": KIND_ZV, "stage[0].wn": wn, "stage[0].zeta": zeta}
    shaper.update({f"stage[{k}].kind": KIND_NONE for k in range(1, 8)})
    return {"Generator": {"Ts": TS, **LIMITS, "profile": 0}, "Shaper": shaper,
            "Drive": {"Ts": TS, "controller": 0}}


#: The system (fmi.ssp): target -> Generator -> Shaper -> Drive.
SYSTEM = _ssp.System(
    name="ShapedServo", description="jerk-limited move, input shaper, servo drive in closed loop",
    components=(("Generator", "TrajectoryGenerator", (("target", "input"), ("q", "output"))),
                ("Shaper", "SmoothShaper", (("u", "input"), ("y", "output"))),
                ("Drive", "ServoDrive", (("q_ref", "input"), ("q_l", "output"),
                                         ("w_l", "output")))),
    connections=(("Generator", "q", "Shaper", "u"), ("Shaper", "y", "Drive", "q_ref")),
    parameters=_parameters(), without_shaper={"Shaper.stage[0].kind": KIND_NONE},
    system_input=("target", "Generator", "target"),
    recorded=(("Shaper", "y"), ("Drive", "q_l"), ("Drive", "w_l")), Ts=TS, stop_time=STOP_TIME,
    target=target_signal)


def write_ssp(out_dir: Path, fmus: dict[str, Path]) -> tuple[Path, Path]:
    """``ShapedServo.ssp`` and ``ShapedServo-libcosim.ssp``
    (:func:`~smoothshaper.fmi.ssp.write_ssp`).

    Parameters
    ----------
    out_dir : Path
        Folder (created).
    fmus : dict of str to Path
        Model name -> FMU file (TrajectoryGenerator, SmoothShaper, ServoDrive).

    Returns
    -------
    tuple of Path

    Raises
    ------
    RuntimeError
        A model is missing.
    """
    return _ssp.write_ssp(SYSTEM, out_dir, fmus)


def reference(n_steps: int, *, shaper: bool) -> tuple[np.ndarray, dict, dict]:
    """The reference of the system, rows as the importers report them (after step k).

    Parameters
    ----------
    n_steps : int
        Steps, >= 1.
    shaper : bool, keyword-only
        With the ZV shaper, or without.

    Returns
    -------
    command : ndarray, shape (n_steps,)
        The shaper's output.
    drive : dict of str to ndarray, shape (n_steps,)
        The drive's outputs (:data:`smoothshaper.fmi.servo.OUTPUTS`).
    floor : dict of str to float
        The drive's rounding sensitivity on this input
        (:func:`~smoothshaper.fmi.servo.rounding_floor`).

    Raises
    ------
    ParameterError
        Naming ``n_steps`` or ``shaper``.
    """
    n_steps = _integer("n_steps", n_steps, 1)
    check_samples("n_steps", n_steps, "the reference run")
    if not isinstance(shaper, (bool, np.bool_)):
        raise ParameterError("shaper", f"shaper must be True or False, got {type(shaper).__name__}")
    from ..stages import shaper as shaper_stage
    stages = [shaper_stage("zv", wn=shaper_mode()[0], zeta=shaper_mode()[1])] if shaper else []
    command = _ssp.generator_shaper_reference(SYSTEM, n_steps, limits=LIMITS, stages=stages)
    plant = _servo.elastic_servo()
    drive = _servo.Drive(plant, _servo.presets.pid(plant), Ts=TS)
    t = np.arange(n_steps + 1) * TS
    q_ref, tau = np.r_[0.0, command], np.zeros(n_steps + 1)   # the drive sees the step before
    out = _fs.expected(drive, t, q_ref, tau)
    return command, {k: v[1:] for k, v in out.items()}, _fs.rounding_floor(drive, t, q_ref, tau)


@dataclass
class ServoRun:
    """One run of the system in one importer.

    Attributes
    ----------
    importer : str
    shaper : bool
    t, command, q_l, w_l : ndarray
        Times (after each step) and the recorded variables.
    overshoot : float
        Load velocity overshoot over vmax [%].
    residual : float
        ``max |q_l - MOVE|`` once the command has settled [rad].
    reference_overshoot, reference_residual : float
        The same of the reference.
    error : float
        ``max |q_l - reference|`` [rad].
    tolerance : float
        Ten times the drive's rounding sensitivity plus 1e-11 MOVE for the command's rounding.
    command_error : float
        ``max |command - reference command|``.
    """
    importer: str
    shaper: bool
    t: np.ndarray
    command: np.ndarray
    q_l: np.ndarray
    w_l: np.ndarray
    overshoot: float
    residual: float
    reference_overshoot: float
    reference_residual: float
    error: float
    tolerance: float
    command_error: float

    @property
    def equal(self) -> bool:
        """The run equals the reference within the tolerances."""
        return self.error <= self.tolerance and self.command_error <= 1e-12 * MOVE


def run_all(ssp: Path, ssp_libcosim: Path, *, importers=("libcosim", "fmpy")) -> list[ServoRun]:
    """Every importer with and without the shaper, against the reference.

    Parameters
    ----------
    ssp, ssp_libcosim : Path
        The two files of :func:`write_ssp`.
    importers : sequence of str, keyword-only
        ``"libcosim"`` and/or ``"fmpy"``.

    Returns
    -------
    list of ServoRun

    Raises
    ------
    RuntimeError
        An importer failed or returned another number of steps.
    """
    n = int(round(STOP_TIME / TS))
    runs = []
    for shaper in (False, True):
        command_ref, drive_ref, floor = reference(n, shaper=shaper)
        tol = _fs.FLOOR_FACTOR * floor["q_l"] + 1e-11 * MOVE
        ref_over = 100.0 * (np.max(drive_ref["w_l"]) / LIMITS["vmax"] - 1.0)
        ref_residual = _ssp.settled_residual(command_ref, drive_ref["q_l"], MOVE)
        for importer in importers:
            if importer == "fmpy":
                t, command, q_l, w_l = _ssp.run_fmpy(SYSTEM, ssp, shaper=shaper)
            else:
                t, command, q_l, w_l = _ssp.run_libcosim(SYSTEM, ssp_libcosim, shaper=shaper,
                                                          n_steps=n)
            if q_l.size != n:
                raise RuntimeError(f"{importer} returned {q_l.size} steps, expected {n}")
            runs.append(ServoRun(importer, shaper, t, command, q_l, w_l,
                                 100.0 * (np.max(w_l) / LIMITS["vmax"] - 1.0),
                                 _ssp.settled_residual(command, q_l, MOVE), ref_over, ref_residual,
                                 float(np.max(np.abs(q_l - drive_ref["q_l"]))), tol,
                                 float(np.max(np.abs(command - command_ref)))))
    return runs


def plot(path: Path, runs: list[ServoRun]) -> None:
    """Load velocity and load position error of every run.

    Parameters
    ----------
    path : Path
        The PNG file.
    runs : list of ServoRun

    Raises
    ------
    OSError
        The file cannot be written.
    """
    plt = _optional.pyplot("the ShapedServo co-simulation figure")
    fig, (a0, a1) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    styles = {("libcosim", False): ("C3", "-", 2.5), ("fmpy", False): ("k", ":", 1.2),
              ("libcosim", True): ("C0", "-", 2.5), ("fmpy", True): ("k", "--", 1.0)}
    for r in runs:
        color, ls, lw = styles[(r.importer, r.shaper)]
        label = f"{'ZV on the locked mode' if r.shaper else 'no shaper'} ({r.importer})"
        a0.plot(r.t, r.w_l, color=color, ls=ls, lw=lw, label=label)
        a1.plot(r.t, np.degrees(r.q_l - MOVE), color=color, ls=ls, lw=lw, label=label)
    a0.axhline(LIMITS["vmax"], color="0.6", lw=0.8)
    a0.set_ylabel("load velocity [rad/s]")
    a0.set_title("TrajectoryGenerator -> SmoothShaper -> ServoDrive (SSP), P/PI drive, "
                 "h = Ts = 0.5 ms", fontsize=10)
    a0.legend(fontsize=8, loc="upper right")
    a1.set_ylim(-0.6, 0.6)
    a1.set_ylabel("load - target [deg]")
    a1.set_xlabel("t [s]")
    a1.axhline(0.0, color="0.7", lw=0.8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def section(out_dir: Path, fmus: dict, *, plots: bool = True) -> tuple[bool, list[str]]:
    """Write the SSP files and the plot into ``out_dir``, run every importer with and without
    the shaper and return (all equal the reference, the report's lines).

    Parameters
    ----------
    out_dir : Path
    fmus : dict of str to Path
        Model name -> FMU file.
    plots : bool, keyword-only
        Write ``servo_cosim.png``.

    Returns
    -------
    tuple
        ``(ok, lines)``.

    Raises
    ------
    RuntimeError
        A model is missing or an importer failed.
    """
    out = Path(out_dir)
    ssp, ssp_libcosim = write_ssp(out, fmus)
    runs = run_all(ssp, ssp_libcosim)
    wn, zeta = shaper_mode()
    header = ("| importer | shaper | load velocity overshoot [%] | reference [%] | "
              "residual [rad] | reference [rad] | max abs(q_l - reference) [rad] | "
              "tolerance [rad] | equal |")
    lines = ["", "# System co-simulation: TrajectoryGenerator -> SmoothShaper -> ServoDrive", "",
             "`ShapedServo.ssp` (SSP 1.0; libcosim runs `ShapedServo-libcosim.ssp`, without the "
             f"system-level input): a load move of {math.degrees(MOVE):g} deg at t = {T_MOVE:g} s "
             f"with vmax = {LIMITS['vmax']:g} rad/s, amax = {LIMITS['amax']:g} rad/s2, "
             f"jmax = {LIMITS['jmax']:g} rad/s3, through a ZV shaper on the drive's locked-motor "
             f"mode (wn = {wn:.2f} rad/s, zeta = {zeta:.4f}) or none, into ServoDrive with its "
             "default P/PI cascade (the servo of Bascetta's motion-control notes); "
             f"h = Ts = {TS * 1e3:g} ms for every FMU.", "",
             "Reference: the NumPy generator and shaper and the servo testbed's drive, with the "
             "one-step delay of each connection. The drive designs its controller in C, the "
             "testbed in scipy: the tolerance is ten times the loop's rounding sensitivity "
             "(`smoothshaper.fmi.servo.rounding_floor`) plus 1e-11 of the move for the "
             "command's rounding. Residual: max |q_l - target| once the command has settled.", "",
             header, "|---|---|---|---|---|---|---|---|---|"]
    ok = True
    for r in runs:
        ok &= r.equal
        lines.append(f"| {r.importer} | {'ZV' if r.shaper else 'none'} | {r.overshoot:.3f} | "
                     f"{r.reference_overshoot:.3f} | {r.residual:.3e} | "
                     f"{r.reference_residual:.3e} | {r.error:.1e} | {r.tolerance:.1e} | "
                     f"{'yes' if r.equal else 'NO'} |")
    off = [r.overshoot for r in runs if not r.shaper]
    on = [r.overshoot for r in runs if r.shaper]
    lines += ["", f"The ZV shaper lowers the load velocity overshoot from {min(off):.2f} % to "
              f"{max(on):.2f} %.", "", "![servo system](servo_cosim.png)", "",
              f"**Result: {'PASS' if ok else 'FAIL'}**", ""]
    if plots:
        plot(out / "servo_cosim.png", runs)
    return ok, lines
