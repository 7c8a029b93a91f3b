# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper validate``: build the FMUs, check them with fmpy and fmutool, compare the two
importers and every validation case with the NumPy reference, and write the report.

:func:`run` builds ``SmoothShaper.fmu`` and ``TrajectoryGenerator.fmu`` with CMake, runs fmpy's
model-description validation and ``fmutool -check`` on every FMU, runs each in libcosim and
fmpy, simulates every stage family and a few chains through ``SmoothShaper.fmu`` with fmpy for
several communication step sizes, compares the output with the reference
(:mod:`smoothshaper.fmi.timing`) and writes ``README.md`` (tables of max errors) and PNG plots
into ``out_dir``.
"""
from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

from .build import build_fmus, fmpy_problems, fmutool_problems
from .cases import TRAJECTORY_LIMITS, TRAJECTORY_PROFILES, validation_cases
from .compare import REL_TOL, compare, compare_importers, compare_importers_trajectory, \
    compare_trajectory

__all__ = ["RUN_STEPS", "run"]


def _plot(path: Path, name: str, t, u, y, y_ref, Ts: float) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
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
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
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


#: The steps of :func:`run`, in order, for a progress display.
RUN_STEPS = ("build", "checks", "importers", "SmoothShaper", "TrajectoryGenerator")


def run(out_dir, *, build_dir=None, fmus: dict | None = None, Ts: float = 1e-3,
        stop_time: float = 0.42, plots: bool = True, progress=None) -> bool:
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
        Model name -> FMU path, to skip the build.
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
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    step = progress or (lambda name: None)
    step("build")
    if fmus is None:
        fmus = build_fmus(Path(build_dir) if build_dir else out / "build")
    step("checks")
    lines = ["# FMU validation", "",
             "Built with CMake; checked with fmpy; simulated with fmpy and compared with the "
             "NumPy reference `smoothshaper.reference.filter` (independent of the C code).", "",
             "Timing accounted for: fmpy sets u at t_k, calls doStep(t_k, h) and records y at "
             "t_{k+1}; the FMU computes the ticks n*Ts in (t_k, t_k + h] with u held at u(t_k) "
             "and reports the last tick's output (see `smoothshaper.fmi.timing`).", "",
             "## fmpy validate and fmutool -check", "",
             "| FMU | binaries | fmpy validate | fmutool -check |", "|---|---|---|---|"]
    ok = True
    for model, path in sorted(fmus.items()):
        problems, checks = fmpy_problems(path), fmutool_problems(path)
        ok &= not problems and not checks
        with zipfile.ZipFile(path) as z:
            platforms = sorted({n.split("/")[1] for n in z.namelist()
                                if n.startswith("binaries/") and n.count("/") == 2 and not n.endswith("/")})
        lines.append(f"| {model}.fmu | {', '.join(platforms)} | {'; '.join(problems) or 'no problem'} | "
                     f"{'; '.join(checks) or 'passed'} |")
    step("importers")
    if "SmoothShaper" in fmus or "TrajectoryGenerator" in fmus:
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
    lines += ["", f"**Result: {'PASS' if ok else 'FAIL'}**", ""]
    (out / "README.md").write_text("\n".join(lines))
    print(f"validation {'passed' if ok else 'FAILED'}: report in {out / 'README.md'}")
    return ok
