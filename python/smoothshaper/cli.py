# SPDX-License-Identifier: Apache-2.0
"""The smoothshaper command line: design, analyze, identify, calibrate, validate, report.

A stage is written KIND:key=value,key=value (--stage, repeatable; stages chain in the given
order). KIND is one of rectangular, harmonic, damped_harmonic, exponential, zv, zvd, zvdd, zvn,
ei, ei2, ei3, mzv, gmzv, notch_tustin, notch_matched ('notch' means notch_matched). Keys:
T [s], sigma [1/s], k, wn [rad/s], zeta, order, tolerance, duration (gmzv, in damped periods),
notch_pole_zeta, timing (exact, paper, or bounded for rectangular and exponential). A
smoother given wn (and optionally zeta, k) instead of T is designed for that mode. Examples:
harmonic:T=0.05, zv:wn=100,zeta=0.05, damped_harmonic:wn=125,zeta=0.12.

Trajectory forms: 'design generator' runs via-points through the online generator, 'design
bspline' interpolates them with a B-spline (see 'smoothshaper design generator --help' and
'smoothshaper design bspline --help').

Exit codes: 0 success, 1 invalid input or failed run (one line on stderr), 2 bad usage,
3 the subcommand's module is not available in this installation.
"""
from __future__ import annotations

import argparse
import math
import os
import re
import sys

import numpy as np

from . import stages as _stages
from .cli_common import (EXIT_ERROR, EXIT_UNAVAILABLE, EXIT_USAGE, CliError,  # noqa: F401
                         Parser as _Parser, decimate, format_table,
                         pyplot as _pyplot)
from .errors import ParameterError
from .stages import Stage

__all__ = ["parse_stage", "stage_rows", "cmd_design", "cmd_analyze",
           "read_record", "first_two_peaks", "cmd_identify", "cmd_validate", "cmd_report",
           "build_parser", "main"]

# Optional dependencies and the pyproject extra that installs each.
_EXTRA_FOR_MODULE = {"scipy": "analysis", "matplotlib": "plot", "fmpy": "validate",
                     "libcosimpy": "validate", "fmu_manipulation_toolbox": "validate"}

_KEY_ALIASES = {"pole_zeta": "notch_pole_zeta"}
_INT_KEYS = ("k", "order")
_FLOAT_KEYS = ("T", "sigma", "wn", "zeta", "tolerance", "notch_pole_zeta", "duration")


# -- stage specs ---------------------------------------------------------------------------

def parse_stage(spec: str) -> Stage:
    """One ``--stage`` spec (see the module docstring) -> Stage. ParameterError (a ValueError)
    naming ``stage`` on bad syntax."""
    kind, _, rest = spec.partition(":")
    kind = kind.strip().lower()
    if kind == "notch":
        kind = "notch_matched"
    if kind not in _stages.KINDS:
        raise ParameterError(
            "stage", f"stage {spec!r}: kind must be one of {', '.join(_stages.KINDS)}, "
                     "or notch")
    fields: dict = {}
    for item in filter(None, (p.strip() for p in rest.split(","))):
        key, eq, value = item.partition("=")
        key = _KEY_ALIASES.get(key.strip(), key.strip())
        if not eq:
            raise ParameterError("stage", f"stage {spec!r}: expected key=value, got {item!r}")
        if key in fields:
            raise ParameterError("stage", f"stage {spec!r}: {key} given twice")
        if key in _INT_KEYS:
            try:
                fields[key] = int(value)
            except ValueError:
                raise ParameterError(
                    "stage", f"stage {spec!r}: {key} must be an integer, got {value!r}") from None
        elif key in _FLOAT_KEYS:
            try:
                fields[key] = float(value)
            except ValueError:
                raise ParameterError(
                    "stage", f"stage {spec!r}: {key} must be a number, got {value!r}") from None
        elif key == "timing":
            fields[key] = value.strip()
        else:
            raise ParameterError(
                "stage", f"stage {spec!r}: unknown key {key!r} (keys: T, sigma, k, wn, zeta, "
                         "order, tolerance, duration, notch_pole_zeta, timing)")
    if kind in _stages.SMOOTHERS and "T" not in fields and "wn" in fields:
        from .filters import design_for_mode
        unused = set(fields) - {"wn", "zeta", "k", "timing"}
        if unused:
            raise ParameterError(
                "stage", f"stage {spec!r}: {', '.join(sorted(unused))} cannot be combined "
                         "with wn (the mode sets the smoother)")
        stage = design_for_mode(kind, wn=fields["wn"], zeta=fields.get("zeta", 0.0),
                                k=fields.get("k", 1))
        return stage.with_(timing=fields.get("timing", "exact"))
    if kind in _stages.SMOOTHERS and "T" not in fields:
        raise ParameterError(
            "stage", f"stage {spec!r}: a {kind} stage needs T=<seconds> or wn=<rad/s>")
    return Stage(kind, **fields)


