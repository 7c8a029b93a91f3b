# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper design generator`` and ``smoothshaper design bspline``.

* ``generator``: a staircase of via-points through the C-backed online generator
  (:class:`smoothshaper.trajectory.Generator`); each via-point is held until the output rests
  on it (or for ``--hold`` seconds), and a table per segment gives the arrival time and the
  sampled peaks of |v|, |a|, |j| against the limits.
* ``bspline``: the C-backed B-spline interpolating filter
  (:class:`smoothshaper.trajectory.BSpline`): knot spacing (from the lowest mode with
  ``--wn``), control points, and the instant and the error with which each via-point is
  passed.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from .common import EXIT_ERROR, CliError, decimate, format_table, run_samples
from .common import numbers as _numbers, parse_via_list, parse_via_points
from .common import pyplot as _pyplot, save_figure as _save, write_outputs
from .cost import PLOT_POINTS, add_options as add_cost_options, start, trajectory_cost

__all__ = ["LIMIT_RTOL", "REST_RTOL", "MAX_SAMPLES", "MAX_BSPLINE_VALUES", "PROFILES", "parse_via_list",
           "parse_via_points", "run_until_reached", "run_with_hold", "segment_rows",
           "cmd_generator", "cmd_bspline", "add_design_forms"]

# The C core keeps every bound "to a few ulps" (trajectory.h); 1e-9 relative is far above
# that and far below any real violation.
LIMIT_RTOL = 1e-9
# Rest on the target: q, v, a, j within this fraction of the move's scale and of the limits.
REST_RTOL = 1e-9
# Refuse generator runs so long that their tables and plots would take minutes.
MAX_SAMPLES = 5_000_000
# Refuse B-spline outputs above this many values (samples x axes; 160 MB per array).
MAX_BSPLINE_VALUES = 20_000_000
PROFILES = ("polynomial", "trigonometric", "damped")


def _at_rest(out: np.ndarray, target: float, scale: float, limits) -> np.ndarray:
    """Mask of samples where q == target and v, a, j == 0, up to rounding."""
    vmax, amax, jmax = limits
    return ((np.abs(out[:, 0] - target) <= REST_RTOL * scale)
            & (np.abs(out[:, 1]) <= REST_RTOL * vmax)
            & (np.abs(out[:, 2]) <= REST_RTOL * amax)
            & (np.abs(out[:, 3]) <= REST_RTOL * jmax))


def run_until_reached(gen, via: np.ndarray, scale: float, max_samples: int):
    """Feed via[1], via[2], ... each until the output rests on it, the next from the sample
    after. Returns (targets, out, starts, arrivals) with sample indices.

    Chunks of Nc samples are stepped at once; when the arrival falls inside a chunk the state
    saved before it is restored and only the samples up to the arrival are replayed, so the
    result is exactly what per-sample stepping would give."""
    limits = (gen.vmax, gen.amax, gen.jmax)
    chunk = max(64, gen.tail_samples)   # tail_samples: the tuned stage's taps (0: none)
    targets, outs, starts, arrivals = [], [], [], []
    k = 0
    for p in via[1:]:
        starts.append(k)
        while True:
            if k >= max_samples:
                raise CliError(f"the output did not reach {p:g} within {max_samples} samples "
                               "(raise --Ts)")
            saved = gen.get_state()
            block = np.full(chunk, p)
            out = gen.process(block)
            hit = np.flatnonzero(_at_rest(out, p, scale, limits))
            if hit.size:
                n = hit[0] + 1
                gen.set_state(saved)
                out = gen.process(block[:n])
                targets.append(block[:n])
                outs.append(out)
                k += n
                arrivals.append(k - 1)
                break
            targets.append(block)
            outs.append(out)
            k += chunk
    return np.concatenate(targets), np.concatenate(outs), starts, arrivals


def run_with_hold(gen, via: np.ndarray, hold_samples: int, scale: float, max_samples: int):
    """Each of via[1], via[2], ... held for hold_samples; the last until the output rests on
    it. Arrival of a segment: first rest on its target inside its window, else None."""
    limits = (gen.vmax, gen.amax, gen.jmax)
    head = np.repeat(via[1:-1], hold_samples)
    out_head = gen.process(head)
    _, out_last, _, last_arrival = run_until_reached(gen, via[-2:], scale,
                                                     max_samples - head.size)
    out = np.concatenate([out_head, out_last])
    targets = np.concatenate([head, np.full(out_last.shape[0], via[-1])])
    starts = [i * hold_samples for i in range(via.size - 1)]
    arrivals = []
    for i, p in enumerate(via[1:-1]):
        window = out[starts[i]:starts[i] + hold_samples]
        hit = np.flatnonzero(_at_rest(window, p, scale, limits))
        arrivals.append(starts[i] + int(hit[0]) if hit.size else None)
    arrivals.append(head.size + last_arrival[0])
    return targets, out, starts, arrivals


