# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper design generator --via "x,y,z;x,y,z;..."``: multi-axis via-points.

Runs the via-points through the C-backed multi-axis generator
(:class:`smoothshaper.trajectory.MultiAxisGenerator`): the first point is the start (rest),
each further point is held until every axis rests on it (or for ``--hold`` seconds, the last
until reached). Prints one row per segment (arrival, duration against the time-optimal
straight move, the largest |v|, |a|, |j| over the axes as a fraction of each axis's limit, and
how far the path leaves the straight segment) and writes a plot: per-axis profiles scaled by
their limits, and the path in 2-D or 3-D.
"""
from __future__ import annotations

import math

import numpy as np

from .common import EXIT_ERROR, CliError, decimate, format_table, run_samples
from .common import numbers as _numbers
from .cost import PLOT_POINTS, start, trajectory_cost
from .common import parse_via_points, pyplot as _pyplot, save_figure as _save
from .common import write_outputs
from ..errors import ParameterError

__all__ = ["LIMIT_RTOL", "MAX_SAMPLES", "AXIS_NAMES", "parse_points", "parse_limit", "run",
           "cmd_multi_generator", "plot"]

LIMIT_RTOL = 1e-9
MAX_SAMPLES = 5_000_000
AXIS_NAMES = "xyzabcuv"


def parse_points(text: str) -> np.ndarray:
    """'x,y,z;x,y,z;...' -> (M, axes), M >= 2, 1 <= axes <= 8."""
    return parse_via_points(text, max_axes=len(AXIS_NAMES))


def parse_limit(option: str, value, axes: int) -> np.ndarray:
    """One value for every axis, or one per axis ('1,2,3')."""
    v = np.array(_numbers(option, value) if isinstance(value, str) else [float(value)])
    if v.size == 1:
        v = np.full(axes, v[0])
    if v.size != axes:
        raise CliError(f"{option}: give one value or one per axis ({axes}), got {v.size}")
    bad = np.flatnonzero(v <= 0)
    if bad.size:
        raise CliError(f"{option}: every limit must be > 0, got {v[bad[0]]:g} for axis "
                       f"{AXIS_NAMES[bad[0]]}")
    return v


def position_limits(args, via: np.ndarray) -> dict:
    """qmin, qmax per axis of --qmin/--qmax (one value for every axis, or one per axis), the
    via-points inside them (else CliError naming the option and the point); {} without."""
    if getattr(args, "qmin", None) is None and getattr(args, "qmax", None) is None:
        return {}
    axes = via.shape[1]
    out = {}
    for name in ("qmin", "qmax"):
        value = getattr(args, name)
        if value is None:
            raise CliError(f"--{name} must be given with --{'qmax' if name == 'qmin' else 'qmin'}")
        q = np.array(_numbers(f"--{name}", value) if isinstance(value, str) else [float(value)])
        if q.size == 1:
            q = np.full(axes, q[0])
        if q.size != axes:
            raise CliError(f"--{name}: give one value or one per axis ({axes}), got {q.size}")
        out[name] = q
    for k, point in enumerate(via):
        bad = np.flatnonzero((point < out["qmin"]) | (point > out["qmax"]))
        if bad.size:
            i = bad[0]
            side = "--qmin" if point[i] < out["qmin"][i] else "--qmax"
            raise CliError(f"{side}: --via point {k} ({point[i]:.6g} on axis {AXIS_NAMES[i]}) "
                           f"is outside [{out['qmin'][i]:.6g}, {out['qmax'][i]:.6g}]")
    return {name: list(map(float, q)) for name, q in out.items()}


def _arrival(out: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Samples where every axis rests exactly on target (the generator lands bit for bit)."""
    return np.flatnonzero(np.all(out[:, :, 0] == target, axis=1)
                          & np.all(out[:, :, 1:] == 0, axis=(1, 2)))


def run(gen, via: np.ndarray, hold_samples: int | None, max_samples: int):
    """(targets, out, starts, arrivals): each point held until reached (or hold_samples)."""
    targets, outs, starts, arrivals = [], [], [], []
    k = 0
    chunk = 4096
    for i, p in enumerate(via[1:]):
        starts.append(k)
        last = i == via.shape[0] - 2
        if hold_samples is not None and not last:
            block = np.tile(p, (hold_samples, 1))
            out = gen.process(block)
            hit = _arrival(out, p)
            targets.append(block)
            outs.append(out)
            arrivals.append(k + int(hit[0]) if hit.size else None)
            k += hold_samples
            continue
        while True:
            if k >= max_samples:
                raise CliError(f"the output did not reach point {i + 1} within {max_samples} "
                               "samples (raise --Ts)")
            block = np.tile(p, (chunk, 1))
            out = gen.process(block)
            hit = _arrival(out, p)
            if hit.size:
                # at rest on p the state no longer changes: the extra samples are dropped
                n = int(hit[0]) + 1
                targets.append(block[:n])
                outs.append(out[:n])
                k += n
                arrivals.append(k - 1)
                break
            targets.append(block)
            outs.append(out)
            k += chunk
    return np.concatenate(targets), np.concatenate(outs), starts, arrivals