def _chain_from_args(args) -> list[Stage]:
    stages = [parse_stage(s) for s in (args.stage or [])]
    for kind in getattr(args, "kind", None) or []:
        if args.wn is None:
            raise CliError("--wn is required with --kind (the mode to design for)")
        from .filters import design_for_mode
        stage = design_for_mode(kind, wn=args.wn, zeta=args.zeta, k=args.k)
        if kind == "zvn":
            stage = stage.with_(order=args.order)
        if kind in ("ei", "ei2", "ei3"):
            stage = stage.with_(tolerance=args.tolerance)
        stages.append(stage)
    return stages


# -- output helpers ------------------------------------------------------------------------

def _shaper_duration(stage: Stage) -> float | None:
    """Time of a shaper's last impulse [s] (C sms_shaper_impulses), None for other kinds."""
    if stage.kind not in _stages.SHAPERS:
        return None
    from .filters import _backend, _fill_config
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    _fill_config(config, stage)
    amps, times = ffi.new("double[64]"), ffi.new("double[64]")
    count = ffi.new("size_t *")
    if lib.sms_shaper_impulses(config, amps, times, 64, count) != 0:
        return None
    return max(times[i] for i in range(count[0]))


def _duration(stage: Stage) -> float | None:
    if stage.kind in _stages.SMOOTHERS:
        return stage.T
    return _shaper_duration(stage)


def stage_rows(stages: list[Stage], Ts: float | None) -> tuple[list[str], list[list]]:
    header = ["#", "kind", "T [s]", "sigma [1/s]", "wn [rad/s]", "zeta", "k", "order", "timing"]
    if Ts is not None:
        header.append("L [samples]")
    rows = []
    for i, s in enumerate(stages):
        smoother = s.kind in _stages.SMOOTHERS
        row = [i, s.kind, _duration(s), s.sigma if smoother else None,
               None if smoother else s.wn, None if smoother else s.zeta,
               s.k if smoother else None, s.order if s.kind == "zvn" else None,
               None if s.kind in _stages.NOTCHES else s.timing]
        if Ts is not None:
            from .filters import Chain, ParameterError
            try:
                row.append(Chain([s], Ts=Ts).length or "IIR")
            except ParameterError as exc:    # name the stage by its place in the whole chain
                raise ParameterError(exc.parameter, str(exc).replace(
                    "stages[0]", f"stages[{len(rows)}]"), exc.status) from None
        rows.append(row)
    return header, rows


# -- subcommands ---------------------------------------------------------------------------

def cmd_design(args) -> int:
    kinematic = [args.h, args.vmax, args.amax, args.jmax]
    if any(v is not None for v in kinematic):
        if args.h is None or args.vmax is None:
            raise CliError("kinematic design needs at least --h and --vmax")
        if args.jmax is not None and args.amax is None:
            raise CliError("--jmax needs --amax (the bounds are consecutive derivatives: "
                           "--vmax, --amax, --jmax)")
        try:
            from .design import kinematic as design_kinematic
        except ImportError as exc:
            raise CliError(f"kinematic design is unavailable in this installation ({exc})",
                           EXIT_UNAVAILABLE) from None
        stages = list(design_kinematic(h=args.h, vmax=args.vmax, amax=args.amax,
                                       jmax=args.jmax, profile=args.profile,
                                       wn=args.wn, zeta=args.zeta, Ts=args.Ts))
        stages += _chain_from_args(argparse.Namespace(stage=args.stage, kind=None))
    else:
        stages = _chain_from_args(args)
    if not stages:
        raise CliError("nothing to design: give --kind with --wn, --stage, or --h/--vmax limits")
    header, rows = stage_rows(stages, args.Ts)
    print(format_table(header, rows))
    total = sum(d for d in (_duration(s) for s in stages) if d is not None)
    print(f"total duration (delay of the chain): {total:.6g} s")
    if args.Ts is not None:
        from .filters import Chain
        chain = Chain(stages, Ts=args.Ts)
        print(f"chain FIR length at Ts={args.Ts:g} s: {chain.length} samples"
              + ("" if chain.is_fir else " (plus IIR notch)"))
    return 0


def _analysis():
    try:
        from . import analysis
    except ImportError as exc:
        raise CliError(f"analyze is unavailable: smoothshaper.analysis cannot be imported ({exc})",
                       EXIT_UNAVAILABLE) from None
    return analysis


def _nominal_mode(args, stages: list[Stage]) -> tuple[float, float]:
    if args.wn is not None:
        return args.wn, args.zeta
    for s in stages:
        if s.kind not in _stages.SMOOTHERS:
            return s.wn, s.zeta
    raise CliError("--wn is required: the mode to analyse (no shaper/notch in the chain names one)")


#: Points of analyze's magnitude plot and of the grid its insensitivity search starts from.
SPECTRUM_POINTS = 4000
BAND_POINTS = 2001
#: Most points of the PRV sweep (and of each axis of the surface): 8 MB per array, checked
#: before any is allocated (the cost model refuses long runs well below it).
MAX_SWEEP_POINTS = 1_000_000


def _step_samples(length: int, is_fir: bool, wn_hat: float, Ts: float) -> int:
    """Samples of analyze's step response: the FIR length and a fifth more, or (with an IIR
    notch) four periods of the mode."""
    return (length if is_fir else 0) + max(10, length // 5) + (
        0 if is_fir else int(round(4 * 2 * math.pi / wn_hat / Ts)))