def segment_rows(out, starts, arrivals, via, Ts, limits):
    """One row per segment: #, target, start, arrival, peaks and peak/limit ratios."""
    rows = []
    ends = starts[1:] + [out.shape[0]]
    for i, (s, e) in enumerate(zip(starts, ends)):
        peaks = np.max(np.abs(out[s:e, 1:4]), axis=0)
        a = arrivals[i]
        rows.append([i + 1, float(via[i + 1]), s * Ts, None if a is None else a * Ts,
                     *[float(v) for v in peaks],
                     *[float(v / lim) for v, lim in zip(peaks, limits)]])
    return rows


def _limit(option: str):
    """The argument type of --vmax/--amax/--jmax: one number, or one per axis ('1,2,3') for
    multi-axis via-points; errors name ``option``."""
    def parse(text: str):
        values = _numbers(option, text)
        return values[0] if len(values) == 1 else text
    return parse


_ONE_AXIS = ("vmin", "amin", "qmin", "qmax")
_MULTI_TOO = ("qmin", "qmax")   # one per axis with multi-axis via-points


def _generator(Generator, args):
    """The single-axis Generator of the options; a refused lower bound or position limit
    names its option."""
    extra = {name: getattr(args, name) for name in _ONE_AXIS}
    try:
        return Generator(vmax=args.vmax, amax=args.amax, jmax=args.jmax, Ts=args.Ts,
                         profile=args.profile, wn=args.wn, zeta=args.zeta, **extra)
    except ParameterError as exc:
        if exc.parameter in _ONE_AXIS:
            raise CliError(f"--{exc.parameter}: {exc}") from None
        raise


def _outside(args, via) -> None:
    """Via-points outside --qmin/--qmax: refused naming the option and the point."""
    if args.qmin is None or args.qmax is None:
        return
    for i, x in enumerate(np.asarray(via, dtype=float)):
        if not args.qmin <= x <= args.qmax:
            side = "--qmin" if x < args.qmin else "--qmax"
            raise CliError(f"{side}: --via point {i} ({x:.6g}) is outside [qmin, qmax] = "
                           f"[{args.qmin:.6g}, {args.qmax:.6g}]")


