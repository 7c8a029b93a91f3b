# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper validate``: build the FMUs, check them with fmpy, compare them with the reference.

``run(out_dir)`` builds ``SmoothShaper.fmu`` and ``TrajectoryGenerator.fmu`` with CMake, runs
fmpy's model-description validation on both, simulates every stage family and a few chains
through ``SmoothShaper.fmu`` with fmpy for several communication step sizes, compares the output
with :func:`smoothshaper.reference.filter` and writes ``README.md`` (tables of max errors) and
PNG plots into ``out_dir``.

Co-simulation output timing (what the comparison accounts for). fmpy sets the inputs at the
communication point t_k, calls ``doStep(t_k, h)`` and records the outputs at t_{k+1}. The FMU
runs internal ticks at n*Ts (n = 1, 2, ...); a doStep from t to t+h computes the ticks in
(t, t+h] with the input held at its value at t, and its outputs are those of the last tick.
So tick n filters x[n-1] = u(t_c), t_c the last communication point before n*Ts, and the value
recorded at a communication point t is y[n_t - 1], n_t = floor(t/Ts) (the chain at rest at u(0)
before the first tick, so y = u(0) while n_t = 0). :func:`expected_output` builds exactly this
from the reference.
"""
from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import reference
from .stages import (TIMINGS, damped_harmonic, exponential, for_mode, harmonic, notch,
                     rectangular, shaper)
from .errors import ParameterError
from ._checks import (finite as _finite, finite_array as _finite_array,
                      finite_signal as _finite_signal, nonnegative as _nonnegative,
                      positive as _positive)
from .reference._checks import check_samples

__all__ = ["REL_TOL", "RUN_STEPS", "ModeStage", "start_values", "reference_stages", "communication_points",
           "tick_inputs", "at_communication_points", "expected_output", "expected_trajectory",
           "simulate", "validation_cases", "build_fmus", "fmpy_problems", "fmutool_problems",
           "simulate_libcosim", "compare_importers", "compare_importers_trajectory", "compare",
           "target_staircase", "simulate_trajectory", "compare_trajectory", "run"]

#: Relative error accepted between FMU and reference (docs/numerics.md: 1e-12 in double).
REL_TOL = 1e-12
#: Fraction of Ts by which a tick may follow the end of a step and still belong to it (fmu/).
TICK_SLACK = 1e-6
#: Model value references (modelDescription/generate.py).
STAGE_FIELDS = ("kind", "design", "timing", "T", "sigma", "k", "wn", "zeta", "order", "tolerance",
                "notch_pole_zeta", "duration")
KIND_VALUES = {k: i for i, k in enumerate(
    ("rectangular", "harmonic", "damped_harmonic", "exponential", "zv", "zvd", "zvdd", "zvn", "ei",
     "ei2", "mzv", "notch_tustin", "notch_matched", "ei3", "gmzv"))}


@dataclass(frozen=True)
class ModeStage:
    """A stage the SmoothShaper FMU designs itself for a mode (``stage[k].design = for_mode``).

    Attributes
    ----------
    kind : str
        A stage kind (:data:`smoothshaper.stages.KINDS`).
    wn : float
        Natural frequency of the mode [rad/s].
    zeta : float
        Its damping ratio (default 0).
    k : int
        Multiple of the zero placed on the mode (default 1).
    """
    kind: str
    wn: float
    zeta: float = 0.0
    k: int = 1


def start_values(stages, *, Ts: float) -> dict:
    """fmpy start values of the SmoothShaper FMU for a chain.

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        At most 8 stages; unused slots get ``stage[k].kind = -1``.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    dict
        Variable name -> value (kinds and choices as Integer codes).

    Raises
    ------
    ParameterError
        Naming ``stages`` when there are more than 8.
    """
    stages = list(stages)
    Ts = _positive("Ts", Ts)
    if len(stages) > 8:
        raise ParameterError("stages", f"stages must hold at most 8 stages, got {len(stages)}")
    values = {"Ts": float(Ts)}
    values.update({f"stage[{k}].kind": -1 for k in range(len(stages), 8)})   # unused: none
    for k, s in enumerate(stages):
        p = f"stage[{k}]."
        values.update({p + "kind": KIND_VALUES[s.kind], p + "k": s.k, p + "wn": s.wn,
                       p + "zeta": s.zeta})
        if isinstance(s, ModeStage):
            values[p + "design"] = 1
        else:
            values.update({p + "design": 0, p + "timing": TIMINGS.index(s.timing),
                           p + "T": s.T, p + "sigma": s.sigma, p + "order": s.order,
                           p + "tolerance": s.tolerance, p + "notch_pole_zeta": s.notch_pole_zeta,
                           p + "duration": s.duration})
    return values


def reference_stages(stages) -> list[Stage]:
    """The Stage list the NumPy reference filters: a ModeStage becomes
    :func:`smoothshaper.stages.for_mode`.

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        The chain given to the FMU.

    Returns
    -------
    list of Stage
        The same chain as plain stages.

    Raises
    ------
    ParameterError
        A ModeStage's mode is invalid (naming ``kind``, ``wn``, ``zeta`` or ``k``).
    """
    return [for_mode(s.kind, wn=s.wn, zeta=s.zeta, k=s.k) if isinstance(s, ModeStage) else s
            for s in stages]


def communication_points(*, step: float, stop_time: float) -> np.ndarray:
    """``t_k = k step``, ``k = 0 .. round(stop_time/step)``, as fmpy computes them.

    Parameters
    ----------
    step : float, keyword-only
        Communication step [s], > 0.
    stop_time : float, keyword-only
        Last point [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        The points [s].

    Raises
    ------
    ZeroDivisionError
        ``step`` is 0.
    """
    step, stop_time = _positive("step", step), _nonnegative("stop_time", stop_time)
    check_samples("step", stop_time / step + 1, "the communication points")
    n = int(round(stop_time / step))
    return np.arange(n + 1) * step


def tick_inputs(t: np.ndarray, u: np.ndarray, *, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """The input of every tick of the FMU's internal sample period and the ticks done by each
    communication point (the timing of the module docstring).

    Tick n is computed in the step from ``t_k`` with ``n_at[k] < n <= n_at[k+1]`` and filters
    ``u[k]`` (set at ``t_k``).

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s].
    u : ndarray of float64, shape (K,) or (K, m)
        Inputs set at them.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    x : ndarray of float64, shape (N,) or (N, m)
        The input of ticks 1..N.
    n_at : ndarray of int64, shape (K,)
        Ticks done by each ``t_k``.

    Raises
    ------
    IndexError
        ``u`` is shorter than ``t``.
    """
    t, u, Ts = _finite_signal("t", t), _finite_signal("u", u), _positive("Ts", Ts)
    if t.size == 0 or np.any(t < 0) or np.any(np.diff(t) < 0):
        raise ParameterError("t", "t must be communication points: non-empty, >= 0 and "
                             "non-decreasing")
    if u.size < t.size:
        raise ParameterError("u", f"u must hold a value for each of the {t.size} points of t, "
                             f"got {u.size}")
    check_samples("Ts", t[-1] / Ts + 1, "the ticks up to the last communication point")
    n_at = np.floor(t / Ts + TICK_SLACK).astype(np.int64)
    ticks = np.arange(1, int(n_at[-1]) + 1)
    step_of_tick = np.searchsorted(n_at, ticks, side="left") - 1
    return u[step_of_tick], n_at


def at_communication_points(y_ticks: np.ndarray, n_at: np.ndarray, rest) -> np.ndarray:
    """Outputs read at the communication points: the last tick's, the rest value before any.

    Parameters
    ----------
    y_ticks : ndarray of float64, shape (N,) or (N, m)
        Output of every tick.
    n_at : ndarray of int64, shape (K,)
        Ticks done by each communication point (:func:`tick_inputs`).
    rest : float or ndarray
        The output before the first tick.

    Returns
    -------
    ndarray of float64, shape (K,) or (K, m)
        The outputs fmpy records.

    Raises
    ------
    IndexError
        ``n_at`` counts more ticks than ``y_ticks`` holds.
    """
    out = np.empty((n_at.size,) + y_ticks.shape[1:])
    out[...] = rest
    done = n_at > 0
    out[done] = y_ticks[n_at[done] - 1]
    return out


def expected_output(stages, t: np.ndarray, u: np.ndarray, *, Ts: float,
                    rest: float | None = None) -> np.ndarray:
    """What the SmoothShaper FMU reports at the communication points, computed with the NumPy
    reference (the chain starts at rest at ``rest``; the timing of the module docstring).

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        The chain.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,)
        Inputs set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    rest : float or None, keyword-only
        Rest value (default ``u[0]``, the input at initialization).

    Returns
    -------
    ndarray of float64, shape (K,)
        The expected output ``y`` at ``t``.

    Raises
    ------
    ParameterError
        An invalid stage at ``Ts``.
    """
    x, n_at = tick_inputs(t, u, Ts=Ts)
    rest = float(np.asarray(u, dtype=float)[0]) if rest is None else _finite("rest", rest)
    y_ticks = reference.filter(reference_stages(stages), x - rest, Ts=Ts) + rest  # unit DC gain
    return at_communication_points(y_ticks, n_at, rest)


def expected_trajectory(t: np.ndarray, target: np.ndarray, *, Ts: float, **limits) -> np.ndarray:
    """What the TrajectoryGenerator FMU reports (columns q, v, a, j) at the communication points,
    from the NumPy reference of the generator
    (:func:`smoothshaper.trajectory.generator_reference`).

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    target : ndarray of float64, shape (K,)
        Targets set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    **limits
        ``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta`` and ``q0`` (the rest
        position, default 0) as the FMU's parameters.

    Returns
    -------
    ndarray of float64, shape (K, 4)
        q, v, a, j at ``t``.

    Raises
    ------
    ParameterError
        Invalid limits.
    """
    from .trajectory import generator_reference
    x, n_at = tick_inputs(t, target, Ts=Ts)
    limits = dict(limits)
    rest = _finite("q0", limits.pop("q0", 0.0))
    rows = generator_reference(x, Ts=Ts, position=rest, **limits) if x.size else np.zeros((0, 4))
    return at_communication_points(rows, n_at, np.array([rest, 0.0, 0.0, 0.0]))


def simulate(fmu: str, stages, t: np.ndarray, u: np.ndarray, *, Ts: float) -> np.ndarray:
    """Output of the SmoothShaper FMU simulated by fmpy with default settings and
    ``output_interval`` = the communication step.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain, set as start values.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,)
        Inputs set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        ``y`` at ``t``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    import fmpy
    step = float(t[1] - t[0])
    signal = np.zeros(t.size, dtype=[("time", float), ("u", float)])
    signal["time"], signal["u"] = t, u
    result = fmpy.simulate_fmu(fmu, start_values=start_values(stages, Ts=Ts), input=signal,
                               start_time=0.0, stop_time=float(t[-1]), output_interval=step,
                               output=["y"], validate=False)
    if result.size != t.size or not np.allclose(result["time"], t, rtol=0, atol=1e-9 * step):
        raise RuntimeError(f"fmpy returned {result.size} samples, expected {t.size}")
    return np.asarray(result["y"], dtype=float)