def cmd_analyze(args) -> int:
    from ._plotting import percent_axis, prv_map
    from .cli_cost import LIMIT_SECONDS, PLOT_POINTS, analyze_cost, chain_taps, start
    stages = _chain_from_args(args)
    if not stages:
        raise CliError("nothing to analyze: give --stage (or --kind with --wn)")
    wn_hat, zeta = _nominal_mode(args, stages)
    if not 0 < args.ratio_min < args.ratio_max < math.inf:
        raise CliError(f"--ratio-min={args.ratio_min:.3g} and --ratio-max={args.ratio_max:.3g} "
                       f"must be finite with 0 < min < max")
    if not 2 <= args.points <= MAX_SWEEP_POINTS:
        raise CliError(f"--points must be in 2..{MAX_SWEEP_POINTS}, got {args.points}")
    if args.surface and not 2 <= args.surface_points <= MAX_SWEEP_POINTS:
        raise CliError(f"--surface-points must be in 2..{MAX_SWEEP_POINTS}, got "
                       f"{args.surface_points}")
    if not (math.isfinite(args.Ts) and args.Ts > 0):
        raise CliError(f"--Ts must be finite and > 0, got {args.Ts!r}")
    ratios = np.linspace(args.ratio_min, args.ratio_max, args.points)
    ratios = ratios[ratios * wn_hat < math.pi / args.Ts]       # modes below Nyquist only
    if ratios.size < 2:
        raise CliError(f"--wn={wn_hat:.3g}, --ratio-max={args.ratio_max:.3g}, --Ts={args.Ts:.3g}: "
                       f"the swept modes (from {args.ratio_min:.3g} to {args.ratio_max:.3g} "
                       f"times wn) lie above the Nyquist frequency pi/Ts = "
                       f"{math.pi / args.Ts:.3g} rad/s: lower --wn, --ratio-max or --Ts")

    # The cost of every phase from the sizes alone (nothing allocated yet): announce or refuse.
    taps = chain_taps(stages, args.Ts)
    is_fir = not any(s.kind in _stages.NOTCHES for s in stages)
    n_step = _step_samples(taps, is_fir, wn_hat, args.Ts)
    surface_points = args.surface_points * ratios.size if args.surface else 0

    def model(sweep, surface):
        return analyze_cost(taps=taps, sweep=sweep, band=BAND_POINTS + 100, surface=surface,
                            spectrum=SPECTRUM_POINTS, step=n_step,
                            plotted=sweep + SPECTRUM_POINTS + min(n_step, PLOT_POINTS) + surface)
    cost = model(ratios.size, surface_points)
    if model(min(ratios.size, 600), 61 * min(ratios.size, 600) if args.surface else 0
             ).seconds > LIMIT_SECONDS:
        cost.blame = {}   # too long at the default counts too: the chain (--Ts) is to blame
    bar = start(cost, args, f"chain of {taps} samples, {ratios.size} sweep points"
                + (f", {surface_points} surface points" if args.surface else ""))
    if bar is None:
        return 0

    from .filters import Chain
    analysis = _analysis()
    plt = _pyplot()
    os.makedirs(args.out, exist_ok=True)
    bar.phase("taps")
    chain = Chain(stages, Ts=args.Ts)
    response = analysis.ChainResponse(stages, Ts=args.Ts, progress=bar.advance)
    work = max(1, response.taps)

    bar.phase("PRV sweep", ratios.size * work)
    prv = analysis.prv_curve(response, wn_hat=wn_hat, ratio=ratios, zeta=zeta)
    bar.phase("band", (BAND_POINTS + 100) * work)
    prv_nominal = float(analysis.prv(response, wn=wn_hat, zeta=zeta))
    try:
        band = analysis.insensitivity(response, wn_hat=wn_hat, zeta=zeta,
                                      tolerance=args.tolerance, points=BAND_POINTS,
                                      span=(args.ratio_min, min(args.ratio_max, ratios[-1])))
        band_text = (f"[{band.low / wn_hat:.4g}, {band.high / wn_hat:.4g}] x wn_hat, "
                     f"relative width {band.relative_width:.4g}")
    except ValueError as exc:
        band_text = f"not bounded inside the sweep ({exc})"
    plots = ["prv.png", "spectrum.png", "step.png"]

    if args.surface:
        zetas = np.linspace(0.0, args.zeta_max, args.surface_points)
        bar.phase("PRV surface", surface_points * work)
        surface = analysis.prv_surface(response, wn=ratios * wn_hat, zeta=zetas)
        fig, ax = plt.subplots(figsize=(7, 4.5))
        # Colour bands on a log-like scale clipped at 200 % (far off the mode PRV runs to
        # 1e4 %, and a linear scale would paint 0..100 % one colour), labelled contours at
        # the levels users compare against.
        prv_map(ax, ratios, zetas, surface)
        ax.set_xlabel(r"actual / nominal natural frequency $\omega_n/\hat\omega_n$ [-]")
        ax.set_ylabel(r"damping ratio $\zeta$ [-]")
        ax.set_title("Residual vibration over frequency and damping")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "prv_surface.png"), dpi=120)
        plt.close(fig)
        plots.append("prv_surface.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(ratios, prv, label="PRV of the chain")
    ax.axhline(100 * args.tolerance, color="gray", ls="--", lw=0.8,
               label=f"{100 * args.tolerance:g} % tolerance")
    percent_axis(ax, top=max(110.0, 1.2 * float(np.max(prv))))
    ax.set_xlabel(r"actual / nominal natural frequency $\omega_n/\hat\omega_n$ [-]")
    ax.set_ylabel("PRV [%] (log scale above 1 %)")
    ax.set_title(f"Residual vibration, zeta = {zeta:g}, wn_hat = {wn_hat:g} rad/s")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "prv.png"), dpi=120)
    plt.close(fig)

    w = np.geomspace(min(wn_hat, math.pi / args.Ts) / 100, math.pi / args.Ts, SPECTRUM_POINTS)
    bar.phase("spectrum", w.size * work)
    mag = np.abs(np.asarray(analysis.frequency_response(response, w)))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogx(w, 20 * np.log10(np.maximum(mag, 1e-12)))
    ax.axvline(wn_hat, color="gray", ls="--", lw=0.8, label=f"mode {wn_hat:g} rad/s")
    ax.set_xlabel("frequency [rad/s]")
    ax.set_ylabel("|H| [dB]")
    ax.set_ylim(-140, 10)
    ax.set_title("Magnitude of the discrete chain")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "spectrum.png"), dpi=120)
    plt.close(fig)

    bar.phase("step response")
    n = _step_samples(chain.length, chain.is_fir, wn_hat, args.Ts)
    y = chain.process(np.ones(n))
    t = np.arange(n) * args.Ts
    bar.phase("plots")
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(*decimate(t, y, PLOT_POINTS), label="filtered unit step (C core)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("output [-]")
    ax.set_title("Step response")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "step.png"), dpi=120)
    plt.close(fig)

    bar.finish()
    print(format_table(*stage_rows(stages, args.Ts)))
    print(f"Ts: {args.Ts:g} s; chain length: {chain.length} samples "
          f"({chain.length * args.Ts:.6g} s){'' if chain.is_fir else ' plus IIR notch'}")
    print(f"mode analysed: wn_hat = {wn_hat:g} rad/s, zeta = {zeta:g}")
    print(f"PRV at the nominal mode: {prv_nominal:.6g} %")
    print(f"insensitivity (PRV <= {100 * args.tolerance:g} %): {band_text}")
    print(f"step response: final value {y[-1]:.12g}, max {y.max():.12g}, min {y.min():.12g}")
    print(f"plots: {', '.join(os.path.join(args.out, f) for f in plots)}")
    return 0