def cmd_generator(args) -> int:
    from ..trajectory import Generator
    if ";" in (args.via or "") or any(isinstance(x, str) for x in (
            args.vmax, args.amax, args.jmax, args.qmin, args.qmax)):
        given = [f"--{n}" for n in _ONE_AXIS if getattr(args, n) is not None
                 and n not in _MULTI_TOO]
        if given:
            raise CliError(f"{', '.join(given)}: one axis only (the multi-axis generator has "
                           "symmetric limits)")
        from .multi_axis import cmd_multi_generator
        return cmd_multi_generator(args)
    if any(x is not None for x in (args.via_velocity, args.via_acceleration, args.start,
                                   args.velocity)):
        return cmd_generator_targets(args)
    if args.via is None:
        raise CliError("--via is required (or --velocity for the velocity interface)")
    via = parse_via_list(args.via)
    gen = _generator(Generator, args)
    _outside(args, via)
    gen.reset(position=float(via[0]))
    scale = max(float(np.max(np.abs(via))), gen.vmax * gen.Ts)
    limits = (gen.vmax, gen.amax, gen.jmax)
    # A move of D takes at most D/vmax + Tc: the velocity rise (vmax/amax + amax/jmax, times
    # pi/2 for the half-cosine transitions) and the stage tuned to a mode; each term is
    # charged to the option it comes from, so a refusal names the one that makes the run long.
    moves = via.size - 1
    # the slower side's bounds (--vmin, --amin) for the estimate
    V, A = min(gen.vmax, -gen.vmin), min(gen.amax, -gen.amin)
    terms = [(f"--via point {i + 1} ({b:.3g})", abs(b - a) / V,
              "bring it closer or raise --vmax") for i, (a, b) in enumerate(zip(via[:-1], via[1:]))]
    terms += [(f"--vmax={gen.vmax:.3g}, --amax={gen.amax:.3g}", 3 * moves * gen.vmax / A,
               "raise --amax or lower --vmax"),
              (f"--amax={gen.amax:.3g}, --jmax={gen.jmax:.3g}",
               3 * moves * math.pi / 2 * gen.amax / gen.jmax, "raise --jmax or lower --amax"),
              (f"--wn={gen.wn or 0:.3g}", 3 * moves * gen.stage_duration, "raise --wn")]
    hold_samples = None
    if args.hold is not None:
        if not (math.isfinite(args.hold) and args.hold >= gen.Ts):
            raise CliError(f"--hold must be a time >= Ts = {gen.Ts:.3g} s, got {args.hold:.3g}")
        terms.append((f"--hold={args.hold:.3g}", (via.size - 2) * args.hold, "shorten --hold"))
    max_samples = run_samples(terms, gen.Ts, MAX_SAMPLES, extra=10 * (via.size + 1))
    if args.hold is not None:
        hold_samples = int(round(args.hold / gen.Ts))
    cost = trajectory_cost("generator", samples=max_samples, axes=1, csv=bool(args.csv),
                           plot=bool(args.plot))
    bar = start(cost, args, f"at most {max_samples} samples")
    if bar is None:
        return 0
    bar.phase("generator")
    if args.hold is None:
        targets, out, starts, arrivals = run_until_reached(gen, via, scale, max_samples)
    else:
        targets, out, starts, arrivals = run_with_hold(gen, via, hold_samples, scale,
                                                       max_samples)
    t = np.arange(out.shape[0]) * gen.Ts
    u = args.unit
    rows = segment_rows(out, starts, arrivals, via, gen.Ts, limits)
    print(f"online generator: vmax = {gen.vmax:g} {u}/s, amax = {gen.amax:g} {u}/s^2, "
          f"jmax = {gen.jmax:g} {u}/s^3, profile {gen.profile}"
          + (f", mode wn = {gen.wn:g} rad/s, zeta = {gen.zeta:g}" if gen.wn else ""))
    print("time-optimal plan to each target"
          + (f", then the stage tuned to the mode: {gen.stage_duration:.6g} s "
             f"({gen.tail_samples} samples at Ts = {gen.Ts:g} s)" if gen.wn else
             f" (Ts = {gen.Ts:g} s)")
          + f"; start at rest at {via[0]:g} {u}")
    print("each via-point held until the output rests on it" if args.hold is None else
          f"each via-point held {hold_samples} samples ({hold_samples * gen.Ts:g} s), "
          "the last until the output rests on it")
    print(format_table(["#", f"target [{u}]", "start [s]", "arrival [s]", "peak |v|",
                        "peak |a|", "peak |j|", "v/vmax", "a/amax", "j/jmax"], rows))
    missed = [r[0] for r in rows if r[3] is None]
    if missed:
        print("not reached before the next target (--hold): segment "
              + ", ".join(str(m) for m in missed))
    total = arrivals[-1] * gen.Ts
    print(f"total time: {total:.6g} s ({arrivals[-1] + 1} samples, rest on {via[-1]:g} {u})")
    peaks = np.max(np.abs(out[:, 1:4]), axis=0)
    ok = all(p <= lim * (1 + LIMIT_RTOL) for p, lim in zip(peaks, limits))
    print("sampled peaks within the limits: " + ("yes" if ok else "NO (exceeded)"))
    write_outputs(args, bar, lambda: (
        ["time", "target", "position", "velocity", "acceleration", "jerk"],
        [t, targets, out[:, 0], out[:, 1], out[:, 2], out[:, 3]]),
        lambda path: _plot_generator(path, t, targets, out, starts, arrivals, limits, u, gen.Ts,
                                     f"{gen.profile} profile" + (
                                         f", mode {gen.wn:g} rad/s, zeta {gen.zeta:g}"
                                         if gen.wn else "")))
    return 0 if ok else EXIT_ERROR


def _per_target(option: str, text, count: int) -> np.ndarray:
    """--via-velocity / --via-acceleration: one value per target (default 0)."""
    if text is None:
        return np.zeros(count)
    values = np.array(_numbers(option, text))
    if values.size != count:
        raise CliError(f"{option} needs one value per target ({count}), got {values.size}")
    return values