def _deviation(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance of the points q from the segment a-b, relative to its length."""
    d = b - a
    L = float(np.linalg.norm(d))
    if L == 0:
        return float(np.max(np.linalg.norm(q - a, axis=1))) if q.size else 0.0
    s = np.clip((q - a) @ d / (L * L), 0.0, 1.0)
    return float(np.max(np.linalg.norm(q - a - np.outer(s, d), axis=1))) / L


def cmd_multi_generator(args) -> int:
    from ..trajectory import MultiAxisGenerator, phase_duration
    via = parse_points(args.via)
    axes = via.shape[1]
    v = parse_limit("--vmax", args.vmax, axes)
    a = parse_limit("--amax", args.amax, axes)
    j = parse_limit("--jmax", args.jmax, axes)
    sync = getattr(args, "sync", None) or "phase"
    limits = position_limits(args, via)
    try:
        gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=args.Ts, sync=sync, q0=via[0],
                                 **limits)
    except ParameterError as exc:
        if exc.parameter.split("[")[0] not in ("qmin", "qmax"):
            raise
        raise CliError(f"--{exc}") from None
    Ts = gen.Ts
    optimum = [phase_duration(q1 - q0, vmax=v, amax=a, jmax=j) for q0, q1 in zip(via[:-1], via[1:])]
    # each move within 3 times its optimum: the cruise part charged to its via-point, the rest
    # (the axes' rise times) to the limit that makes it long, so a refusal names the option
    cruise = [float(np.max(np.abs(q1 - q0) / v)) for q0, q1 in zip(via[:-1], via[1:])]
    rise = math.fsum(3 * max(t - c, 0.0) for t, c in zip(optimum, cruise))
    by_amax, by_jmax = v / a, a / j        # each axis's rise: vmax/amax + amax/jmax
    slow, k = (("--amax", int(np.argmax(by_amax))) if np.max(by_amax) >= np.max(by_jmax)
               else ("--jmax", int(np.argmax(by_jmax))))
    terms = [("--via point {} ({})".format(i + 1, ",".join(f"{x:.3g}" for x in q)), 3 * c,
              "bring it closer or raise --vmax") for i, (q, c) in enumerate(zip(via[1:], cruise))]
    pair = ((f"--vmax={v[k]:.3g}, --amax={a[k]:.3g}", "raise --amax or lower --vmax")
            if slow == "--amax" else
            (f"--amax={a[k]:.3g}, --jmax={j[k]:.3g}", "raise --jmax or lower --amax"))
    terms.append((f"{pair[0]} (axis {AXIS_NAMES[k]})", rise, pair[1]))
    hold_samples = None
    if args.hold is not None:
        if not (math.isfinite(args.hold) and args.hold >= Ts):
            raise CliError(f"--hold must be a time >= Ts = {Ts:.3g} s, got {args.hold:.3g}")
        terms.append((f"--hold={args.hold:.3g}", args.hold * len(optimum), "shorten --hold"))
    max_samples = run_samples(terms, Ts, MAX_SAMPLES, extra=10 * (len(optimum) + 1) + 4096)
    if args.hold is not None:
        hold_samples = int(round(args.hold / Ts))
    cost = trajectory_cost("generator", samples=max_samples, axes=axes, csv=bool(args.csv),
                           plot=bool(args.plot))
    bar = start(cost, args, f"at most {max_samples} samples on {axes} axes")
    if bar is None:
        return 0
    bar.phase("generator")
    targets, out, starts, arrivals = run(gen, via, hold_samples, max_samples)
    lim = np.array([v, a, j])                                   # (3, axes)
    names = AXIS_NAMES[:axes]
    u = args.unit
    rows = []
    ends = starts[1:] + [out.shape[0]]
    prev = via[0]
    for i, (s, e) in enumerate(zip(starts, ends)):
        ratio = (np.abs(out[s:e, :, 1:]) / lim.T[None]).max(axis=(0, 1))
        arr = arrivals[i]
        dur = None if arr is None else (arr - s) * Ts
        # the segment a move follows: from where it started (rest on the previous point, or
        # wherever the previous one was left by --hold) to this point
        dev = _deviation(out[s:e, :, 0], out[s - 1, :, 0] if s else prev, via[i + 1])
        rows.append([i + 1, ",".join(f"{x:g}" for x in via[i + 1]), s * Ts,
                     None if arr is None else arr * Ts, dur, optimum[i], *map(float, ratio), dev])
    print(f"multi-axis generator ({gen.sync}), {axes} axes ({names}), Ts = {Ts:g} s; "
          f"start at rest at ({','.join(f'{x:g}' for x in via[0])}) {u}")
    print(format_table(["axis", f"vmax [{u}/s]", f"amax [{u}/s^2]", f"jmax [{u}/s^3]"],
                       [[names[i], float(v[i]), float(a[i]), float(j[i])] for i in range(axes)]))
    print()
    print("each point held until every axis rests on it" if hold_samples is None else
          f"each point held {hold_samples} samples ({hold_samples * Ts:g} s), the last "
          "until reached")
    print(format_table(["#", f"target [{u}]", "start [s]", "arrival [s]", "duration [s]",
                        "optimum [s]", "max v/vmax", "max a/amax", "max j/jmax",
                        "off line"], rows))
    print("optimum: time-optimal straight move from rest (phase-synchronised); 'off line': "
          "largest distance from the straight segment / its length")
    missed = [r[0] for r in rows if r[3] is None]
    if missed:
        print("not reached before the next point (--hold): segment "
              + ", ".join(str(m) for m in missed))
    total = arrivals[-1] * Ts
    print(f"total time: {total:.6g} s ({arrivals[-1] + 1} samples)")
    ok = bool(np.all(np.abs(out[:, :, 1:]) <= lim.T[None] * (1 + LIMIT_RTOL)))
    print("every axis within its limits at every sample: " + ("yes" if ok else "NO (exceeded)"))

    def columns():
        cols = [np.arange(out.shape[0]) * Ts] + [targets[:, i] for i in range(axes)]
        header = ["time"] + [f"target_{n}" for n in names]
        for i, n in enumerate(names):
            cols += [out[:, i, m] for m in range(4)]
            header += [f"{n}_q", f"{n}_v", f"{n}_a", f"{n}_j"]
        return header, cols
    write_outputs(args, bar, columns,
                  lambda path: plot(path, out, via, lim, arrivals, Ts, names, u, gen.sync))
    return 0 if ok else EXIT_ERROR


def plot(path, out, via, lim, arrivals, Ts, names, u, sync):
    """Left: q and v/vmax, a/amax, j/jmax of every axis over time; right: the path."""
    plt = _pyplot("design generator --plot")
    axes = out.shape[1]
    t = np.arange(out.shape[0]) * Ts
    # the path is smooth: every k-th sample (and the last) draws it at the same resolution
    drawn = out[np.unique(np.r_[np.arange(0, out.shape[0], max(1, out.shape[0] // PLOT_POINTS)),
                               out.shape[0] - 1])]
    fig = plt.figure(figsize=(13, 8))
    gs = fig.add_gridspec(4, 2, width_ratios=[1.35, 1])
    left = [fig.add_subplot(gs[0, 0])]
    left += [fig.add_subplot(gs[r, 0], sharex=left[0]) for r in range(1, 4)]
    labels = [f"position [{u}]", "v / vmax", "a / amax", "j / jmax"]
    for m, ax in enumerate(left):
        for i in range(axes):
            y = out[:, i, m] if m == 0 else out[:, i, m] / lim[m - 1, i]
            if m == 3:
                ax.step(*decimate(t, y, PLOT_POINTS), where="post", lw=1.0, label=names[i])
            else:
                ax.plot(*decimate(t, y, PLOT_POINTS), lw=1.2, label=names[i])
        if m:
            ax.axhline(1, color="red", lw=0.7, ls=":")
            ax.axhline(-1, color="red", lw=0.7, ls=":")
            ax.set_ylim(-1.15, 1.15)
        for k in arrivals:
            if k is not None:
                ax.axvline(k * Ts, color="green", lw=0.5, alpha=0.5)
        ax.set_ylabel(labels[m])
        ax.grid(True, alpha=0.3)
    left[0].legend(loc="best", fontsize=8, ncol=min(axes, 4))
    left[0].set_title(f"Per-axis profiles ({sync}; red: each axis's limit, green: arrivals)")
    left[-1].set_xlabel("time [s]")
    if axes >= 3:
        ax = fig.add_subplot(gs[:, 1], projection="3d")
        ax.plot(via[:, 0], via[:, 1], via[:, 2], "--", color="gray", lw=0.8,
                label="straight segments")
        ax.plot(drawn[:, 0, 0], drawn[:, 1, 0], drawn[:, 2, 0], lw=1.5, label="generated path")
        ax.scatter(via[:, 0], via[:, 1], via[:, 2], color="red", s=20, label="via-points")
        ax.set_zlabel(f"{names[2]} [{u}]")
        ax.set_box_aspect(None, zoom=0.88)   # room for the z label inside the figure
    else:
        ax = fig.add_subplot(gs[:, 1])
        y0 = via[:, 1] if axes >= 2 else np.zeros(via.shape[0])
        y = drawn[:, 1, 0] if axes >= 2 else np.zeros(drawn.shape[0])
        ax.plot(via[:, 0], y0, "--", color="gray", lw=0.8, label="straight segments")
        ax.plot(drawn[:, 0, 0], y, lw=1.5, label="generated path")
        ax.plot(via[:, 0], y0, "o", color="red", ms=4, label="via-points")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
    ax.set_xlabel(f"{names[0]} [{u}]")
    if axes >= 2:
        ax.set_ylabel(f"{names[1]} [{u}]")
    ax.set_title("Path" + (" (first three axes)" if axes > 3 else ""))
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    _save(fig, plt, path)