def read_record(path: str, column: str | None, time_column: str | None,
                Ts: float | None) -> tuple[np.ndarray, float]:
    """(x, Ts) from a CSV: optional header row (also a '#time,accel_x,...' comment line right
    above the data), comma/semicolon/tab/space separated; errors name the file and row."""
    from .calibrate.records import read_table
    header, data, rows = read_table(path)

    def index(name, default):
        if name is None:
            return default
        if header is not None and name in header:
            return header.index(name)
        try:
            i = int(name)
        except ValueError:
            raise CliError(f"{path}: no column {name!r}"
                           + (f" (columns: {', '.join(header)})" if header else "")) from None
        if not -data.shape[1] <= i < data.shape[1]:
            raise CliError(f"{path}: column index {i} out of range ({data.shape[1]} columns)")
        return i

    xi = index(column, data.shape[1] - 1)
    x = data[:, xi]
    if Ts is None:
        if data.shape[1] < 2 and time_column is None:
            raise CliError(f"{path}: one column only: give --Ts (the sample period)")
        ti = index(time_column, 0) % data.shape[1]
        t = data[:, ti]
        dt = np.diff(t)
        if dt.size == 0:
            raise CliError(f"{path}: a single data row: a record needs at least two samples")
        bad = np.flatnonzero(~(dt > 0))
        if bad.size:
            i = int(bad[0]) + 1
            raise CliError(f"{path}, row {int(rows[i])}, column {ti}: time {t[i]:.6g} s does "
                           f"not increase (previous {t[i - 1]:.6g} s): time stamps must be "
                           "strictly increasing")
        Ts = float(np.mean(dt))
        if np.max(np.abs(dt - Ts)) > 1e-6 * Ts + 1e-12:
            # jittered time stamps (real accelerometer logs): resample onto a uniform grid
            from scipy.interpolate import CubicSpline
            if np.max(dt) > 5 * Ts:
                i = int(np.argmax(dt)) + 1
                raise CliError(f"{path}, row {int(rows[i])}: a gap of {dt[i - 1]:.6g} s before "
                               f"time {t[i]:.6g} s: the record is not contiguous")
            x = CubicSpline(t - t[0], x)(np.arange(t.size) * Ts)
    return x, Ts