def run_targets(gen, targets, hold_samples, max_samples):
    """Feed each target (position, velocity, acceleration, interface) until the plan has
    reached it (Generator.arrival) or for hold_samples, the last until reached. Returns the
    per-sample target columns, out, the segment starts and arrivals (None: not reached within
    its hold)."""
    cols = [[], [], [], []]
    outs, starts, arrivals = [], [], []
    k = 0
    for i, (p, v, a, interface) in enumerate(targets):
        last = i == len(targets) - 1
        starts.append(k)
        first = gen.process(np.array([p]), velocity=v, acceleration=a, interface=interface)
        remaining = gen.arrival
        n = remaining if (hold_samples is None or last) else hold_samples - 1
        if k + 1 + n > max_samples:
            raise CliError(f"target {i + 1} is not reached within {max_samples} samples "
                           "(raise --Ts)")
        rest = gen.process(np.full(n, p), velocity=v, acceleration=a, interface=interface)
        outs += [first, rest]
        for c, x in zip(cols, (p, v, a, interface)):
            c += [x] * (1 + n)
        arrivals.append(k + remaining if remaining <= n else None)
        k += 1 + n
    return ([np.array(c) for c in cols[:3]] + [np.array(cols[3])], np.concatenate(outs),
            starts, arrivals)


