# SPDX-License-Identifier: Apache-2.0
"""System co-simulation: three FMUs connected by an SSP file, run in libcosim and fmpy.

Run ``python -m smoothshaper.cosim --out DIR`` (``scripts/main.sh`` does, into out/cosim).

The system (``ShapedMotion.ssp``, SSP 1.0, one file for both importers)::

    Generator (TrajectoryGenerator) --q--> Shaper (SmoothShaper) --y--> Plant (ElasticPlant)

The generator's target is one of the SSP's parameter bindings (``Generator.target = MOVE``,
its start value), so the system needs no input of its own: a jerk-limited move of height
``MOVE`` from t = 0 drives the two-mass elastic transmission of Biagiotti and Melchiorri ("FIR
filters for online trajectory planning with time- and frequency-domain specifications", 2012,
eq. 12, Table 1: wn = 260.4 rad/s, zeta = 0.0083) through a ZV input shaper designed for that
mode, or (run "without shaper") through a shaper whose stages are all ``none``. The system runs
in two importers: libcosim (libcosimpy loads the SSP file and applies its parameter bindings)
and fmpy (``fmpy.ssp.simulate_ssp``, whose master accumulates ``t += h``). fmpy reads the
bindings but does not apply them (its ``instantiate_fmu`` sets only the ``parameter_set``
argument): :func:`fmpy_applies_bindings` detects that (run alone, the generator never moves)
and :func:`run_fmpy` passes the file's own bindings as ``parameter_set``
(:func:`ssp_parameter_set`), saying so. The residual vibration of every run is compared with
the NumPy reference of the same system: the generator reference
(``trajectory.generator_reference``), the shaper reference (``reference.filter``) and the exact
zero-order-hold plant (``plants.simulate_zoh``), composed with the one-step delay of each
connection. Residual vibration: the largest distance of the load from the target once the
command into the plant has settled (the shaped command stays within 1e-12 of the target).

Co-simulation timing (both importers, step h = Ts): at step k every FMU steps with the inputs
its connections carried after step k-1, and each connection adds one step of delay.
:func:`reference` builds exactly this.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _optional
from .._checks import (finite_array as _finite_array, finite_signal as _finite_signal,
                       integer as _integer)
from ..errors import ParameterError
from ..reference._checks import check_samples
from . import ssp as _ssp
from .ssp import SSD_NS, ssp_parameter_set, ssp_parameters

__all__ = ["TS", "STOP_TIME", "MOVE", "PLANT", "LIMITS", "SSD_NS", "plant_mode",
           "parameters", "WITHOUT_SHAPER", "COMPONENTS", "CONNECTIONS", "SYSTEM",
           "system_structure", "write_ssp", "target_signal", "ssp_parameters",
           "ssp_parameter_set", "fmpy_applies_bindings", "run_fmpy", "run_libcosim", "reference",
           "residual_vibration", "Run", "run_all", "plot", "run", "main"]

#: Sample period of every FMU and the communication step [s].
TS = 1e-3
#: Length of a run [s] and the height of the move (any position unit; here m), which starts at
#: t = 0: the generator's target, set by the SSP's parameter bindings.
STOP_TIME = 0.6
MOVE = 0.01
#: The plant: Table 1 of Biagiotti and Melchiorri (2012).
PLANT = {"J_l": 0.23e-5, "k_t": 0.156, "b_t": 1.0e-5}
#: The generator's limits (short jerk phases: the move excites the 41 Hz mode).
LIMITS = {"vmax": 0.1, "amax": 4.0, "jmax": 400.0}
#: Shaper stage codes (SmoothShaper's stage[k].kind): zv and none.
KIND_ZV, KIND_NONE = 4, -1

def plant_mode() -> tuple[float, float]:
    """(wn, zeta) of the plant: wn = sqrt(k_t/J_l), zeta = b_t/(2 sqrt(k_t J_l))."""
    J, k, b = PLANT["J_l"], PLANT["k_t"], PLANT["b_t"]
    return math.sqrt(k / J), b / (2.0 * math.sqrt(k * J))


def parameters() -> dict[str, dict[str, float | int]]:
    """Start values of every component (the SSP's parameter bindings), shaper on."""
    wn, zeta = plant_mode()
    shaper = {"Ts": TS, "stage[0].kind": KIND_ZV, "stage[0].wn": wn, "stage[0].zeta": zeta}
    shaper.update({f"stage[{k}].kind": KIND_NONE for k in range(1, 8)})
    return {"Generator": {"Ts": TS, **LIMITS, "profile": 0, "target": MOVE},
            "Shaper": shaper,
            "Plant": {"Ts": TS, **PLANT}}


WITHOUT_SHAPER = {"Shaper.stage[0].kind": KIND_NONE}

# The generator's target is no connector: it keeps the value its binding sets (an importer sets
# every input connector before each step, fmpy to 0.0 when nothing is connected to it).
COMPONENTS = (("Generator", "TrajectoryGenerator", (("q", "output"),)),
              ("Shaper", "SmoothShaper", (("u", "input"), ("y", "output"))),
              ("Plant", "ElasticPlant", (("u", "input"), ("y", "output"))))
CONNECTIONS = (("Generator", "q", "Shaper", "u"), ("Shaper", "y", "Plant", "u"))


def target_signal(t: np.ndarray) -> np.ndarray:
    """The generator's target at the times ``t``: MOVE (bound at initialization)."""
    return np.full(np.shape(_finite_array("t", t)), MOVE)


#: The system (fmi.ssp): Generator -> Shaper -> Plant, the target bound.
SYSTEM = _ssp.System(
    name="ShapedMotion", description="jerk-limited move, input shaper, two-mass elastic plant",
    components=COMPONENTS, connections=CONNECTIONS, parameters=parameters(),
    without_shaper=WITHOUT_SHAPER, system_input=None,
    recorded=(("Shaper", "y"), ("Plant", "y")), Ts=TS, stop_time=STOP_TIME,
    target=target_signal)


def system_structure() -> str:
    """SystemStructure.ssd of the system (SSP 1.0; parameters inline as ssv parameter sets,
    the generator's target among them; no system-level connector, so that libcosim, which
    refuses a connection from one, and fmpy read the same file)."""
    return _ssp.system_structure(SYSTEM)


def write_ssp(out_dir: Path, fmus: dict[str, Path]) -> Path:
    """Write ``ShapedMotion.ssp`` (a zip: SystemStructure.ssd + resources/<Model>.fmu, the FMI
    2.0 FMUs, which both importers run) into out_dir and return its path."""
    return _ssp.write_ssp(SYSTEM, out_dir, fmus)[0]


def fmpy_applies_bindings(ssp: Path) -> bool:
    """Does ``fmpy.ssp.simulate_ssp`` apply the SSP's parameter bindings by itself? Run alone
    for 50 steps, the shaped command moves towards the bound target only if it does (fmpy 0.3:
    it does not)."""
    return _ssp.fmpy_applies_bindings(SYSTEM, ssp)


# ---------------------------------------------------------------- the two importers

def run_fmpy(ssp: Path, *, shaper: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, shaped command, load position) from fmpy's SSP master (t += h, step TS): row k is
    the state after step k, i.e. at t_(k+1). The file's parameter bindings are passed as
    ``parameter_set`` (fmpy does not apply them itself, :func:`fmpy_applies_bindings`)."""
    return _ssp.run_fmpy(SYSTEM, ssp, shaper=shaper)


def run_libcosim(ssp: Path, *, shaper: bool, n_steps: int):
    """The same in libcosim: libcosim loads the SSP (components, connections, parameter
    bindings, the generator's target among them); "without shaper" sets the shaper's first
    stage to none over the binding; outputs are read after every step."""
    return _ssp.run_libcosim(SYSTEM, ssp, shaper=shaper, n_steps=n_steps)


# ---------------------------------------------------------------- reference and measures

def reference(n_steps: int, *, shaper: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The NumPy reference of the system, rows as the importers report them (after step k)."""
    n_steps = _integer("n_steps", n_steps, 1)
    check_samples("n_steps", n_steps, "the reference run")
    if not isinstance(shaper, (bool, np.bool_)):
        raise ParameterError("shaper", f"shaper must be True or False, got {type(shaper).__name__}")
    from .. import plants
    from ..stages import shaper as shaper_stage
    wn, zeta = plant_mode()
    stages = [shaper_stage("zv", wn=wn, zeta=zeta)] if shaper else []
    s = np.r_[0.0, _ssp.generator_shaper_reference(SYSTEM, n_steps, limits=LIMITS, stages=stages)]
    plant = plants.two_mass(**PLANT)
    _, y = plants.simulate_zoh(plant, s, Ts=TS)
    return (np.arange(n_steps) + 1) * TS, s[1:], y[1:]


def residual_vibration(s: np.ndarray, p: np.ndarray) -> float:
    """max |load - target| once the command into the plant stays within 1e-12 of the target."""
    s, p = _finite_signal("s", s), _finite_signal("p", p)
    if p.shape != s.shape:
        raise ParameterError("p", f"p must have the shape of s {s.shape}, got {p.shape}")
    return _ssp.settled_residual(s, p, MOVE)


@dataclass
class Run:
    importer: str
    shaper: bool
    t: np.ndarray
    s: np.ndarray
    p: np.ndarray
    residual: float
    reference_residual: float
    max_error: float      # max |load - reference load| over the run


def run_all(ssp: Path, *, importers=("libcosim", "fmpy")) -> list[Run]:
    """Every importer with and without the shaper, on the one SSP file."""
    n = int(round(STOP_TIME / TS))
    runs = []
    for shaper in (False, True):
        _, s_ref, p_ref = reference(n, shaper=shaper)
        ref_residual = residual_vibration(s_ref, p_ref)
        for importer in importers:
            if importer == "fmpy":
                t, s, p = run_fmpy(ssp, shaper=shaper)
            else:
                t, s, p = run_libcosim(ssp, shaper=shaper, n_steps=n)
            if s.size != n:
                raise RuntimeError(f"{importer} returned {s.size} steps, expected {n}")
            runs.append(Run(importer, shaper, t, s, p, residual_vibration(s, p), ref_residual,
                            float(np.max(np.abs(p - p_ref)))))
    return runs


def plot(path: Path, runs: list[Run]) -> None:
    plt, fig, a0, a1 = _ssp.run_figure(
        "the system co-simulation (its figure)", runs, upper=lambda r: r.p * 1e3,
        lower=lambda r: (r.p - MOVE) * 1e6,
        label=lambda r: f"load, {'ZV shaper' if r.shaper else 'no shaper'} ({r.importer})")
    a0.axhline(MOVE * 1e3, color="0.6", lw=1, label="target", zorder=1.5)   # under the runs
    a0.set_ylabel("position [mm]")
    a0.set_title("TrajectoryGenerator -> SmoothShaper -> ElasticPlant (SSP), h = Ts = 1 ms")
    a0.legend(fontsize=8, loc="lower right")
    a1.set_ylim(-1.2 * max(r.residual for r in runs) * 1e6, 1.2 * max(r.residual for r in runs) * 1e6)
    a1.set_ylabel("load - target [um]")
    _ssp.save_run_figure(plt, fig, path)

def run(out_dir, *, fmus: dict | None = None, build_dir=None, importers=("libcosim", "fmpy"),
        plots: bool = True) -> bool:
    """Build the FMUs (unless given), write the SSP, run it with and without the shaper in each
    importer, compare with the reference; write README.md, ShapedMotion.ssp and
    system_cosim.png into out_dir; then the same for ShapedServo (:mod:`.servo_cosim`) when
    ServoDrive.fmu is among the FMUs. True if every run equals the reference; MissingDependency
    (an ImportError naming the extra) before anything is done when an importer is missing."""
    from .build import build_fmus
    needs = [{"libcosim": "libcosimpy"}.get(imp, imp) for imp in importers]
    _optional.require_all(needs + ["matplotlib"] * bool(plots), "the system co-simulation")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    if fmus is None:
        fmus = build_fmus(Path(build_dir) if build_dir else out / "build")
    ssp = write_ssp(out, fmus)
    applies = "fmpy" not in importers or fmpy_applies_bindings(ssp)
    if not applies:
        fmpy = _optional.require("fmpy", "the system co-simulation in fmpy")
        print(f"fmpy {fmpy.__version__}: fmpy.ssp.simulate_ssp does not apply the SSP's "
              "parameter bindings (run alone, the system did not move); passing them as "
              "parameter_set")
    runs = run_all(ssp, importers=importers)
    wn, zeta = plant_mode()
    tol = 1e-12 * MOVE
    header = ("| importer | shaper | residual vibration [m] | reference [m] | "
              "max abs(load - reference) [m] | equal |")
    lines = ["# System co-simulation: TrajectoryGenerator -> SmoothShaper -> ElasticPlant", "",
             "`ShapedMotion.ssp` (SSP 1.0) connects the three FMUs; libcosim and fmpy run the "
             "same file, with its parameter bindings (the generator's target among them). "
             + ("fmpy's `simulate_ssp` applies them itself. " if applies else
                "fmpy's `simulate_ssp` reads them but does not apply them (detected: run alone, "
                "the system did not move), so the runner passes them as `parameter_set` "
                "(`cosim.ssp_parameter_set`). ")
             + f"Move of {MOVE * 1e3:g} mm from "
             f"t = 0, limits vmax = {LIMITS['vmax']:g} m/s, "
             f"amax = {LIMITS['amax']:g} m/s2, jmax = {LIMITS['jmax']:g} m/s3; "
             f"plant J_l = {PLANT['J_l']:g} kg m2, "
             f"k_t = {PLANT['k_t']:g} N m/rad, b_t = {PLANT['b_t']:g} N m s/rad "
             f"(wn = {wn:.1f} rad/s, zeta = {zeta:.4f}); shaper: ZV for that mode, or every stage "
             f"none; h = Ts = {TS:g} s for every FMU.", "",
             "Residual vibration: max |load - target| once the command into the plant has "
             "settled. Reference: the NumPy generator, shaper and exact ZOH plant composed with "
             "the one-step delay of each connection.", "",
             header, "|---|---|---|---|---|---|"]
    ok = True
    for r in runs:
        equal = abs(r.residual - r.reference_residual) <= tol and r.max_error <= tol
        ok &= equal
        lines.append(f"| {r.importer} | {'ZV' if r.shaper else 'none'} | {r.residual:.6e} | "
                     f"{r.reference_residual:.6e} | {r.max_error:.1e} | {'yes' if equal else 'NO'} |")
    off = [r.residual for r in runs if not r.shaper]
    on = [r.residual for r in runs if r.shaper]
    lines += ["", f"Percentage residual vibration with the shaper: "
              f"{100 * max(on) / min(off):.2g} % (equal means within {tol:g} m).", "",
              "![system](system_cosim.png)", "", f"**Result: {'PASS' if ok else 'FAIL'}**", ""]
    if plots:
        plot(out / "system_cosim.png", runs)
    table = lines.index(header)
    print("\n".join(lines[table:table + len(runs) + 4]))     # the table and the percentage
    if "ServoDrive" in fmus:   # the shaped reference into a drive in closed loop
        from . import servo_cosim
        servo_ok, servo_lines = servo_cosim.section(out, fmus, plots=plots)
        ok &= servo_ok
        lines += servo_lines
        table = next(i for i, line in enumerate(servo_lines) if line.startswith("| importer"))
        print("\n".join(servo_lines[table:table + 7]))
    (out / "README.md").write_text("\n".join(lines))
    print(f"system co-simulation {'passed' if ok else 'FAILED'}: report in {out / 'README.md'}")
    return ok


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(prog="python -m smoothshaper.cosim", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="out/cosim", help="output directory")
    ap.add_argument("--build-dir", default=None, help="CMake build directory of the FMUs")
    args = ap.parse_args(argv)
    try:   # run() checks its packages before any work: one line naming the extra, exit 3
        return 0 if run(args.out, build_dir=args.build_dir) else 1
    except _optional.MissingDependency as exc:
        import sys
        sys.stderr.write(f"python -m smoothshaper.cosim: {exc}\n")
        return 3


if __name__ == "__main__":
    raise SystemExit(main())
