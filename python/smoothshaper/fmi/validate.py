# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper validate``: build the FMUs, check them with fmpy and fmutool, compare the two
importers and every validation case with the NumPy reference, and write the report.

:func:`run` builds the FMI 2.0 and FMI 3.0 FMUs with CMake, runs fmpy's model-description
validation and ``fmutool -check`` on every FMU, runs each FMI 2.0 FMU in libcosim and fmpy
(libcosim has no FMI 3.0), simulates every stage family and a few chains through
``SmoothShaper.fmu`` with fmpy for several communication step sizes, compares the output with
the reference (:mod:`smoothshaper.fmi.timing`), compares ``ServoDrive.fmu`` with the servo
testbed for every controller (:mod:`smoothshaper.fmi.servo`), runs every model's FMI 3.0 FMU
in fmpy against its FMI 2.0 FMU (bit for bit; MultiAxisGenerator with 1 to 8 axes) and writes
``README.md`` (tables of max errors) and PNG plots into ``out_dir``.
"""
from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

from . import servo
from .build import build_fmus, fmpy_problems, fmutool_problems
from .cases import (TRAJECTORY_LIMITS, TRAJECTORY_PROFILES, multi_axis_case, target_staircase,
                    test_input, validation_cases)
from .compare import REL_TOL, compare, compare_importers, compare_importers_trajectory, \
    compare_trajectory
from .timing import communication_points

from .. import _optional
from .._optional import pyplot

__all__ = ["RUN_STEPS", "REQUIRES", "fmi3_against_fmi2", "run"]

#: The optional packages a run needs (extra ``validate``), checked before it starts.
REQUIRES = ("fmpy", "libcosimpy", "fmu_manipulation_toolbox", "matplotlib")


def _plot(path: Path, name: str, t, u, y, y_ref, Ts: float) -> None:
    plt = pyplot("smoothshaper validate (its figures)")
    fig, (a0, a1) = plt.subplots(2, 1, figsize=(7, 4.8), sharex=True)
    a0.step(t, u, where="post", color="0.6", label="u (held)")
    a0.plot(t, y_ref, "k-", lw=2.5, alpha=0.4, label="reference")
    a0.plot(t, y, "C1--", lw=1, label="FMU (fmpy)")
    a0.set_title(f"SmoothShaper.fmu vs reference: {name}\ncommunication step h = Ts = {Ts:g} s",
                 fontsize=10)
    a0.set_ylabel("input u, output y [-]")
    a0.legend(loc="best", fontsize=8)
    a1.plot(t, y - y_ref, "C3")
    a1.set_ylabel("FMU - reference [-]")
    a1.set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _plot_trajectory(path: Path, t, target, y, ref) -> None:
    plt = pyplot("smoothshaper validate (its figures)")
    fig, axes = plt.subplots(4, 1, figsize=(7, 7), sharex=True)
    axes[0].step(t, target, where="post", color="0.6", label="target")
    for ax, k, name in zip(axes, range(4), ("q [m]", "v [m/s]", "a [m/s2]", "j [m/s3]")):
        ax.plot(t, ref[:, k], "k-", lw=2.5, alpha=0.4, label="reference")
        ax.plot(t, y[:, k], "C1--", lw=1, label="FMU (fmpy)")
        ax.set_ylabel(name)
    axes[0].legend(fontsize=8)
    axes[0].set_title("TrajectoryGenerator.fmu vs NumPy reference")
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _plot_servo(path: Path, name: str, c, n: float) -> None:
    plt = pyplot("the ServoDrive validation figure")
    fig, axes = plt.subplots(4, 1, figsize=(7, 8.5), sharex=True)
    t = c.t
    axes[0].plot(t, c.q_ref, color="0.6", lw=1, label="q_ref")
    panels = ((axes[0], (("q_l", 1.0),), "position [rad]"),
              (axes[1], (("w_m", 1.0 / n), ("w_l", 1.0)), "velocity, load side [rad/s]"),
              (axes[2], (("tau_m", 1.0),), "motor torque [N m]"))
    for ax, curves, label in panels:
        for k, (out, gain) in enumerate(curves):
            tag = out if gain == 1.0 else f"{out}/n"
            ax.plot(t, gain * c.reference[out], f"C{k}-", lw=2.5, alpha=0.4,
                    label=f"{tag}, testbed")
            ax.plot(t, gain * c.fmu[out], "k--", lw=0.8, label=f"{tag}, FMU (fmpy)")
        ax.set_ylabel(label, fontsize=9)
        ax.legend(fontsize=7, loc="best")
    for k, out in enumerate(c.fmu):
        axes[3].plot(t, (c.fmu[out] - c.reference[out]) / c.scale[out], f"C{k}", lw=0.8,
                     label=out)
    axes[3].set_ylabel("(FMU - testbed) / max|testbed|", fontsize=9)
    axes[3].legend(fontsize=7, ncol=5, loc="best")
    axes[0].set_title(f"ServoDrive.fmu vs the servo testbed: {name}, h = Ts", fontsize=10)
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


#: The steps of :func:`run`, in order, for a progress display.
RUN_STEPS = ("build", "checks", "importers", "SmoothShaper", "TrajectoryGenerator", "ServoDrive",
             "FMI 3.0")


def _elastic_plant(fmu, t, u, Ts: float) -> np.ndarray:
    fmpy = _optional.require("fmpy", "running ElasticPlant in fmpy")
    sig = np.zeros(t.size, dtype=[("time", float), ("u", float)])
    sig["time"], sig["u"] = t, u
    r = fmpy.simulate_fmu(str(fmu), start_values={"Ts": Ts}, input=sig, stop_time=float(t[-1]),
                          output_interval=float(t[1] - t[0]), output=["y"], validate=False)
    return np.asarray(r["y"], dtype=float)


def fmi3_against_fmi2(fmus: dict, fmus3: dict, *, Ts: float = 1e-3):
    """Every model's FMI 3.0 FMU against its FMI 2.0 FMU in fmpy, on the same cases: every
    SmoothShaper validation case, every TrajectoryGenerator profile, MultiAxisGenerator with 1
    to 8 axes (arrays in FMI 3.0), ElasticPlant, every ServoDrive validation case; each pair
    must agree bit for bit.

    Parameters
    ----------
    fmus, fmus3 : dict
        Model name -> FMU path, FMI 2.0 and FMI 3.0.
    Ts : float, keyword-only
        Sample period and communication step [s] (default 1e-3).

    Returns
    -------
    list of tuple
        ``(model, case, max |FMI 3.0 - FMI 2.0|)`` for every case of a model built in both.

    Raises
    ------
    RuntimeError
        fmpy returned other points than asked for.
    """
    from .simulate import simulate, simulate_multi_axis, simulate_trajectory
    rows = []
    both = set(fmus) & set(fmus3)
    if "SmoothShaper" in both:
        t = communication_points(step=Ts, stop_time=0.3)
        u = test_input(t)
        for name, stages in validation_cases(Ts):
            y2, y3 = (simulate(str(f["SmoothShaper"]), stages, t, u, Ts=Ts) for f in (fmus, fmus3))
            rows.append(("SmoothShaper", name, float(np.max(np.abs(y3 - y2)))))
    if "TrajectoryGenerator" in both:
        t = communication_points(step=Ts, stop_time=1.2)
        target = target_staircase(t)
        for name, params in TRAJECTORY_PROFILES:
            y2, y3 = (simulate_trajectory(str(f["TrajectoryGenerator"]), t, target, Ts=Ts,
                                          **TRAJECTORY_LIMITS, **params) for f in (fmus, fmus3))
            rows.append(("TrajectoryGenerator", f"profile {name}", float(np.max(np.abs(y3 - y2)))))
    if "MultiAxisGenerator" in both:
        t = communication_points(step=Ts, stop_time=0.8)
        for axes in range(1, 9):
            values, targets, _ = multi_axis_case(axes, t)
            y2, y3 = (simulate_multi_axis(f["MultiAxisGenerator"], t, targets, values)
                      for f in (fmus, fmus3))
            rows.append(("MultiAxisGenerator", f"{axes} axes", float(np.max(np.abs(y3 - y2)))))
    if "ElasticPlant" in both:
        t = communication_points(step=2.5 * Ts, stop_time=0.3)
        u = test_input(t)
        y2, y3 = (_elastic_plant(f["ElasticPlant"], t, u, Ts) for f in (fmus, fmus3))
        rows.append(("ElasticPlant", "h = 2.5 Ts", float(np.max(np.abs(y3 - y2)))))
    if "ServoDrive" in both:   # at its own Ts, the testbed's
        t = communication_points(step=servo.TS, stop_time=1.5)
        q_ref, tau_load = servo.reference_input(t, Ts=servo.TS)
        for name, overrides in servo.VALIDATION_CASES:
            y2, y3 = (servo.simulate_servo(f["ServoDrive"], t, q_ref, tau_load, overrides)
                      for f in (fmus, fmus3))
            rows.append(("ServoDrive", name, max(float(np.max(np.abs(y3[n] - y2[n])))
                                                 for n in servo.OUTPUTS)))
    return rows


def run(out_dir, *, build_dir=None, fmus: dict | None = None, fmus3: dict | None = None,
        Ts: float = 1e-3, stop_time: float = 0.42, plots: bool = True, progress=None) -> bool:
    """Build the FMUs, check them (fmpy, fmutool), compare both importers and compare every
    validation case with the NumPy reference; write ``README.md`` and the plots to
    ``out_dir``.

    Parameters
    ----------
    out_dir : str or Path
        Output folder (created).
    build_dir : str or Path or None, keyword-only
        CMake build folder (default ``out_dir/build``).
    fmus : dict or None, keyword-only
        Model name -> FMU path, to skip the build (FMI 2.0).
    fmus3 : dict or None, keyword-only
        The same for FMI 3.0 (default: built, unless ``fmus`` is given).
    Ts : float, keyword-only
        Sample period of the cases [s] (default 1e-3).
    stop_time : float, keyword-only
        Length of the SmoothShaper runs [s] (default 0.42).
    plots : bool, keyword-only
        Write the PNG plots (default True).
    progress : callable or None, keyword-only
        Called as ``progress(step)`` when each step of :data:`RUN_STEPS` starts.

    Returns
    -------
    bool
        True if every check and comparison passed.

    Raises
    ------
    RuntimeError
        The FMUs cannot be built (no sources, no CMake) or an importer failed.
    MissingDependency
        (an ImportError) a package of :data:`REQUIRES` is not installed: nothing is done.
    """
    _optional.require_all(REQUIRES if plots else REQUIRES[:-1], "smoothshaper validate")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    step = progress or (lambda name: None)
    step("build")
    if fmus is None:
        folder = Path(build_dir) if build_dir else out / "build"
        fmus = build_fmus(folder)
        if fmus3 is None:
            fmus3 = build_fmus(folder, fmi_version="3.0")
    fmus3 = fmus3 or {}
    step("checks")
    lines = ["# FMU validation", "",
             "Built with CMake; checked with fmpy; simulated with fmpy and compared with the "
             "NumPy reference `smoothshaper.reference.filter` (independent of the C code).", "",
             "Timing accounted for: fmpy sets u at t_k, calls doStep(t_k, h) and records y at "
             "t_{k+1}; the FMU computes the ticks n*Ts in (t_k, t_k + h] with u held at u(t_k) "
             "and reports the last tick's output (see `smoothshaper.fmi.timing`).", "",
             "## fmpy validate and fmutool -check", "",
             "| FMU | FMI | binaries | fmpy validate | fmutool -check |", "|---|---|---|---|---|"]
    ok = True
    for version, built in (("2.0", fmus), ("3.0", fmus3)):
        for model, path in sorted(built.items()):
            problems, checks = fmpy_problems(path), fmutool_problems(path)
            ok &= not problems and not checks
            with zipfile.ZipFile(path) as z:
                platforms = sorted({n.split("/")[1] for n in z.namelist()
                                    if n.startswith("binaries/") and n.count("/") == 2
                                    and not n.endswith("/")})
            lines.append(f"| {model}.fmu | {version} | {', '.join(platforms)} | "
                         f"{'; '.join(problems) or 'no problem'} | "
                         f"{'; '.join(checks) or 'passed'} |")
    step("importers")
    if {"SmoothShaper", "TrajectoryGenerator", "ServoDrive"} & set(fmus):
        lines += ["", "## Second importer (libcosim via libcosimpy)", "",
                  "Every parameter set in libcosim (choices as Integer codes), h = Ts; libcosim "
                  "must equal fmpy bit for bit.", "",
                  "| FMU | case | max abs(libcosim - fmpy) | same |", "|---|---|---|---|"]
    if "SmoothShaper" in fmus:
        for name, stages in validation_cases(Ts):
            d_importers, _ = compare_importers(fmus["SmoothShaper"], stages, Ts=Ts)
            ok &= d_importers == 0.0
            lines.append(f"| SmoothShaper | {name} | {d_importers:.1e} | "
                         f"{'yes' if d_importers == 0.0 else 'NO'} |")
    if "TrajectoryGenerator" in fmus:
        for name, params in TRAJECTORY_PROFILES:
            d_tg = compare_importers_trajectory(fmus["TrajectoryGenerator"], Ts=Ts, **params)
            ok &= d_tg == 0.0
            lines.append(f"| TrajectoryGenerator | profile {name} | {d_tg:.1e} | "
                         f"{'yes' if d_tg == 0.0 else 'NO'} |")
    if "ServoDrive" in fmus:
        t = np.arange(1201) * servo.TS
        q_ref, tau = servo.reference_input(t, t_torque=0.4)
        for code, name in enumerate(servo.CONTROLLERS):
            a = servo.simulate_servo(fmus["ServoDrive"], t, q_ref, tau, {"controller": code})
            b = servo.simulate_servo(fmus["ServoDrive"], t, q_ref, tau, {"controller": code},
                                     importer="libcosim")
            d_sd = max(float(np.max(np.abs(a[n][1:] - b[n][1:]))) for n in servo.OUTPUTS)
            ok &= d_sd == 0.0
            lines.append(f"| ServoDrive | controller {code} ({name}) | {d_sd:.1e} | "
                         f"{'yes' if d_sd == 0.0 else 'NO'} |")
    step("SmoothShaper")
    if "SmoothShaper" in fmus:
        steps = (("Ts", Ts), ("7 Ts", 7 * Ts), ("2.5 Ts", 2.5 * Ts), ("0.4 Ts", 0.4 * Ts))
        lines += ["", f"## SmoothShaper vs reference (Ts = {Ts:g} s, 0 to {stop_time:g} s, "
                  f"tolerance {REL_TOL:g} relative)", "",
                  "| case | " + " | ".join(f"h = {n}" for n, _ in steps) + " | pass |",
                  "|---|" + "---|" * (len(steps) + 1)]
        for i, (name, stages) in enumerate(validation_cases(Ts)):
            cells, passed = [], True
            for j, (_, h) in enumerate(steps):
                t, u, y, y_ref, err, rel = compare(fmus["SmoothShaper"], stages, Ts=Ts, step=h,
                                                   stop_time=stop_time)
                passed &= rel <= REL_TOL
                cells.append(f"{rel:.2e}")
                if plots and j == 0:
                    _plot(out / f"smoothshaper_{i:02d}.png", name, t, u, y, y_ref, Ts)
            ok &= passed
            lines.append(f"| {name} | " + " | ".join(cells) + f" | {'yes' if passed else 'NO'} |")
        lines += ["", "Cells: max |y_FMU - y_ref| / max |y_ref| over the run. Plots (h = Ts): "
                  "`smoothshaper_NN.png` in table order."]
    step("TrajectoryGenerator")
    if "TrajectoryGenerator" in fmus:
        lines += ["", "## TrajectoryGenerator vs reference (`trajectory.generator_reference`, "
                  f"vmax = {TRAJECTORY_LIMITS['vmax']:g} m/s, "
                  f"amax = {TRAJECTORY_LIMITS['amax']:g} m/s2, "
                  f"jmax = {TRAJECTORY_LIMITS['jmax']:g} m/s3, Ts = {Ts:g} s)", "",
                  "| step | q | v | a | j | pass |", "|---|---|---|---|---|---|"]
        for label, h in (("Ts", Ts), ("7 Ts", 7 * Ts), ("2.5 Ts", 2.5 * Ts)):
            t, target, y, ref, rel = compare_trajectory(
                fmus["TrajectoryGenerator"], Ts=Ts, step=h, stop_time=1.5)
            passed = bool(np.all(rel <= REL_TOL))
            ok &= passed
            lines.append(f"| {label} | {rel[0]:.2e} | {rel[1]:.2e} | {rel[2]:.2e} | {rel[3]:.2e} | "
                         f"{'yes' if passed else 'NO'} |")
            if plots and label == "Ts":
                _plot_trajectory(out / "trajectory_generator.png", t, target, y, ref)
        lines += ["", "Cells: max |FMU - reference| / max |reference| of q, v, a, j. Where the jerk "
                  "jumps on a tick (these limits put every jump on the grid), both report the right "
                  "limit, the value held over the next sample period (trajectory.h)."]
    step("ServoDrive")
    if "ServoDrive" in fmus:
        steps = (("Ts", servo.TS), ("4 Ts", 4 * servo.TS), ("2.5 Ts", 2.5 * servo.TS))
        lines += ["", "## ServoDrive vs the servo testbed (`smoothshaper.servo`)", "",
                  "The FMU designs its controller in C and the testbed in scipy; each sums in its "
                  "own order, so they agree to the loop's rounding sensitivity: the tolerance of "
                  f"each output is {servo.FLOOR_FACTOR:g} times how far it moves when every "
                  "coefficient of the testbed's closed loop is perturbed by N u relative "
                  "(`smoothshaper.fmi.servo.rounding_floor`). A 0.5 rad move shaped by two moving "
                  "averages, then a 5 N m load torque step at 1 s; Ts = 0.5 ms.", "",
                  "| case | " + " | ".join(f"h = {n}" for n, _ in steps) + " | pass |",
                  "|---|" + "---|" * (len(steps) + 1)]
        for i, (name, overrides) in enumerate(servo.VALIDATION_CASES):
            cells, passed = [], True
            for j, (_, h) in enumerate(steps):
                c = servo.compare(fmus["ServoDrive"], overrides, step=h)
                passed &= c.passed
                rel = max(c.error[n] / c.scale[n] for n in servo.OUTPUTS)
                cells.append(f"{rel:.1e} ({c.worst_ratio:.2f})")
                if plots and j == 0 and name in ("pid", "lqg"):
                    _plot_servo(out / f"servo_drive_{name}.png", name, c,
                                servo.default_parameters(fmus["ServoDrive"])["n"])
            ok &= passed
            lines.append(f"| {name} | " + " | ".join(cells) + f" | {'yes' if passed else 'NO'} |")
        lines += ["", "Cells: max over q_m, w_m, q_l, w_l, tau_m of max |FMU - testbed| / max "
                  "|testbed|, and in brackets the largest error over its tolerance. Plots "
                  "(h = Ts): `servo_drive_pid.png`, `servo_drive_lqg.png`."]
    step("FMI 3.0")
    if fmus3:
        lines += ["", "## FMI 3.0 against FMI 2.0 (fmpy, h = Ts)", "",
                  "The FMI 3.0 FMUs are built from the same model files; each must give the FMI "
                  "2.0 FMU's outputs bit for bit (MultiAxisGenerator's per-axis variables are "
                  "arrays of 8 in FMI 3.0; every axis's target is given, so fmpy warns of no "
                  "missing input).", "", "| FMU | case | max abs(FMI 3.0 - FMI 2.0) | same |",
                  "|---|---|---|---|"]
        for model, case, diff in fmi3_against_fmi2(fmus, fmus3, Ts=Ts):
            ok &= diff == 0.0
            lines.append(f"| {model} | {case} | {diff:.1e} | {'yes' if diff == 0.0 else 'NO'} |")
    lines += ["", f"**Result: {'PASS' if ok else 'FAIL'}**", ""]
    (out / "README.md").write_text("\n".join(lines))
    print(f"validation {'passed' if ok else 'FAILED'}: report in {out / 'README.md'}")
    return ok