def first_two_peaks(x: np.ndarray, Ts: float) -> tuple[float, float, float, float]:
    """(t1, p1, t2, p2): the first two successive positive maxima of x about its final value
    (the mean of the record's last tenth, so a settled decay with an offset works), each
    refined by a parabola through the sample and its neighbours (peaks of a damped sinusoid
    are exactly one damped period apart, so their spacing and ratio give wd and sigma)."""
    x = x - np.mean(x[-max(1, x.size // 10):])
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]) & (x[1:-1] > 0)) + 1
    if i.size < 2:
        raise CliError("the record has fewer than two positive peaks: cannot use --method peaks")
    out = []
    for j in i[:2]:
        a, b, c = x[j - 1], x[j], x[j + 1]
        denom = a - 2 * b + c
        shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
        out += [(j + shift) * Ts, b - 0.25 * (a - c) * shift]
    return tuple(out)


def cmd_identify(args) -> int:
    from .cli_cost import record_cost, start
    from .filters import identify_from_peaks, identify_from_record
    nbytes = os.path.getsize(args.csv) if os.path.isfile(args.csv) else 0
    bar = start(record_cost("identify", nbytes=nbytes), args, f"a record of {nbytes} bytes")
    if bar is None:
        return 0
    bar.phase("read and fit")
    if args.Ts is not None and not (math.isfinite(args.Ts) and args.Ts > 0):
        raise CliError(f"--Ts must be finite and > 0, got {args.Ts:.3g}")
    x, Ts = read_record(args.csv, args.column, args.time_column, args.Ts)
    if args.start is not None:
        duration = x.size * Ts
        if not (math.isfinite(args.start) and 0 <= args.start < duration):
            raise CliError(f"--start must be a time within the record [0, {duration:.3g}) s, "
                           f"got {args.start:.3g}")
        x = x[int(round(args.start / Ts)):]
    # a sweep or noise must not yield a confident mode: the whole record has to be explained
    # by damped oscillations (calibrate.modes.decay_modes); it also gives the uncertainties
    from .calibrate.modes import decay_modes
    try:
        fitted, r2 = decay_modes(x, Ts, path=args.csv, column=args.column or "signal")
        if args.method == "peaks":
            t1, p1, t2, p2 = first_two_peaks(x, Ts)
            mode = identify_from_peaks(t1=t1, p1=p1, t2=t2, p2=p2)
        else:
            mode = identify_from_record(x, Ts=Ts)
    except (CliError, ValueError) as exc:
        if args.Ts is None:
            raise
        # the record's own time scale was overridden: name the option with the failure
        raise CliError(f"{exc} (with --Ts={args.Ts:.3g})") from None
    if args.method == "peaks":
        print(f"peaks about the final value: ({t1:.6g} s, {p1:.6g}) and ({t2:.6g} s, {p2:.6g})")
    bar.finish()
    print(f"record: {x.size} samples at Ts = {Ts:.6g} s")
    print(format_table(["wn [rad/s]", "zeta", "wd [rad/s]", "sigma [1/s]", "Td [s]"],
                       [[mode.wn, mode.zeta, mode.wd, mode.sigma, 2 * math.pi / mode.wd]]))
    m = fitted[0]
    print(f"whole-record fit (explains {100 * r2:.1f} % of the signal): wn = {m.wn:.6g} +- "
          f"{m.wn_std:.2g} rad/s (f = {m.f_hz:.5g} Hz), zeta = {m.zeta:.4g} +- "
          f"{m.zeta_std:.2g} (1 sd)"
          + (f"; {len(fitted) - 1} further mode(s): see 'smoothshaper calibrate'"
             if len(fitted) > 1 else ""))
    print("suggested stages: "
          f"damped_harmonic:wn={mode.wn:.6g},zeta={mode.zeta:.6g}  "
          f"zv:wn={mode.wn:.6g},zeta={mode.zeta:.6g}")
    return 0


def _run_module(name: str, module_name: str, out_dir: str, args, cost, sizes: str,
                **options) -> int:
    """Call smoothshaper.<module_name>.run(out_dir) for the subcommand ``name``: a missing
    module is reported (exit 3), not a crash; then the request's estimate (``cost(module)``,
    see :func:`smoothshaper.cli_cost.start`) and a bar whose phases the module names through
    ``run(..., progress=)``."""
    import importlib
    import inspect

    from .cli_cost import start
    modname = f"smoothshaper.{module_name}"
    try:
        module = importlib.import_module(modname)
    except ModuleNotFoundError as exc:
        if exc.name == modname:
            raise CliError(f"{name} is unavailable: module {modname} is not part of this "
                           "installation yet", EXIT_UNAVAILABLE) from None
        raise CliError(f"{name} is unavailable: it needs the Python package {exc.name!r} "
                       "(pip install 'smoothshaper[validate]')", EXIT_UNAVAILABLE) from None
    run = getattr(module, "run", None)
    if run is None:
        raise CliError(f"{name} is unavailable: {modname} has no run(out_dir)", EXIT_UNAVAILABLE)
    bar = start(cost(module), args, sizes)
    if bar is None:
        return 0
    if "progress" in inspect.signature(run).parameters:
        options["progress"] = lambda phase: bar.phase(phase)
    try:
        result = run(out_dir, **options)
    finally:
        bar.finish()
    if result is False or (isinstance(result, int) and not isinstance(result, bool) and result):
        return EXIT_ERROR
    print(f"{name}: results written to {out_dir}")
    return 0


