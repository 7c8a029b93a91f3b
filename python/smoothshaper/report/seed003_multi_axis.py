# SPDX-License-Identifier: Apache-2.0
"""Seed 003's Cartesian robot moved through 3-D via-points by the phase-synchronised multi-axis
generator, next to the B-spline of Sec. IV.

Three commands on the Table I axes (x, z: wn = 60 rad/s; y: 40 rad/s), simulated exactly:

* **stop-and-go**: :class:`smoothshaper.trajectory.MultiAxisGenerator` (sync="phase") through
  the corners of the robot's path, each held until reached: straight lines, every axis starts
  and arrives on the same sample, time-optimal under every axis's limits;
* the same with vibration stages, a ZV shaper for each of the two modes on *every* axis (the
  same stages on every axis keep the lines straight);
* **streamed**: the via-points of Sec. IV fed one per dwell, so each target arrives
  mid-motion and the generator blends the corners; and the cubic B-spline through the same
  via-points (T from ``bspline_period``).

Residual vibration per axis: the largest deviation of the load from the final point after the
command has stopped.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import stages as st
from ..trajectory import BSpline, MultiAxisGenerator, bspline_period, phase_duration
from .claims import Claim
from .figures import figure
from .seed003_robot import ROBOT

__all__ = ["run"]

TS = 1e-3
VMAX = np.array([0.5, 0.4, 0.2])      # m/s per axis (z slower, as a vertical axis)
AMAX = np.array([5.0, 4.0, 2.0])      # m/s^2
JMAX = np.array([200.0, 150.0, 100.0])  # m/s^3
SETTLE = 1.5                            # s simulated after the command stops
AXES = "xyz"


def corners(via: np.ndarray) -> np.ndarray:
    """Start, the ends of the two bends and the end of the Sec. IV path (3-D)."""
    idx = [0, 6, 9, 15, 18, via.shape[0] - 1]
    return via[idx]


def _modes():
    return {a: (math.sqrt(k / m), d / (2 * math.sqrt(k * m))) for a, (m, d, k) in ROBOT.items()}


def shaper_stages():
    """One ZV per distinct mode, the same list on every axis."""
    m = _modes()
    return [st.shaper("zv", wn=m["y"][0], zeta=m["y"][1]), st.shaper("zv", wn=m["x"][0],
                                                                     zeta=m["x"][1])]


def stop_and_go(points: np.ndarray, stages=None):
    """Each point held until the generator rests on it. Returns (out, starts, arrivals) with
    arrivals[i] = the sample at which every axis reached point i + 1 (per axis)."""
    gen = MultiAxisGenerator(vmax=VMAX, amax=AMAX, jmax=JMAX, Ts=TS, q0=points[0])
    outs, starts, arrivals = [], [], []
    k = 0
    for p in points[1:]:
        T = phase_duration(p - points[len(starts)], vmax=VMAX, amax=AMAX, jmax=JMAX)
        n = int(math.ceil(T / TS)) + 2
        out = gen.process(np.tile(p, (n, 1)))
        at = (out[:, :, 0] == p) & np.all(out[:, :, 1:] == 0, axis=2)
        moved = np.flatnonzero(p != points[len(starts)])  # an axis that stays has no arrival
        per_axis = np.array([int(np.argmax(at[:, i])) for i in moved])
        m = int(per_axis.max()) + 1
        outs.append(out[:m])
        starts.append(k)
        arrivals.append(k + per_axis)
        k += m
    out = np.concatenate(outs + [np.tile(np.concatenate([points[-1][:, None],
                                                          np.zeros((3, 3))], axis=1),
                                         (int(SETTLE / TS), 1, 1))])
    if stages is not None:
        from ..filters import Chain
        for i in range(3):
            out[:, i, 0] = Chain(stages, Ts=TS).process(out[:, i, 0] - points[0, i]) + points[0, i]
    return out, starts, arrivals, k


def streamed(via: np.ndarray, dwell: float):
    """Each via-point the target for ``dwell`` seconds (the last until reached)."""
    gen = MultiAxisGenerator(vmax=VMAX, amax=AMAX, jmax=JMAX, Ts=TS, q0=via[0])
    n = int(round(dwell / TS))
    head = gen.process(np.repeat(via[1:-1], n, axis=0))
    tail = gen.process(np.tile(via[-1], (int(5.0 / TS), 1)))
    at = np.all(tail[:, :, 0] == via[-1], axis=1) & np.all(tail[:, :, 1:] == 0, axis=(1, 2))
    stop = head.shape[0] + int(np.argmax(at))
    rest = np.tile(np.concatenate([via[-1][:, None], np.zeros((3, 3))], axis=1),
                   (int(SETTLE / TS), 1, 1))
    return np.concatenate([head, tail[:int(np.argmax(at)) + 1], rest]), stop


def residual(cmd: np.ndarray, stop: int, final: np.ndarray) -> np.ndarray:
    """Load response of the three axes and the largest |load - final| after ``stop`` [m]."""
    from .seed003_robot import _respond
    load = _respond(cmd)
    return load, np.abs(load[stop:] - final).max(axis=0)


def run(sec, via: np.ndarray) -> dict:
    pts = corners(via)
    out, starts, arrivals, stop = stop_and_go(pts)
    spread = max(int(a.max() - a.min()) for a in arrivals)
    sec.add(Claim("multi.same_sample", "Multi-axis, stop-and-go through the corners: largest "
                  "spread of the arrival sample over the axes", spread, 0, 0,
                  "phase synchronisation: one common profile", unit="samples"))
    grid = max(abs(int(a[0] - s) - math.ceil(phase_duration(pts[i + 1] - pts[i], vmax=VMAX,
                                                              amax=AMAX, jmax=JMAX) / TS))
               for i, (s, a) in enumerate(zip(starts, arrivals)))
    sec.add(Claim("multi.duration", "Multi-axis: largest |samples per segment - ceil(T*/Ts)|, "
                  "T* the time-optimal straight move under every axis's limits", grid, 0, 0,
                  "closed form (double-S on the path parameter)", unit="samples"))
    dev = 0.0
    for i, (s, a) in enumerate(zip(starts, arrivals)):
        q = out[s:a[0] + 1, :, 0]
        d = pts[i + 1] - pts[i]
        sp = (q - pts[i]) @ d / (d @ d)
        dev = max(dev, float(np.abs(q - pts[i] - np.outer(sp, d)).max() / np.abs(d).max()))
    sec.add(Claim("multi.straight", "Multi-axis: largest deviation from the straight segments, "
                  "relative to the move", dev, 0.0, 1e-12, "straight lines in axis space",
                  relation="<="))
    lim = np.array([VMAX, AMAX, JMAX]).T
    ratio = float((np.abs(out[:stop, :, 1:]) / lim[None]).max())
    sec.add(Claim("multi.limits", "Multi-axis: largest |v|/vmax, |a|/amax, |j|/jmax over axes "
                  "and samples", ratio, 1.0, 1e-9, "every axis's own limits", relation="<="))
    cmd = out[:, :, 0]
    load_plain, rv_plain = residual(cmd, stop, pts[-1])
    shaped, _, _, _ = stop_and_go(pts, stages=shaper_stages())
    # the shaped command stops when the last shaper impulse has passed
    moving = np.flatnonzero(np.any(np.abs(shaped[:, :, 0] - pts[-1]) > 1e-12, axis=1))
    stop_shaped = int(moving[-1]) + 1
    load_shaped, rv_shaped = residual(shaped[:, :, 0], stop_shaped, pts[-1])
    dev_corner = _path_deviation(shaped[:, :, 0], pts)
    seg = pts[1:3]  # the first segment on which all three axes move
    one, _, _, _ = stop_and_go(seg, stages=shaper_stages())
    dev_one = _path_deviation(one[:, :, 0], seg)
    sec.add(Claim("multi.shaped_straight", "Multi-axis + the same ZV stages on every axis, one "
                  "move: largest distance from the straight segment / its length", dev_one, 0.0,
                  1e-12, "identical linear filters keep lines straight", relation="<="))
    m = _modes()
    own = [[st.shaper("zv", wn=m[a][0], zeta=m[a][1])] for a in AXES]
    bent = stop_and_go(seg)[0]
    from ..filters import Chain
    for i in range(3):
        bent[:, i, 0] = Chain(own[i], Ts=TS).process(bent[:, i, 0] - seg[0, i]) + seg[0, i]
    dev_own = _path_deviation(bent[:, :, 0], seg)
    sec.add(Claim("multi.own_stages_bend", "Multi-axis + a ZV tuned to each axis's own mode "
                  "(x, z: 60, y: 40 rad/s), one move: largest distance from the straight "
                  "segment / its length", dev_own, 1e-3, 0.0,
                  "different delays per axis bend the line (the class warns)", relation=">="))
    for i, axis in enumerate(AXES):
        sec.add(Claim(f"multi.rv_shaped.{axis}", f"Multi-axis: residual vibration on {axis} with "
                      "the two-mode ZV stages over without", rv_shaped[i] / rv_plain[i], 0.05, 0.0,
                      "ZV zeros at both modes", relation="<="))
    dwell = 0.09
    stream, stop_stream = streamed(via, dwell)
    ratio_s = float((np.abs(stream[:stop_stream, :, 1:]) / lim[None]).max())
    sec.add(Claim("multi.stream_limits", f"Multi-axis, {via.shape[0]} via-points streamed every {dwell} s "
                  "(blended mid-motion): largest |v|/vmax, |a|/amax, |j|/jmax", ratio_s, 1.0,
                  1e-9, "every axis's own limits", relation="<="))
    sec.add(Claim("multi.stream_arrival", "Multi-axis streamed: distance of the command from the "
                  "last via-point once stopped", float(np.abs(stream[-1, :, 0] - via[-1]).max()),
                  0.0, 0.0, "exact arrival on the held target", unit="m"))
    load_stream, rv_stream = residual(stream[:, :, 0], stop_stream, via[-1])
    wn = [m[0] for m in _modes().values()]
    b = BSpline(degree=3, T=bspline_period(wn=wn, Ts=TS), Ts=TS, axes=3)
    bcmd = b.interpolate(via, extra=int(SETTLE / TS))
    bstop = b.end_sample(via.shape[0])
    load_b, rv_b = residual(bcmd, bstop, via[-1])
    rows = ["| command | duration [s] | RV x [mm] | RV y [mm] | RV z [mm] |", "|---|---|---|---|---|"]
    table = [("generator, corners, stop-and-go", stop * TS, rv_plain),
             ("generator + ZV(40) ZV(60) on every axis", stop_shaped * TS, rv_shaped),
             (f"generator, {via.shape[0]} via-points streamed every {dwell} s", stop_stream * TS,
              rv_stream),
             (f"cubic B-spline through the {via.shape[0]} via-points", bstop * TS, rv_b)]
    for name, T, rv in table:
        rows.append(f"| {name} | {T:.3f} | " + " | ".join(f"{1000 * x:.3g}" for x in rv) + " |")
    body = "\n".join([
        "Multi-axis generator on the same robot (limits per axis vmax = "
        f"{', '.join(f'{v:g}' for v in VMAX)} m/s, amax = {', '.join(f'{v:g}' for v in AMAX)} "
        f"m/s^2, jmax = {', '.join(f'{v:g}' for v in JMAX)} m/s^3 for x, y, z). Stop-and-go "
        f"through the {pts.shape[0]} corners of the path: every axis arrives on the same sample, "
        f"the path stays on the straight segments (deviation {dev:.1e} of the move) and each "
        "segment takes the time-optimal straight duration rounded up to 1 ms. Residual "
        "vibration after the command stops (largest |load - final point|):", "", *rows, "",
        f"Identical ZV stages on every axis cancel both modes and keep a move straight "
        f"(deviation {dev_one:.1e}); at the corners they average points of the two segments "
        f"and cut them by up to {100 * dev_corner:.2g} % of the shortest segment. A ZV tuned to "
        f"each axis's own mode instead bends even a single move by {100 * dev_own:.2g} % of its "
        "length. Streaming the via-points blends the corners mid-motion, within every axis's "
        "limits, and lands exactly on the last one. The B-spline passes through every "
        "via-point but its knot spacing is set by the lowest mode, not by the limits."])

    def figures(sec_, fig_dir: Path):
        _figures(sec_, fig_dir, via, pts, cmd, shaped[:, :, 0], stream[:, :, 0], bcmd,
                 dict(plain=(load_plain, stop), shaped=(load_shaped, stop_shaped),
                      stream=(load_stream, stop_stream), bspline=(load_b, bstop)),
                 dict(plain=rv_plain, shaped=rv_shaped, stream=rv_stream, bspline=rv_b))
    return {"body": body, "figures": figures}


def _path_deviation(q: np.ndarray, pts: np.ndarray) -> float:
    """Largest distance of the points q from the polyline pts, relative to the shortest segment."""
    best = np.full(q.shape[0], np.inf)
    for a, b in zip(pts[:-1], pts[1:]):
        d = b - a
        s = np.clip((q - a) @ d / (d @ d), 0, 1)
        best = np.minimum(best, np.linalg.norm(q - a - np.outer(s, d), axis=1))
    return float(best.max() / np.min(np.linalg.norm(np.diff(pts, axis=0), axis=1)))


NAMES = dict(plain="generator (stop-and-go)", shaped="generator + ZV stages",
             stream="generator, streamed", bspline="cubic B-spline")


def _figures(sec, fig_dir, via, pts, cmd, shaped, stream, bcmd, loads, rvs):
    plt_fig = fig_dir / "robot_multi_axis_path.png"
    with figure(plt_fig, "Seed 003 robot, multi-axis generator: commands in x-y (left) and x-z "
                "(right) through the corners (phase-synchronised, straight) and all "
                "via-points (streamed, blended), with the cubic B-spline", sec.figures,
                ncols=2, size=(12, 5)) as (f, ax):
        for a, (j, name) in zip(ax, ((1, "y"), (2, "z"))):
            a.plot(via[:, 0], via[:, j], "ko", ms=3, label="via-points (Sec. IV)")
            a.plot(pts[:, 0], pts[:, j], "rs", ms=6, mfc="none", label="corners")
            a.plot(cmd[:, 0], cmd[:, j], lw=1.6, label=NAMES["plain"])
            a.plot(stream[:, 0], stream[:, j], lw=1.0, label=NAMES["stream"])
            a.plot(bcmd[:, 0], bcmd[:, j], "--", lw=1.0, label=NAMES["bspline"])
            a.set_xlabel("x [m]")
            a.set_ylabel(f"{name} [m]")
    with figure(fig_dir / "robot_multi_axis_rv.png", "Seed 003 robot: load minus final point "
                "after the command stops, per axis, for the four commands (mm)", sec.figures,
                ncols=3, size=(14, 5)) as (f, ax):
        for key, (load, stop) in loads.items():
            final = via[-1] if key in ("stream", "bspline") else pts[-1]
            t = (np.arange(load.shape[0] - stop)) * TS
            for i in range(3):
                ax[i].plot(t, 1000 * (load[stop:, i] - final[i]), lw=0.9,
                           label=f"{NAMES[key]}: RV {1000 * rvs[key][i]:.2g} mm")
        for i in range(3):
            # under the plot: inside it would hide the largest swings
            ax[i].legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=7)
            ax[i].set_xlabel("time after the command stops [s]")
            ax[i].set_ylabel(f"{AXES[i]}: load - final [mm]")