def cmd_generator_targets(args) -> int:
    """Targets beyond rest: via-points reached with a velocity and an acceleration, a start
    state in motion, or the velocity interface (--velocity)."""
    from ..trajectory import Generator
    gen = _generator(Generator, args)
    if args.velocity is not None:
        if args.via_velocity is not None or args.via_acceleration is not None:
            raise CliError("--velocity (the velocity interface) takes no --via-velocity or "
                           "--via-acceleration: its values are the velocities to reach")
        via = parse_via_list(args.via + ",0") if args.via is not None else np.zeros(2)
        if via.size != 2:
            raise CliError("--via with --velocity is the start position alone (one number)")
        speeds = np.array(_numbers("--velocity", args.velocity))
        targets = [(0.0, float(v), 0.0, "velocity") for v in speeds]
        if args.hold is None and speeds.size > 1:
            raise CliError("--velocity with several velocities needs --hold SECONDS (how long "
                           "each is held)")
    else:
        if args.via is None:
            raise CliError("--via is required (or --velocity for the velocity interface)")
        via = parse_via_list(args.via)
        _outside(args, via)
        vel = _per_target("--via-velocity", args.via_velocity, via.size - 1)
        acc = _per_target("--via-acceleration", args.via_acceleration, via.size - 1)
        targets = [(float(p), float(v), float(a), "position")
                   for p, v, a in zip(via[1:], vel, acc)]
    v0, a0 = 0.0, 0.0
    if args.start is not None:
        state = _numbers("--start", args.start)
        if len(state) != 2:
            raise CliError("--start is the start velocity and acceleration: V,A")
        v0, a0 = state
    first = targets[0]
    try:
        if first[3] == "velocity":
            gen.start_from(float(via[0]), v0, a0, interface="velocity", velocity=first[1])
        else:
            gen.start_from(float(via[0]), v0, a0, target=first[0], velocity=first[1],
                           acceleration=first[2])
    except ParameterError as exc:
        option = {"v": "--start", "a": "--start", "velocity": "--via-velocity",
                  "acceleration": "--via-acceleration", "target": "--via", "qmin": "--qmin",
                  "qmax": "--qmax"}.get(exc.parameter, "--via")
        raise CliError(f"{option}: {exc}") from None
    limits = (gen.vmax, gen.amax, gen.jmax)
    hold_samples = None
    if args.hold is not None:
        if not (math.isfinite(args.hold) and args.hold >= gen.Ts):
            raise CliError(f"--hold must be a time >= Ts = {gen.Ts:.3g} s, got {args.hold:.3g}")
        hold_samples = int(round(args.hold / gen.Ts))
    # the run's size from the distances, the limits and the holds (each term named)
    moves = len(targets)
    span = float(np.ptp(np.r_[via, [t[0] for t in targets]]))
    V, A = min(gen.vmax, -gen.vmin), min(gen.amax, -gen.amin)
    terms = [("--via", 2 * moves * span / V, "bring the points closer or raise --vmax"),
             (f"--vmax={gen.vmax:.3g}, --amax={gen.amax:.3g}", 4 * moves * gen.vmax / A,
              "raise --amax or lower --vmax"),
             (f"--amax={gen.amax:.3g}, --jmax={gen.jmax:.3g}",
              4 * moves * math.pi / 2 * gen.amax / gen.jmax, "raise --jmax or lower --amax"),
             (f"--wn={gen.wn or 0:.3g}", 3 * moves * gen.stage_duration, "raise --wn")]
    if args.hold is not None:
        terms.append((f"--hold={args.hold:.3g}", moves * args.hold, "shorten --hold"))
    max_samples = run_samples(terms, gen.Ts, MAX_SAMPLES, extra=10 * (moves + 2))
    cost = trajectory_cost("generator", samples=max_samples, axes=1, csv=bool(args.csv),
                           plot=bool(args.plot))
    bar = start(cost, args, f"at most {max_samples} samples")
    if bar is None:
        return 0
    bar.phase("generator")
    try:
        cols, out, starts, arrivals = run_targets(gen, targets, hold_samples, max_samples)
    except ParameterError as exc:
        option = {"velocity": "--via-velocity", "acceleration": "--via-acceleration"}.get(
            exc.parameter, "--via")
        if args.velocity is not None:
            option = "--velocity"
        raise CliError(f"{option}: {exc}") from None
    t = np.arange(out.shape[0]) * gen.Ts
    u = args.unit
    print(f"online generator: vmax = {gen.vmax:g} {u}/s, amax = {gen.amax:g} {u}/s^2, "
          f"jmax = {gen.jmax:g} {u}/s^3, profile {gen.profile}"
          + (f", mode wn = {gen.wn:g} rad/s, zeta = {gen.zeta:g}" if gen.wn else ""))
    print(f"start at {via[0]:g} {u} moving at {v0:g} {u}/s, {a0:g} {u}/s^2; "
          + ("each velocity reached in the least time (the velocity interface)"
             if args.velocity is not None else
             "each via-point reached in the least time with its velocity and acceleration, "
             "exactly on a sample")
          + ("" if hold_samples is None else
             f"; each held {hold_samples} samples ({hold_samples * gen.Ts:g} s), the last until "
             "reached"))
    rows = []
    ends = starts[1:] + [out.shape[0]]
    for i, (s0, e, a) in enumerate(zip(starts, ends, arrivals)):
        peaks = np.max(np.abs(out[s0:e, 1:4]), axis=0)
        state = out[a] if a is not None else [None] * 3
        rows.append([i + 1, *([None] if args.velocity is not None else [targets[i][0]]),
                     targets[i][1], *([] if args.velocity is not None else [targets[i][2]]),
                     s0 * gen.Ts, None if a is None else a * gen.Ts,
                     *[None if x is None else float(x) for x in state[:3]],
                     *[float(p / lim) for p, lim in zip(peaks, limits)]])
    if args.velocity is not None:
        rows = [[r[0]] + r[2:] for r in rows]
        head = ["#", f"velocity [{u}/s]", "start [s]", "arrival [s]", f"q [{u}]",
                f"v [{u}/s]", f"a [{u}/s^2]", "v/vmax", "a/amax", "j/jmax"]
    else:
        head = ["#", f"target [{u}]", f"velocity [{u}/s]", f"acceleration [{u}/s^2]",
                "start [s]", "arrival [s]", f"q [{u}]", f"v [{u}/s]", f"a [{u}/s^2]",
                "v/vmax", "a/amax", "j/jmax"]
    print(format_table(head, rows))
    missed = [r[0] for r, a in zip(rows, arrivals) if a is None]
    if missed:
        print("not reached before the next target (--hold): segment "
              + ", ".join(str(m) for m in missed))
    peaks = np.max(np.abs(out[:, 1:4]), axis=0)
    ok = all(p <= lim * (1 + LIMIT_RTOL) for p, lim in zip(peaks, limits))
    print(f"total time: {(out.shape[0] - 1) * gen.Ts:.6g} s ({out.shape[0]} samples)")
    print("sampled peaks within the limits: " + ("yes" if ok else "NO (exceeded)"))
    what = f"{gen.profile} profile" + (f", mode {gen.wn:g} rad/s" if gen.wn else "")
    write_outputs(args, bar, lambda: (
        ["time", "target_position", "target_velocity", "target_acceleration", "position",
         "velocity", "acceleration", "jerk"],
        [t, cols[0], cols[1], cols[2], out[:, 0], out[:, 1], out[:, 2], out[:, 3]]),
        lambda path: _plot_generator(
            path, t, None if args.velocity is not None else cols[0], out, starts, arrivals,
            limits, u, gen.Ts, what, velocity_targets=cols[1],
            arrival_states=None if args.velocity is not None else [
                (targets[i][0], targets[i][1]) for i in range(len(targets))],
            title="Online generator, the velocity interface" if args.velocity is not None
            else "Online generator, via-points reached moving"))
    return 0 if ok else EXIT_ERROR