def cmd_validate(args) -> int:
    from .cli_cost import validate_cost
    build = args.build_dir or os.path.join(args.out, "build")
    built = os.path.isdir(os.path.join(build, "fmus"))
    options = {"build_dir": args.build_dir} if args.build_dir else {}
    return _run_module("validate", "validation", args.out, args,
                       lambda module: validate_cost(built=built),
                       "FMUs already built" if built else "the FMUs to build first", **options)


def cmd_report(args) -> int:
    from .cli_cost import report_cost

    def cost(module):
        sections = getattr(module, "SECTIONS", ())
        unknown = [k for k in args.only or () if k not in sections]
        if unknown:
            raise CliError(f"--only: unknown section {unknown[0]!r} (sections: "
                           f"{', '.join(sections)})")
        return report_cost(list(args.only or sections))

    options = {"only": args.only} if args.only else {}
    return _run_module("report", "report", args.out, args, cost,
                       f"{len(args.only)} section(s)" if args.only else "all sections", **options)


# -- parser --------------------------------------------------------------------------------

def _kind_arg(text: str) -> str:
    """--kind value: kind names compare case-insensitively; 'notch' means notch_matched."""
    try:
        return _stages.kind_name(text)
    except ValueError:
        return text          # argparse then reports it against the choices


def _add_chain_options(p, *, with_kind: bool = True) -> None:
    p.add_argument("--stage", action="append", metavar="STAGE",
                   help="a stage KIND:key=value,... (repeatable; see 'smoothshaper --help')")
    if with_kind:
        p.add_argument("--kind", action="append", choices=_stages.KINDS, type=_kind_arg,
                       help="design a stage of this kind for the mode --wn/--zeta (repeatable)")
    p.add_argument("--wn", type=float, help="natural frequency of the mode [rad/s]")
    p.add_argument("--zeta", type=float, default=0.0, help="damping ratio of the mode (default 0)")
    p.add_argument("--k", type=int, default=1, help="multiple of the zero placed on the mode "
                   "(odd for the harmonic families; default 1)")
    if with_kind:
        p.add_argument("--order", type=int, default=1, help="n of --kind zvn (default 1)")
    p.add_argument("--tolerance", type=float, default=0.05,
                   help="vibration tolerance V: the residual --kind ei/ei2 accept at the mode, "
                   "and the PRV level of analyze's insensitivity band (default 0.05 = 5 %%)")
    # The old name of --tolerance for design (deprecated, hidden).
    p.add_argument("--shaper-tolerance", dest="tolerance", type=float, help=argparse.SUPPRESS)