def test_input(t: np.ndarray, *, seed: int = 1) -> np.ndarray:
    """A staircase with steps of several sizes and both signs, then holding still."""
    rng = np.random.default_rng(seed)
    u = np.zeros_like(t)
    edges = np.linspace(0.05, 0.6, 6) * t[-1]
    for e in edges:
        u[t >= e] += rng.uniform(-2.0, 3.0)
    return u + 0.5   # a non-zero rest point exercises "initial u is the rest point"


def validation_cases(Ts: float) -> list[tuple[str, list]]:
    """The validation cases: every family (raw and designed for a mode, every timing)
    and a few chains, with durations and a mode off the sample grid.

    Parameters
    ----------
    Ts : float
        Sample period [s] the durations are scaled to.

    Returns
    -------
    list of (str, list)
        ``(name, stages)`` pairs.

    Raises
    ------
    ParameterError
        ``Ts`` so large that a stage is invalid.
    """
    wn, zeta = 2 * math.pi * 7.3, 0.08            # Td ~ 137 Ts at Ts = 1 ms: off the grid
    T = 21.37 * Ts
    cases = [
        ("rectangular", [rectangular(T=T)]),
        ("rectangular (paper)", [rectangular(T=T, timing="paper")]),
        ("rectangular (bounded)", [rectangular(T=T, timing="bounded")]),
        ("exponential (bounded)", [exponential(T=T, sigma=-9.0, timing="bounded")]),
        ("harmonic", [harmonic(T=T)]),
        ("damped_harmonic", [damped_harmonic(T=T, sigma=-12.0)]),
        ("exponential", [exponential(T=T, sigma=-9.0)]),
        ("zv", [shaper("zv", wn=wn, zeta=zeta)]),
        ("zvd", [shaper("zvd", wn=wn, zeta=zeta)]),
        ("zvdd", [shaper("zvdd", wn=wn, zeta=zeta)]),
        ("zvn (n=4)", [shaper("zvn", wn=wn, zeta=zeta, order=4)]),
        ("ei", [shaper("ei", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("ei2", [shaper("ei2", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("mzv", [shaper("mzv", wn=wn, zeta=zeta)]),
        ("ei3", [shaper("ei3", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("gmzv (n=5, 1.2 Td)", [shaper("gmzv", wn=wn, zeta=zeta, order=5, duration=1.2)]),
        ("zv (paper)", [shaper("zv", wn=wn, zeta=zeta, timing="paper")]),
        ("notch_tustin", [notch(wn=wn, zeta=0.02, notch_pole_zeta=0.5, discretization="tustin")]),
        ("notch_matched", [notch(wn=wn, zeta=0.02, notch_pole_zeta=0.5, discretization="matched")]),
        ("zvd for mode", [ModeStage("zvd", wn, zeta)]),
        ("damped_harmonic for mode", [ModeStage("damped_harmonic", wn, zeta)]),
        ("exponential for mode (k=2)", [ModeStage("exponential", wn, zeta, 2)]),
        ("chain M*M*S (double-S, harmonic end)",
         [rectangular(T=40 * Ts), rectangular(T=12.5 * Ts), harmonic(T=6.3 * Ts)]),
        ("chain M*ZV", [rectangular(T=30 * Ts), shaper("zv", wn=wn, zeta=zeta)]),
        ("chain M*M*S_sigma*notch", [rectangular(T=25 * Ts), rectangular(T=9 * Ts),
                                     damped_harmonic(T=T, sigma=-5.0),
                                     notch(wn=3 * wn, zeta=0.0, notch_pole_zeta=0.7)]),
    ]
    return cases


# ---------------------------------------------------------------- build and fmpy checks

def repo_root() -> Path:
    return Path(__file__).resolve().parents[2]


#: The FMUs and their model files under fmu/.
FMU_MODELS = {"SmoothShaper": "smoothshaper_model.c", "TrajectoryGenerator": "trajectory_model.c",
              "ElasticPlant": "elastic_plant_model.c", "MultiAxisGenerator": "multi_axis_model.c"}


def build_fmus(build_dir: Path, *, source_dir: Path | None = None) -> dict[str, Path]:
    """Configure and build the FMUs with CMake.

    Parameters
    ----------
    build_dir : Path
        CMake build folder (an existing build is reused).
    source_dir : Path or None, keyword-only
        Source checkout (default: the repository this package is installed from).

    Returns
    -------
    dict of str to Path
        Model name -> FMU file, for the FMUs that were built.

    Raises
    ------
    RuntimeError
        No FMU sources under ``source_dir``, or CMake not on PATH.
    subprocess.CalledProcessError
        CMake failed.
    """
    source_dir = Path(source_dir) if source_dir else repo_root()
    if not (source_dir / "fmu" / "CMakeLists.txt").is_file():
        raise RuntimeError(f"no FMU sources under {source_dir} (run from a source checkout)")
    cmake = shutil.which("cmake")
    if cmake is None:
        raise RuntimeError("cmake is not on PATH: it is needed to build the FMUs")
    subprocess.run([cmake, "-S", str(source_dir), "-B", str(build_dir), "-DSMS_BUILD_TESTS=OFF",
                    "-DSMS_BUILD_SHARED=OFF", f"-DPython3_EXECUTABLE={sys.executable}"],
                   check=True, stdout=subprocess.DEVNULL)
    targets = [m + "_fmu" for m, src in FMU_MODELS.items()
               if (source_dir / "fmu" / src).is_file()]
    subprocess.run([cmake, "--build", str(build_dir), "-j2", "--target", *targets], check=True,
                   stdout=subprocess.DEVNULL)
    found = {m: build_dir / "fmus" / f"{m}.fmu" for m in FMU_MODELS}
    return {m: p for m, p in found.items() if p.is_file()}


def fmpy_problems(fmu: Path) -> list[str]:
    """fmpy's validation of the FMU's model description.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.

    Returns
    -------
    list of str
        The problems found (empty: none).

    Raises
    ------
    ImportError
        fmpy is not installed.
    """
    from fmpy.validation import validate_fmu
    return list(validate_fmu(str(fmu)))


def fmutool_problems(fmu: Path) -> list[str]:
    """``fmutool -input FMU -check`` (fmu-manipulation-toolbox).

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.

    Returns
    -------
    list of str
        The problems reported (empty: it passed; one entry if fmutool is not installed).

    Raises
    ------
    OSError
        fmutool cannot be started.
    """
    exe = shutil.which("fmutool") or str(Path(sys.executable).with_name("fmutool"))
    if not Path(exe).is_file():
        return ["fmutool not found (pip install fmu-manipulation-toolbox)"]
    run_ = subprocess.run([exe, "-input", str(fmu), "-check"], capture_output=True, text=True)
    text = run_.stdout + run_.stderr
    problems = [line.strip() for line in text.splitlines() if "ERROR" in line or "WARNING" in line]
    if "No semantic error" not in text or "compliant" not in text:
        problems.append("fmutool did not report the FMU compliant")
    return problems


def simulate_libcosim(fmu: str, t: np.ndarray, u: np.ndarray, params: dict, *, input_name: str = "u",
                      outputs=("y",)) -> np.ndarray:
    """Outputs of an FMU in libcosim (libcosimpy), the second importer.

    Fixed step ``t[1] - t[0]``, the input overridden before every step (as fmpy sets it),
    outputs read after the step; row 0 is the rest point (libcosim observes only after steps)
    and is left NaN.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,)
        Inputs set at ``t``.
    params : dict
        Start values: int values are set as Integers (the FMUs' choice codes), the others as
        Reals.
    input_name : str, keyword-only
        The input variable (default ``"u"``).
    outputs : sequence of str, keyword-only
        Output variables, one column each (default ``("y",)``).

    Returns
    -------
    ndarray of float64, shape (K, len(outputs))
        The outputs at ``t`` (row 0 NaN).

    Raises
    ------
    RuntimeError
        libcosim refused an initial value or a step failed.
    """
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave
    log_output_level(CosimLogLevel.ERROR)
    vr = {v.name: v.valueReference for v in read_model_description(fmu).modelVariables}
    step_ns = int(round((t[1] - t[0]) * 1e9))
    execution = CosimExecution.from_step_size(step_size=step_ns)
    index = execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=str(fmu), instance_name="s"))
    override = CosimManipulator.create_override()
    execution.add_manipulator(manipulator=override)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    for name, value in {**params, input_name: float(u[0])}.items():
        if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
            accepted = execution.integer_initial_value(index, vr[name], int(value))
        else:
            accepted = execution.real_initial_value(index, vr[name], float(value))
        if not accepted:
            raise RuntimeError(f"libcosim refused the initial value of {name}")
    y = np.full((t.size, len(outputs)), np.nan)
    out_vrs = [vr[n] for n in outputs]
    for k in range(t.size - 1):
        override.slave_real_values(index, [vr[input_name]], [float(u[k])])
        if not execution.step():
            raise RuntimeError(f"libcosim step {k} failed")
        y[k + 1] = observer.last_real_values(index, out_vrs)
    return y


def compare_importers(fmu: Path, stages, *, Ts: float = 1e-3,
                      stop_time: float = 0.3) -> tuple[float, float]:
    """The SmoothShaper FMU with the chain ``stages`` in libcosim and in fmpy, and fmpy against
    the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain.
    Ts : float, keyword-only
        Sample period and communication step [s] (default 1e-3).
    stop_time : float, keyword-only
        Length of the run [s] (default 0.3).

    Returns
    -------
    tuple of float
        ``(max |y_libcosim - y_fmpy|, max |y_fmpy - reference|)``.

    Raises
    ------
    RuntimeError
        An importer failed.
    """
    t = communication_points(step=Ts, stop_time=stop_time)
    u = test_input(t)
    y_cosim = simulate_libcosim(str(fmu), t, u, start_values(stages, Ts=Ts))[1:, 0]
    y_fmpy = simulate(str(fmu), stages, t, u, Ts=Ts)
    ref = expected_output(stages, t, u, Ts=Ts)
    return float(np.max(np.abs(y_cosim - y_fmpy[1:]))), float(np.max(np.abs(y_fmpy - ref)))


def compare_importers_trajectory(fmu: Path, *, Ts: float = 1e-3, stop_time: float = 1.0,
                                 profile: int = 0, wn: float = 0.0, zeta: float = 0.0) -> float:
    """The TrajectoryGenerator FMU in libcosim and in fmpy for one profile.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    Ts : float, keyword-only
        Sample period and communication step [s] (default 1e-3).
    stop_time : float, keyword-only
        Length of the run [s] (default 1).
    profile : int, keyword-only
        Integer code: 0 polynomial, 1 trigonometric, 2 damped (with the mode wn, zeta).
    wn : float, keyword-only
        Mode of the damped profile [rad/s].
    zeta : float, keyword-only
        Its damping ratio.

    Returns
    -------
    float
        ``max |(q, v, a, j)_libcosim - (q, v, a, j)_fmpy|``.

    Raises
    ------
    RuntimeError
        An importer failed.
    """
    t = communication_points(step=Ts, stop_time=stop_time)
    target = target_staircase(t)
    params = {"Ts": Ts, **TRAJECTORY_LIMITS, "profile": int(profile), "wn": wn, "zeta": zeta}
    y_cosim = simulate_libcosim(str(fmu), t, target, params, input_name="target", outputs="qvaj")
    y_fmpy = simulate_trajectory(str(fmu), t, target, Ts=Ts, **TRAJECTORY_LIMITS,
                                 profile=int(profile), wn=wn, zeta=zeta)
    return float(np.max(np.abs(y_cosim[1:] - y_fmpy[1:])))


#: The TrajectoryGenerator profiles the importer comparison runs (the damped one with a mode).
TRAJECTORY_PROFILES = (("polynomial", dict(profile=0)), ("trigonometric", dict(profile=1)),
                       ("damped", dict(profile=2, wn=60.0, zeta=0.1)))


# ---------------------------------------------------------------- report

def compare(fmu: Path, stages, *, Ts: float, step: float, stop_time: float):
    """One SmoothShaper run by fmpy against the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain.
    Ts : float, keyword-only
        The FMU's sample period [s].
    step : float, keyword-only
        Communication step [s] (any multiple or fraction of Ts).
    stop_time : float, keyword-only
        Length of the run [s].

    Returns
    -------
    tuple
        ``(t, u, y, y_ref, err, rel)``: points, inputs, FMU and reference outputs, the
        maximum absolute error and the error relative to ``max |y_ref|``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    t = communication_points(step=step, stop_time=stop_time)
    u = test_input(t)
    y = simulate(str(fmu), stages, t, u, Ts=Ts)
    y_ref = expected_output(stages, t, u, Ts=Ts)
    err = float(np.max(np.abs(y - y_ref)))
    rel = err / max(float(np.max(np.abs(y_ref))), 1e-300)
    return t, u, y, y_ref, err, rel


TRAJECTORY_LIMITS = dict(vmax=1.0, amax=10.0, jmax=200.0)


def target_staircase(t: np.ndarray) -> np.ndarray:
    """Targets for the TrajectoryGenerator runs: via-points with a reversal mid-motion, a target
    arriving mid-motion and a tiny step.

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        The target at each point [m].

    Raises
    ------
    IndexError
        ``t`` is empty.
    """
    t = _finite_array("t", t)
    x = np.full(t.shape, 0.1)
    for at, value in ((0.05, 0.4), (0.4, 0.0), (0.45, 0.35), (1.0, 0.3501)):
        x[t >= at] = value
    return x


def simulate_trajectory(fmu: str, t: np.ndarray, target: np.ndarray, *, Ts: float, **limits):
    """Outputs q, v, a, j of the TrajectoryGenerator FMU simulated by fmpy.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    target : ndarray of float64, shape (K,)
        Targets set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    **limits
        The FMU's parameters (``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta``,
        ``q0``).

    Returns
    -------
    ndarray of float64, shape (K, 4)
        q, v, a, j at ``t``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    import fmpy
    step = float(t[1] - t[0])
    signal = np.zeros(t.size, dtype=[("time", float), ("target", float)])
    signal["time"], signal["target"] = t, target
    r = fmpy.simulate_fmu(fmu, start_values=dict(Ts=Ts, **limits), input=signal, start_time=0.0,
                          stop_time=float(t[-1]), output_interval=step, output=list("qvaj"),
                          validate=False)
    return np.column_stack([np.asarray(r[c], dtype=float) for c in "qvaj"])


def compare_trajectory(fmu: Path, *, Ts: float, step: float, stop_time: float, **limits):
    """One TrajectoryGenerator run by fmpy against the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    Ts : float, keyword-only
        The FMU's sample period [s].
    step : float, keyword-only
        Communication step [s].
    stop_time : float, keyword-only
        Length of the run [s].
    **limits
        The FMU's parameters.

    Returns
    -------
    tuple
        ``(t, target, y, ref, rel)``: points, targets, FMU and reference outputs (K, 4) and
        the relative maximum errors of q, v, a, j.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    limits = limits or TRAJECTORY_LIMITS
    t = communication_points(step=step, stop_time=stop_time)
    target = target_staircase(t)
    y = simulate_trajectory(str(fmu), t, target, Ts=Ts, **limits)
    ref = expected_trajectory(t, target, Ts=Ts, **limits)
    rel = np.max(np.abs(y - ref), axis=0) / np.max(np.abs(ref), axis=0)
    return t, target, y, ref, rel


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
             "and reports the last tick's output (see `smoothshaper.validation`).", "",
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