def _plot_generator(path, t, targets, out, starts, arrivals, limits, u, Ts, what="",
                    velocity_targets=None, arrival_states=None,
                    title="Online multi-point generator"):
    plt = _pyplot("design generator --plot")
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 8))
    names = [("position", f"[{u}]"), ("velocity", f"[{u}/s]"),
             ("acceleration", f"[{u}/s$^2$]"), ("jerk", f"[{u}/s$^3$]")]
    if targets is not None:
        axes[0].step(*decimate(t, targets, PLOT_POINTS), where="post", color="gray", lw=0.8,
                     ls="--", label="target")
    if velocity_targets is not None and (targets is None or np.any(velocity_targets != 0)):
        axes[1].step(*decimate(t, velocity_targets, PLOT_POINTS), where="post", color="gray",
                     lw=0.8, ls="--", label="target velocity")
    if arrival_states is not None:
        for a, (q, v) in zip(arrivals, arrival_states):
            if a is not None:
                axes[0].plot(a * Ts, q, "o", ms=5, mfc="none", color="green")
                axes[1].plot(a * Ts, v, "o", ms=5, mfc="none", color="green")
    for i, (ax, (name, unit)) in enumerate(zip(axes, names)):
        if i == 3:  # jerk: right limits at the samples, piecewise constant between
            ax.step(*decimate(t, out[:, i], PLOT_POINTS), where="post", lw=1.2, label=name)
        else:
            ax.plot(*decimate(t, out[:, i], PLOT_POINTS), lw=1.2, label=name)
        if i:
            lim = limits[i - 1]
            ax.axhline(lim, color="red", lw=0.7, ls=":", label="limit")
            ax.axhline(-lim, color="red", lw=0.7, ls=":")
        for a in arrivals:
            if a is not None:
                ax.axvline(a * Ts, color="green", lw=0.5, alpha=0.5)
        ax.set_ylabel(f"{name} {unit}")
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="best", fontsize=8)
    axes[1].legend(loc="best", fontsize=8)
    axes[-1].set_xlabel("time [s]")
    axes[0].set_title(f"{title} (green: arrivals)" + (f"\n{what}" if what else ""))
    fig.tight_layout()
    _save(fig, plt, path)


# -- B-spline ------------------------------------------------------------------------------

def cmd_bspline(args) -> int:
    from ..trajectory import BSpline, bspline_period
    via = parse_via_points(args.via)
    M, n_axes = via.shape
    if not 1 <= args.degree <= 7:
        raise CliError(f"--degree must be 1..7, got {args.degree}")
    if args.wn is not None:
        modes = _numbers("--wn", args.wn)
        if any(w <= 0 for w in modes):
            raise CliError(f"--wn must be frequencies > 0 rad/s, got {args.wn!r}")
        T = bspline_period(wn=modes, Ts=args.Ts)
        origin = (f"from the lowest mode wn = {min(modes):g} rad/s "
                  f"(2 pi/wn = {2 * math.pi / min(modes):.6g} s)")
    else:
        T, origin = args.T, f"requested T = {args.T:g} s"
    if not (math.isfinite(T) and math.isfinite(args.Ts) and T > 0 and args.Ts > 0):
        BSpline(degree=args.degree, T=T, Ts=args.Ts, axes=n_axes)    # the named error
    # The size of the run from T/Ts alone (nothing allocated yet): refuse or announce. The
    # refusal names --Ts when the run would fit at Ts = 1 ms, else the knot spacing's source.
    ratio = T / args.Ts
    N = max(1, round(ratio)) if ratio < 2.0 ** 62 else ratio
    samples = (M - 2) * N + args.degree * (N - 1) + 1
    if samples * n_axes > MAX_BSPLINE_VALUES:
        at_1ms = ((M - 2) + args.degree) * max(1.0, T / 1e-3) * n_axes
        option = (f"--Ts={args.Ts:.3g}" if at_1ms <= MAX_BSPLINE_VALUES else
                  f"--wn={args.wn}" if args.wn is not None else f"--T={T:.3g}")
        raise CliError(f"{option}: the interpolation would produce {samples:.3g} samples on "
                       f"{n_axes} axis(es), more than the limit of {MAX_BSPLINE_VALUES:.3g} "
                       f"values (knot spacing T = {T:.3g} s from "
                       f"{'--wn' if args.wn is not None else '--T'}, T/Ts = {ratio:.3g}); use a "
                       "shorter knot spacing (--T, or a higher --wn) or a larger --Ts")
    cost = trajectory_cost("bspline", samples=samples, axes=n_axes, csv=bool(args.csv),
                           plot=bool(args.plot))
    bar = start(cost, args, f"{samples} samples on {n_axes} axis(es)")
    if bar is None:
        return 0
    spline = BSpline(degree=args.degree, T=T, Ts=args.Ts, axes=n_axes)
    ctrl = spline.control_points(via)
    bar.phase("filter", samples)
    out = spline.interpolate(via, progress=bar.advance)
    passes = [None] + [int(k) for k in spline.pass_samples(M)] + [spline.end_sample(M)]
    axes = "xyz"[:n_axes]
    print(f"B-spline of degree {spline.degree}, {n_axes} axis(es), {M} via-points")
    print(f"knot spacing T = {spline.T:.6g} s (N = {spline.N} samples at Ts = {spline.Ts:g} s; "
          f"{origin}); zeros at multiples of {2 * math.pi / spline.T:.6g} rad/s")
    print(format_table(["#"] + [f"via {a}" for a in axes] + [f"control {a}" for a in axes],
                       [[i, *map(float, via[i]), *map(float, ctrl[i])] for i in range(M)]))
    rows, errors = [], []
    for i, k in enumerate(passes):
        if k is None:  # the filter rests on via[0] before sample 0 (reset)
            rows.append([i, None, "rest", *([None] * n_axes), 0.0])
            continue
        err = float(np.max(np.abs(out[k] - via[i])))
        errors.append(err)
        rows.append([i, k, k * spline.Ts, *map(float, out[k]), err])
    print()
    print(format_table(["#", "sample", "time [s]"] + [f"output {a}" for a in axes]
                       + ["|error|"], rows))
    print(f"duration: {passes[-1] * spline.Ts:.6g} s (rest on the last via-point from sample "
          f"{passes[-1]}); max pass-through error {max(errors):.3g}")
    write_outputs(args, bar, lambda: (
        ["time"] + list(axes),
        [np.arange(out.shape[0]) * spline.Ts] + [out[:, a] for a in range(n_axes)]),
        lambda path: _plot_bspline(path, spline, via, ctrl, out, passes))
    return 0