def build_parser() -> argparse.ArgumentParser:
    from .cli_cost import add_options as add_cost_options
    parser = _Parser(prog="smoothshaper", description=__doc__,
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    from . import __version__
    parser.add_argument("--version", action="version", version=f"smoothshaper {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    p = sub.add_parser("design", help="print the stages for a mode or kinematic limits; "
                       "'design generator' / 'design bspline' run via-points (see their --help)",
                       description="Without FORM: the stages for a mode (--kind/--stage with "
                       "--wn) or for kinematic limits (--h, --vmax, ...). With FORM (optional): "
                       "'generator' runs via-points through the online generator, 'bspline' "
                       "interpolates them; see 'smoothshaper design FORM --help'.")
    _add_chain_options(p)
    p.add_argument("--Ts", type=float, help="sample period [s]: also print lengths in samples; "
                   "a kinematic design is then made on this grid (see below)")
    g = p.add_argument_group(
        "kinematic limits", "A step of --h through the chain keeps |v| <= vmax, |a| <= amax, "
        "|j| <= jmax. With --Ts every stage lasts a whole number of samples, chosen so that the "
        "sampled differences keep every bound (docs/sampled-limits.md); without it, the "
        "continuous optimum. With --wn (and --zeta) the last stage is also tuned to that mode.")
    g.add_argument("--h", type=float, help="displacement")
    g.add_argument("--vmax", type=float, help="velocity limit")
    g.add_argument("--amax", type=float, help="acceleration limit")
    g.add_argument("--jmax", type=float, help="jerk limit (needs --amax)")
    g.add_argument("--profile", default="polynomial",
                   choices=("polynomial", "trigonometric", "damped"),
                   help="last stage: polynomial = moving average, trigonometric = half sine, "
                   "damped = exponential for the mode --wn/--zeta (default polynomial)")
    p.set_defaults(func=cmd_design)
    from .cli_trajectory import add_design_forms
    add_design_forms(p, _Parser)

    p = sub.add_parser("analyze", help="PRV curve, spectrum and step response as PNG plots",
                       description="Analyse a chain (--stage/--kind) against a vibration mode "
                       "(--wn, --zeta): writes prv.png (percent residual vibration over the "
                       "actual-to-nominal frequency ratio, with the insensitivity band at "
                       "--tolerance), spectrum.png (magnitude of the discrete chain in dB over "
                       "frequency) "
                       "and step.png (step response), and prints the insensitivity band. "
                       "--surface adds prv_surface.png over frequency ratio and damping. "
                       "Residual vibration and PRV are defined in docs/analysis.md.")
    _add_chain_options(p)
    p.add_argument("--Ts", type=float, default=1e-3, help="sample period [s] (default 1e-3)")
    p.add_argument("--out", default="analysis", help="output folder for the PNGs (default ./analysis)")
    p.add_argument("--ratio-min", type=float, default=0.2, help="sweep start, wn/wn_hat (default 0.2)")
    p.add_argument("--ratio-max", type=float, default=3.0, help="sweep end, wn/wn_hat (default 3)")
    p.add_argument("--points", type=int, default=600, help="sweep points (default 600)")
    p.add_argument("--surface", action="store_true",
                   help="also write prv_surface.png: PRV over wn/wn_hat and zeta")
    p.add_argument("--zeta-max", type=float, default=0.3, help="surface damping range (default 0.3)")
    p.add_argument("--surface-points", type=int, default=61,
                   help="surface damping rows (default 61)")
    add_cost_options(p)
    p.set_defaults(func=cmd_analyze)

    p = sub.add_parser("identify", help="mode (wn, zeta) from a CSV record of a free decay",
                       description="Estimate the natural frequency wn [rad/s] and damping ratio "
                       "zeta of one mode from a sampled free decay (a CSV with a time column and "
                       "a signal column, or one column with --Ts), and suggest stages that "
                       "cancel it. Example data: examples/decay.csv. For accelerometer sweeps, "
                       "PSD tables and several modes use 'smoothshaper calibrate'.")
    p.add_argument("csv", help="CSV file: a time column and a signal column (header optional)")
    p.add_argument("--column", help="signal column: header name or index (default: last)")
    p.add_argument("--time-column", help="time column: header name or index (default: first)")
    p.add_argument("--Ts", type=float, help="sample period [s] when the file has no time column")
    p.add_argument("--start", type=float, help="ignore samples before this time [s]")
    p.add_argument("--method", choices=("record", "peaks"), default="record",
                   help="record: least-squares fit of the whole decay, any constant offset "
                   "included (default); peaks: two successive peaks, measured about the "
                   "final value (the mean of the record's last tenth)")
    add_cost_options(p)
    p.set_defaults(func=cmd_identify)

    from .cli_calibrate import add_parser as add_calibrate
    add_calibrate(sub)

    descriptions = {
        "validate": "Build the FMUs with CMake, check their model descriptions (fmpy, fmutool), "
                    "simulate every stage family and several chains with fmpy at several "
                    "communication step sizes and with libcosim, and compare with the NumPy "
                    "reference (docs/cosimulation.md). Writes README.md (tables of maximum "
                    "errors) and plots into --out; exit code 1 if any comparison fails.",
        "report": "Reproduce the numerical claims of the source papers (docs/references.md) "
                  "and of the shaper literature: every claim is recomputed, compared with its "
                  "closed form or published value within a stated tolerance, and listed with "
                  "figures in --out/README.md; exit code 1 if a claim fails."}
    for name, func, what in (("validate", cmd_validate, "build and validate the FMUs with fmpy"),
                             ("report", cmd_report, "reproduce the source papers' claims "
                              "(docs/references.md)")):
        p = sub.add_parser(name, help=what, description=descriptions[name])
        p.add_argument("--out", default=os.path.join("out", name),
                       help=f"output folder (default ./out/{name})")
        if name == "validate":
            p.add_argument("--build-dir", help="CMake build folder for the FMUs (default: "
                           "OUT/build); an existing build there is reused")
        if name == "report":
            p.add_argument("--only", nargs="+", metavar="SECTION",
                           help="build only these sections (e.g. seed000 seed004)")
        add_cost_options(p)
        p.set_defaults(func=func)
    return parser


def _os_error(exc: OSError, argv: list[str]) -> str:
    """A failed file operation named by the option the user gave for the path (``--out=x:
    File exists (not a folder)``) instead of Python's ``[Errno 17] File exists: 'x'``."""
    if exc.filename is None or not exc.strerror:
        return str(exc)
    path = os.fsdecode(exc.filename)
    given = [f"{name}={value}" for name, value in _given(argv) if value == path]
    why = exc.strerror + (" (not a folder)" if isinstance(exc, FileExistsError) else "")
    return f"{given[0] if given else path}: {why}"


def _given(argv: list[str]) -> list[tuple[str, str]]:
    """(option, value) pairs as the user wrote them (--x=v or --x v)."""
    pairs = []
    for i, a in enumerate(argv):
        if a.startswith("--"):
            name, eq, value = a.partition("=")
            if not eq and i + 1 < len(argv) and not argv[i + 1].startswith("--"):
                value = argv[i + 1]
            pairs.append((name, value))
    return pairs


def _option_for(parameter: str, message: str, argv: list[str]) -> str | None:
    """The options the user gave that a library ParameterError comes from: those whose values
    the message shows (``vmax[1]=...`` -> ``--vmax=1,2 (axis 1)``), else the option of
    ``parameter`` itself (or of the same name with a prefix, ``--shaper-tolerance``); a
    stage's field (``stages[0]``, ``T``) -> its ``--stage``/``--kind``; None if none."""
    given = _given(argv)
    options = {name: value for name, value in given}

    def shown(name, index=""):
        return f"{name}={options[name]}" + (f" (axis {index})" if index else "")
    found = []
    for m in re.finditer(r"(?<![\w\[-])([A-Za-z_]+)(?:\[(\d+)\])? ?=", message):
        name = "--" + m.group(1).replace("_", "-")
        if name in options and not any(f.startswith(name + "=") for f in found):
            found.append(shown(name, m.group(2) or ""))
    base, _, index = parameter.partition("[")
    base, index = base.replace("_", "-"), index.rstrip("]")
    if not found:
        same = [n for n in options if n == f"--{base}" or n.endswith(f"-{base}")]
        # of two options for one parameter (--tolerance, --shaper-tolerance): the one whose
        # value the message quotes
        quoted = [n for n in same if any(_quotes(message, v) for v in options[n].split(","))]
        if quoted or same:
            found.append(shown((quoted or same)[-1], index if index.isdigit() else ""))
    if not found:
        spec = next((v for n, v in given if n == "--stage" and f"{base}=" in v), None)
        if spec is not None:
            found.append(f"--stage {spec}")
    stage = re.search(r"stages\[(\d+)\]", message + " " + parameter)
    if stage and "--h" in options and not any(n in options for n in ("--stage", "--kind")):
        # the stages of a kinematic design come from its bounds
        found = [shown(n) for n in ("--h", "--vmax", "--amax", "--jmax") if n in options] + [
            f for f in found if f.startswith("--Ts=")]
    specs = [f"{n} {v}" for n, v in given if n in ("--stage", "--kind")]
    if stage and specs and not any(f.startswith(("--stage", "--kind")) for f in found):
        i = int(stage.group(1))
        found.insert(0, specs[i] if i < len(specs) else specs[-1])
    if not found and base in ("targets", "via") and "--via" in options:
        found.append("--via")
    if found and "--Ts" in options and not any(f.startswith("--Ts=") for f in found) and (
            " Ts=" in message or "T/Ts" in message):
        found.append(shown("--Ts"))      # a duration in samples: set by the two together
    return ", ".join(found) or None


def _quotes(message: str, text: str) -> bool:
    """Does the message quote the number the user wrote as ``text`` (in any usual form)?"""
    try:
        x = float(text)
    except ValueError:
        return False
    return any(form in message for form in (repr(x), f"{x:g}", f"{x:.6g}", text))


def _readable(message: str) -> str:
    """Numbers with more than 6 significant digits as %.6g (integers of 10 or more digits as
    %.3g): an error line stays readable whatever the value."""
    def short(m):
        text = m.group(0)
        digits = len(re.sub(r"[^0-9]", "", text.split("e")[0].split("E")[0]).lstrip("0"))
        if "." not in text and "e" not in text.lower():
            return f"{float(text):.3g}" if digits >= 10 else text
        return f"{float(text):.6g}" if digits > 7 else text
    return re.sub(r"(?<![\w.])\d+(?:\.\d*)?(?:[eE][-+]?\d+)?", short, message)


#: Longest error line (longer ones keep their start and end around " [...] ").
MAX_MESSAGE = 600


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the exit code (errors: one line on stderr, no traceback). A
    library ParameterError is prefixed with the option the user gave for it (``--jmax=...``)
    and every number in an error is printed readably (at most 7 significant digits)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = build_parser().parse_args(argv)
        return args.func(args)
    except BrokenPipeError:
        # The reader went away (e.g. `| head`): not an error worth a message.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_ERROR
    except CliError as exc:
        code, message = exc.code, str(exc)
    except ModuleNotFoundError as exc:
        extra = _EXTRA_FOR_MODULE.get((exc.name or "").split(".")[0])
        if extra is None:
            raise
        code, message = EXIT_UNAVAILABLE, (
            f"this command needs the Python package {exc.name.split('.')[0]!r}: "
            f"pip install 'smoothshaper[{extra}]'")
    except ParameterError as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, str(exc)
        option = _option_for(exc.parameter, message, argv)
        if option is not None and not message.startswith(option):
            message = f"{option}: {message}"
    except OSError as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, _os_error(exc, argv)
    except (ValueError, RuntimeError, ImportError) as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, str(exc)
    except KeyboardInterrupt:
        code, message = 130, "interrupted"
    message = _readable(" ".join(message.split()))
    if len(message) > MAX_MESSAGE:     # an echoed argument of 100 kB (--stage xxx...)
        message = message[:MAX_MESSAGE - 100] + " [...] " + message[-93:]
    if not message.startswith("smoothshaper"):
        message = f"smoothshaper: error: {message}"
    sys.stderr.write(message + "\n")
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
