# SPDX-License-Identifier: Apache-2.0
"""Seed 003 Sec. IV: the Cartesian robot tracking B-spline trajectories through via-points.

The paper's via-points are not published; ours follow its description: straight lines with
circular bends in the x-y plane, equally spaced (d = 0.0454 m as the paper's average), and a
slow z ramp so that all three axes move. Each axis is ``m q'' + d q' + k q = d q_d' + k q_d``
(Table I), simulated exactly (zero-order hold) at Ts = 1 ms. The residual vibration RV is the
largest deviation of the load from the final via-point after the command has stopped, in
percent of d (the paper normalises by d the same way, but measures along straight segments).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import plants
from .. import reference as ref
from .. import stages as st
from ..trajectory import BSpline, bspline_period
from .claims import Claim
from .figures import figure

__all__ = ["run"]

TS = 1e-3
SPACING = 0.0454       # m, the paper's mean via-point distance
BEND_RADIUS = 0.06     # m
SETTLE = 1.5           # s simulated after the command stops
#: Per axis (m, d, k) of m q'' + d q' + k q = d q_d' + k q_d (Biagiotti & Melchiorri 2011b, Table I).
ROBOT = {"x": (2.777, 4.0, 1e4), "y": (6.25, 4.0, 1e4), "z": (2.777, 4.0, 1e4)}
#: The paper's natural frequency [rad/s] and damping ratio per axis.
ROBOT_PAPER = {"x": (60.0, 0.012), "y": (40.0, 0.008), "z": (60.0, 0.012)}


def via_points() -> np.ndarray:
    """(M, 3) via-points: +x 0.3 m, a 90 degree bend, +y 0.3 m, a bend back, +x 0.3 m, equally
    spaced along the path; z rises 0.05 m linearly along it."""
    r, L = BEND_RADIUS, 0.3
    pieces = []
    s = np.linspace(0, 1, 400)
    pieces.append(np.column_stack([L * s, 0 * s]))
    a = np.linspace(-math.pi / 2, 0, 400)
    pieces.append(np.column_stack([L + r * np.cos(a), r + r * np.sin(a)]))
    pieces.append(np.column_stack([L + r + 0 * s, r + L * s]))
    a = np.linspace(math.pi, math.pi / 2, 400)
    pieces.append(np.column_stack([L + 2 * r + r * np.cos(a), r + L + r * np.sin(a)]))
    pieces.append(np.column_stack([L + 2 * r + L * s, L + 2 * r + 0 * s]))
    dense = np.vstack(pieces)
    arc = np.concatenate([[0], np.cumsum(np.hypot(*np.diff(dense, axis=0).T))])
    n = int(round(arc[-1] / SPACING))
    targets = np.linspace(0, arc[-1], n + 1)
    xy = np.column_stack([np.interp(targets, arc, dense[:, 0]),
                          np.interp(targets, arc, dense[:, 1])])
    z = 0.05 * targets / arc[-1]
    return np.column_stack([xy, z])


def _axes():
    return {a: plants.cartesian_axis(m=m, d=d, k=k) for a, (m, d, k) in ROBOT.items()}


def _respond(cmd: np.ndarray) -> np.ndarray:
    out = np.empty_like(cmd)
    for i, plant in enumerate(_axes().values()):
        out[:, i] = plants.simulate_zoh(plant, cmd[:, i], Ts=TS,
                                        x0=plants.rest_state(plant, cmd[0, i]))[1]
    return out


def rv(degree: int, T: float, via: np.ndarray):
    """RV [% of the via-point spacing] on x and y after the stop, the command, the load
    response, the spline and its via-point error."""
    b = BSpline(degree=degree, T=T, Ts=TS, axes=3)
    cmd = b.interpolate(via, extra=int(SETTLE / TS))
    load = _respond(cmd)
    end = b.end_sample(via.shape[0])
    dev = np.abs(load[end:] - via[-1]).max(axis=0)
    d = float(np.mean(np.linalg.norm(np.diff(via, axis=0), axis=1)))
    passes = b.pass_samples(via.shape[0])
    err = float(np.abs(cmd[passes] - via[1:-1]).max())
    return 100 * dev / d, cmd, load, b, err


def run(sec) -> dict:
    via = via_points()
    wn = [math.sqrt(k / m) for (m, _, k) in ROBOT.values()]
    T40 = bspline_period(wn=wn, Ts=TS)           # T >= 2 pi/min(wn): w0 <= 40 rad/s
    T50 = 2 * math.pi / 50.0
    d = float(np.mean(np.linalg.norm(np.diff(via, axis=0), axis=1)))
    sec.add(Claim("robot.spacing", "Sec. IV: mean via-point distance d", d, 0.0454, 5e-4,
                  "paper (~0.0454 m)", unit="m", paper=0.0454))
    sec.add(Claim("robot.T_rule", "Sec. IV: knot spacing from bspline_period (T >= 2 pi/min wn)",
                  T40, math.ceil(2 * math.pi / 40.0 / TS) * TS, 1e-12,
                  "closed form ceil(2 pi/(40 Ts)) Ts", unit="s"))
    res = {}
    for p in (3, 4, 5):
        for name, T in (("w0<=40", T40), ("w0=50", T50)):
            res[(p, name)] = rv(p, T, via)
    for p in (3, 4, 5):
        sec.add(Claim(f"robot.interp.p{p}", f"Fig. 16: B-spline p = {p} through the via-points "
                      "(max error at the pass samples)", res[(p, "w0<=40")][4], 0.0, 1e-9,
                      "exact interpolation", unit="m"))
    for p in (4, 5):
        for i, axis in enumerate("xy"):
            sec.add(Claim(f"robot.rv.p{p}.{axis}", f"Fig. 11: RV on {axis}, p = {p} over p = 3 "
                          "(w0 <= 40 rad/s)",
                          res[(p, "w0<=40")][0][i] / res[(3, "w0<=40")][0][i], 1.0, 0.0,
                          "paper: higher degree, lower vibration", relation="<="))
    sec.add(Claim("robot.rv.y_above", "Fig. 10: RV on y (wn = 40 rad/s), p = 3, with w0 = 50 "
                  "over w0 <= 40 rad/s", res[(3, "w0=50")][0][1] / res[(3, "w0<=40")][0][1], 1.0,
                  0.0, "paper: vibration stays limited only while w0 <= wn", relation=">="))
    # Fig. 3-4: spectrum of the x command (its velocity, which starts and ends at rest)
    spectra = {}
    w = np.linspace(1.0, 250.0, 2500)
    for p in (1, 3, 5):
        b = BSpline(degree=p, T=T50, Ts=TS, axes=3)
        v = np.diff(b.interpolate(via, extra=10)[:, 0], prepend=via[0, 0]) / TS
        V = TS * np.abs(np.exp(-1j * np.outer(w, np.arange(v.size)) * TS) @ v)
        spectra[p] = V
        w0 = 2 * math.pi / b.T
        at = TS * abs(np.sum(v * np.exp(-1j * w0 * np.arange(v.size) * TS)))
        sec.add(Claim(f"robot.spectrum_zero.p{p}", f"Fig. 3-4: x velocity spectrum of the "
                      f"B-spline p = {p} at w0 = 2 pi/T, over its peak", at / V.max(), 0.0, 1e-9,
                      "exact zero of M^p at w0"))
    sec.add(Claim("robot.spectrum_p", "Fig. 4: x velocity spectrum above 1.5 w0, p = 5 over p = 1 "
                  "(largest ratio of the peaks)",
                  float(spectra[5][w > 75].max() / spectra[1][w > 75].max()), 0.1, 0.0,
                  "paper: higher degree, stronger attenuation of high frequencies",
                  relation="<="))
    # Input shapers do not interpolate (Fig. 15): ZV at 50 rad/s on the linear path
    lin = BSpline(degree=1, T=T40, Ts=TS, axes=3).interpolate(via, extra=200)
    zv = st.shaper("zv", wn=50.0)
    shaped = np.column_stack([ref.filter([zv], lin[:, i] - lin[0, i], Ts=TS) + lin[0, i]
                              for i in range(3)])
    miss = max(float(np.min(np.linalg.norm(shaped - q, axis=1))) for q in via[1:-1])
    sec.add(Claim("robot.is_miss", "Fig. 15: largest distance from a via-point to the ZV-shaped "
                  "linear path (w0 = 50 rad/s)", miss, 1e-4, 0.0,
                  "paper: input shapers do not pass through the via-points", unit="m",
                  relation=">="))
    rows = ["| degree p | RV x, w0 <= 40 [%] | RV y, w0 <= 40 [%] | RV x, w0 = 50 [%] | "
            "RV y, w0 = 50 [%] |", "|---|---|---|---|---|"]
    for p in (3, 4, 5):
        a, b = res[(p, "w0<=40")][0], res[(p, "w0=50")][0]
        rows.append(f"| {p} | {a[0]:.3g} | {a[1]:.3g} | {b[0]:.3g} | {b[1]:.3g} |")
    body = "\n".join([
        f"Robot example (Sec. IV): {via.shape[0]} via-points along three straight lines joined by "
        f"two circular bends (radius {BEND_RADIUS} m), spacing d = {d:.4f} m, z rising 0.05 m; "
        "`smoothshaper.trajectory.BSpline(degree=p, T=..., Ts=1 ms, axes=3)` computes the "
        "control points and filters them; the axes are Table I's, simulated exactly. "
        f"T = {T40:.3f} s from `bspline_period` (w0 = {2 * math.pi / T40:.2f} rad/s <= "
        f"min wn = 40) against T = {T50:.4f} s (w0 = 50 rad/s, above the y mode). Residual "
        "vibration after the stop, in % of d:", "", *rows, "",
        f"A ZV shaper (50 rad/s) on the piecewise-linear path misses the via-points at the "
        f"bends by up to {1000 * miss:.1f} mm; the B-splines pass through them to 1e-9 m.",
        "The paper's RV figures (10-14) are measured on its own path during the motion and "
        "are not reproduced number for number: its via-points are not published."])

    def figures(sec_, fig_dir: Path):
        _figures(sec_, fig_dir, via, res, shaped, T40)
        with figure(fig_dir / "fig4_spectra.png", "Seed 003 Fig. 3-4: spectrum of the x-axis "
                    "velocity of B-splines of degree 1, 3, 5 through the via-points, T = 2 pi/50 s",
                    sec_.figures) as (f, ax):
            for p_, V in spectra.items():
                ax.semilogy(w, V, label=f"p = {p_}")
            for k in (1, 2, 3, 4):
                ax.axvline(50 * k, color="0.6", lw=0.6)
            ax.set_ylim(1e-6, None)
            ax.set_xlabel("frequency [rad/s]")
            ax.set_ylabel("|V_x(w)| [m]")
    return {"body": body, "figures": figures}


def _figures(sec, fig_dir, via, res, shaped, T40):
    with figure(fig_dir / "robot_path.png", "Seed 003 Sec. IV: via-points, cubic B-spline "
                "command and robot (load) path in the x-y plane; right: detail of the first bend "
                "with the ZV-shaped linear path", sec.figures, ncols=2, size=(12, 5)) as (f, ax):
        _, cmd, load, _, _ = res[(3, "w0<=40")]
        for a in ax:
            a.plot(via[:, 0], via[:, 1], "ko", ms=4, label="via-points")
            a.plot(cmd[:, 0], cmd[:, 1], color="tab:blue", label="B-spline p = 3 (command)")
            a.plot(load[:, 0], load[:, 1], color="tab:red", lw=0.8, label="robot (load)")
            a.set_xlabel("x [m]")
            a.set_ylabel("y [m]")
        ax[1].plot(shaped[:, 0], shaped[:, 1], "--", color="tab:green",
                   label="ZV-shaped linear path")
        ax[1].set_xlim(0.25, 0.40)
        ax[1].set_ylim(-0.02, 0.13)
        ax[0].set_aspect("equal")
    with figure(fig_dir / "robot_rv.png", "Seed 003 Fig. 10-11: deviation of the load from the "
                "command on the y axis (wn = 40 rad/s) for p = 3, 4, 5, with w0 <= 40 rad/s "
                "(left) and w0 = 50 rad/s (right)", sec.figures, ncols=2, size=(12, 4)) as (f, ax):
        for col, name in enumerate(("w0<=40", "w0=50")):
            for p in (3, 4, 5):
                _, cmd, load, _, _ = res[(p, name)]
                t = np.arange(cmd.shape[0]) * TS
                ax[col].plot(t, 1000 * (load[:, 1] - cmd[:, 1]), lw=0.8, label=f"p = {p}")
            ax[col].set_title(name.replace("<=", " <= ").replace("=50", " = 50") + " rad/s",
                              fontsize=9)
            ax[col].set_xlabel("time [s]")
            ax[col].set_ylabel("load - command, y [mm]")