def _plot_bspline(path, spline, via, ctrl, out, passes):
    plt = _pyplot("design bspline --plot")
    n_axes = via.shape[1]
    t = np.arange(out.shape[0]) * spline.Ts
    held = spline.staircase(ctrl, out.shape[0])
    fig, axes = plt.subplots(n_axes, 1, sharex=True, figsize=(8, 2.6 * n_axes + 0.6),
                             squeeze=False)
    tp = np.array([-spline.Ts if k is None else k * spline.Ts for k in passes])
    for a, ax in enumerate(axes[:, 0]):
        ax.step(*decimate(t, held[:, a], PLOT_POINTS), where="post", color="gray", lw=0.8,
                ls="--", label="control points (held)")
        ax.plot(*decimate(t, out[:, a], PLOT_POINTS), lw=1.2, label="B-spline output")
        ax.plot(tp, via[:, a], "o", ms=5, mfc="none", color="red", label="via-points")
        ax.set_ylabel(f"{'xyz'[a]} [unit]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(loc="best", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]")
    axes[0, 0].set_title(f"B-spline interpolation, degree {spline.degree}, "
                         f"T = {spline.T:.4g} s")
    fig.tight_layout()
    _save(fig, plt, path)


# -- parsers -------------------------------------------------------------------------------

def _hinting(parser_class):
    """parser_class whose errors add the fix for a --via value starting with '-' (argparse
    takes '-5,10' for an option)."""

    class FormParser(parser_class):
        def error(self, message):
            if "--via: expected one argument" in message:
                message += " (a list starting with a negative value is written --via=-5,10)"
            super().error(message)

    return FormParser


def add_design_forms(design_parser, parser_class) -> None:
    """Add the ``generator`` and ``bspline`` forms under ``design`` (optional, so the plain
    ``design --kind ...`` / ``design --h ...`` forms keep working)."""
    forms = design_parser.add_subparsers(dest="form", metavar="FORM",
                                         parser_class=_hinting(parser_class))
    forms.required = False

    p = forms.add_parser("generator", help="via-points through the online generator",
                         description="Run a staircase of via-points through the C-backed "
                         "online generator: each via-point is held until the output rests on "
                         "it (or for --hold seconds). The first via-point is the start (rest). "
                         "Several axes: points separated by ';' (--via \"0,0,0;10,5,2;...\"), "
                         "limits per axis ('1,2,3') or one for all; the axes move on straight "
                         "lines and arrive together (--sync phase) or each on its own "
                         "(--sync independent). Negative values: write --via=-5,10.")
    p.add_argument("--via", metavar="P0,P1,... | X,Y,Z;X,Y,Z;...",
                   help="positions: start, then the targets in order (e.g. 0,20,40,100,60,0); "
                   "for several axes points separated by ';' (with --velocity: the start "
                   "position alone, default 0)")
    p.add_argument("--via-velocity", metavar="V1,V2,...",
                   help="one axis: the velocity at arrival on each target (default 0: at "
                   "rest); the output reaches the target moving, exactly on a sample, then "
                   "holds that velocity until the next target")
    p.add_argument("--via-acceleration", metavar="A1,A2,...",
                   help="one axis: the acceleration at arrival on each target (default 0)")
    p.add_argument("--start", metavar="V,A",
                   help="one axis: the start state's velocity and acceleration at the first "
                   "--via point (default at rest)")
    p.add_argument("--velocity", metavar="V1,V2,...",
                   help="one axis, the velocity interface: reach each velocity in the least "
                   "time (the position free; 0 = stop), each held --hold seconds")
    p.add_argument("--vmax", type=_limit("--vmax"), required=True,
                   help="velocity limit [unit/s] (one per axis: V1,V2,...)")
    p.add_argument("--amax", type=_limit("--amax"), required=True,
                   help="acceleration limit [unit/s^2] (one per axis: A1,A2,...)")
    p.add_argument("--jmax", type=_limit("--jmax"), required=True,
                   help="jerk limit [unit/s^3] (one per axis: J1,J2,...)")
    p.add_argument("--vmin", type=float,
                   help="one axis: lower velocity limit [unit/s], < 0 (default -vmax)")
    p.add_argument("--amin", type=float,
                   help="one axis: lower acceleration limit [unit/s^2], < 0 (default -amax)")
    p.add_argument("--qmin", type=_limit("--qmin"),
                   help="with --qmax: lower position limit [unit] (one per axis: Q1,Q2,...); "
                   "every sample stays in [qmin, qmax] and the via-points must lie inside")
    p.add_argument("--qmax", type=_limit("--qmax"),
                   help="with --qmin: upper position limit [unit] (one per axis: Q1,Q2,...)")
    p.add_argument("--sync", choices=("phase", "independent"), default="phase",
                   help="several axes: straight lines and common arrival (phase, default) or "
                   "each axis time-optimal on its own (independent)")
    p.add_argument("--Ts", type=float, required=True, help="sample period [s]")
    p.add_argument("--profile", default="polynomial", choices=PROFILES,
                   help="shape of the acceleration's transitions: polynomial (linear ramps), "
                        "trigonometric (half cosines) or damped (ramps, with the exponential "
                        "stage tuned to --wn); default polynomial")
    p.add_argument("--wn", type=float, help="mode to cancel [rad/s] (needed by damped)")
    p.add_argument("--zeta", type=float, default=0.0, help="damping ratio of the mode (default 0)")
    p.add_argument("--hold", type=float, metavar="SECONDS",
                   help="hold each via-point this long instead of until reached (the last "
                   "one is held until reached)")
    p.add_argument("--unit", default="unit", help="position unit for labels (default 'unit')")
    p.add_argument("--plot", metavar="PNG", help="write q, v, a, j over time to this PNG")
    p.add_argument("--csv", metavar="CSV", help="write time, target, q, v, a, j to this CSV")
    add_cost_options(p)
    p.set_defaults(func=cmd_generator, figures_option="--plot")

    p = forms.add_parser("bspline", help="B-spline through via-points",
                         description="Interpolate via-points with the C-backed uniform "
                         "B-spline filter. Negative values: write --via=\"-1,2;3,4\".")
    p.add_argument("--via", required=True, metavar="X,Y,Z;...",
                   help="via-points separated by ';', coordinates (1 to 3 axes) by ','")
    p.add_argument("--degree", type=int, default=3, help="spline degree 1..7 (default 3)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--T", type=float, help="knot spacing [s] (rounded to whole samples)")
    g.add_argument("--wn", metavar="WN[,WN...]",
                   help="modes [rad/s]: T = the shortest N Ts >= 2 pi / min(wn)")
    p.add_argument("--Ts", type=float, required=True, help="sample period [s]")
    p.add_argument("--plot", metavar="PNG", help="write the axes over time to this PNG")
    p.add_argument("--csv", metavar="CSV", help="write time and the axes to this CSV")
    add_cost_options(p)
    p.set_defaults(func=cmd_bspline, figures_option="--plot")
