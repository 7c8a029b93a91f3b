# SPDX-License-Identifier: Apache-2.0
"""Seed 003 (Biagiotti & Melchiorri): input shaping via B-spline filters.

Claims of the paper and what this section checks (w0 = 2 pi/T):

=====================================================  ==========================================
paper                                                  check
=====================================================  ==========================================
eq. 4, Fig. 5: |M^p(jw)| = |sinc(w/w0)|^p; PRV of M^p  PRV = 100 |sinc(r)|^p, zero at r = 1, not
is 0 at wn = w0 and decreases with p                   increasing with p
Fig. 6: ZV^p IS: C(s) = ((1 + e^{-s pi/w0})/2)^p;      PRV = 100 |cos(pi r/2)|^p; near r = 1 M^3
M^3 and ZVDDD comparable near w0, M^3 strongly         and ZVDDD within a factor ~3; asymmetry
asymmetric; insensitivity of M^p "may be made          PRV(0.8)/PRV(1.2) = 1.5^3; PRV <= 5 % for
infinite": PRV <= V_tol for all wn >= w0               every r >= r_5 (root of sinc^3 = 0.05)
Table I: wn = 60 rad/s, delta = 0.012 (x, z);          plants.cartesian_axis poles
wn = 40 rad/s, delta = 0.008 (y)
Fig. 3-4: the spline's spectrum is P(jw) sinc^p,       velocity spectrum of the spline through
zero at k w0, lower at high frequency for larger p      the robot's via-points: 0 at w0; p = 5 vs 1
Sec. IV: B-spline through via-points on three axes,    smoothshaper.trajectory.BSpline: via-points
exact interpolation, T >= 2 pi/min(wn)                 hit, residual vibration vs p and w0; a ZV
                                                       shaper misses the via-points (Fig. 15)
(beyond the paper) the same robot and via-points       MultiAxisGenerator: common arrival, straight
through the multi-axis generator                       lines, limits, residual vibration per axis
=====================================================  ==========================================
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import analysis, plants
from .. import stages as st
from .claims import Claim, Section
from .figures import COLORS, figure
from .seed003_robot import ROBOT, ROBOT_PAPER, run as robot_run
from .seed003_robot import via_points as robot_via_points

__all__ = ["COMMAND", "build"]

COMMAND = "python -m smoothshaper.report --out report --only seed003"
W0 = 50.0                                  # rad/s, as the paper's Fig. 3 (T = 0.1257 s)
R = np.linspace(0.01, 3.0, 3000)           # wn / w0


def bspline_chain(p: int, w0: float = W0):
    return [st.rectangular(T=2 * math.pi / w0)] * p


def zv_power(p: int, w0: float = W0):
    """ZV^p for the undamped mode w0 (p = 1 ZV, 2 ZVD, 3 ZVDD, 4 ZVDDD)."""
    return [st.shaper("zvn", wn=w0, order=p)]


def r5_closed_form(p: int = 3, level: float = 0.05) -> float:
    """Below w0, the ratio where |sinc(r)|^p = level (the band of PRV <= level starts there)."""
    from scipy.optimize import brentq
    return brentq(lambda r: np.sinc(r) - level ** (1 / p), 0.3, 1.0, xtol=1e-15)


def build(fig_dir=None) -> Section:
    sec = Section(
        key="seed003",
        title="Seed 003: input shaping via B-spline filters (Biagiotti & Melchiorri)",
        claim=("A uniform B-spline of degree p is a step through p rectangular smoothers of "
               "length T; as an input shaper its PRV |sinc(wn/w0)|^p vanishes at w0 = 2 pi/T, "
               "falls with p and stays below any tolerance for all wn >= w0 (for p large "
               "enough), unlike the ZV^p shapers whose PRV is periodic; a cubic B-spline is "
               "comparable to ZVDDD near w0."),
        command=COMMAND)
    data = {}
    prv_m = {p: analysis.prv(bspline_chain(p), wn=R * W0) for p in range(1, 5)}
    prv_zv = {p: analysis.prv(zv_power(p), wn=R * W0) for p in range(1, 5)}
    data.update(prv_m=prv_m, prv_zv=prv_zv)
    for p in range(1, 5):
        sec.add(Claim(f"fig5.zero.p{p}", f"Fig. 5: PRV of M^{p} at wn = w0",
                      float(analysis.prv(bspline_chain(p), wn=W0)), 0.0, 1e-10, "exact zero",
                      unit="%"))
        for r in (0.5, 1.5):
            sec.add(Claim(f"fig5.p{p}.r{r}", f"Fig. 5: PRV of M^{p} at wn/w0 = {r}",
                          float(analysis.prv(bspline_chain(p), wn=r * W0)),
                          100 * abs(np.sinc(r)) ** p, 1e-9, "closed form 100 |sinc(r)|^p",
                          unit="%"))
            sec.add(Claim(f"fig6.zv{p}.r{r}", f"Fig. 6: PRV of ZV^{p} at wn/w0 = {r}",
                          float(analysis.prv(zv_power(p), wn=r * W0)),
                          100 * abs(math.cos(math.pi * r / 2)) ** p, 1e-9,
                          "closed form 100 |cos(pi r/2)|^p", unit="%"))
    sec.add(Claim("fig5.monotone", "Fig. 5: max over r and p of PRV(M^{p+1}) - PRV(M^p)",
                  float(max(np.max(prv_m[p + 1] - prv_m[p]) for p in range(1, 4))), 0.0, 1e-12,
                  "paper: vibration decreases with p", unit="%", relation="<="))
    near = [float(analysis.prv(bspline_chain(3), wn=r * W0) / analysis.prv(zv_power(4), wn=r * W0))
            for r in (0.9, 1.1)]
    sec.add(Claim("fig6.comparable", "Fig. 6: max over r = 0.9, 1.1 of PRV(M^3)/PRV(ZVDDD)",
                  max(near), 4.0, 0.0, "paper: comparable near w0 (same order)", relation="<="))
    sec.add(Claim("fig6.asymmetry", "Fig. 6: PRV(M^3) at 0.8 w0 over at 1.2 w0",
                  float(analysis.prv(bspline_chain(3), wn=0.8 * W0)
                        / analysis.prv(bspline_chain(3), wn=1.2 * W0)),
                  1.5 ** 3, 1e-9, "closed form (1.2/0.8)^3 (|sin| equal)"))
    r5 = r5_closed_form()
    beyond = np.linspace(r5, 40.0, 200001)
    sec.add(Claim("fig6.infinite", "Sec. III: max PRV of M^3 for all wn/w0 in [r_5, 40], "
                  f"r_5 = {r5:.4f}", float(analysis.prv(bspline_chain(3), wn=beyond * W0).max()),
                  5.0, 1e-9, "5 % tolerance (infinite insensitivity)", unit="%", relation="<="))
    zvddd = analysis.insensitivity(zv_power(4), wn_hat=W0, tolerance=0.05)
    sec.add(Claim("fig6.zvddd_band", "Fig. 6: 5 % insensitivity of ZVDDD (finite)",
                  zvddd.relative_width, 2 * (1 - 2 / math.pi * math.acos(0.05 ** 0.25)), 1e-8,
                  "closed form 2 (1 - (2/pi) arccos(0.05^(1/4)))"))
    sec.add(Claim("fig6.zvddd_periodic", "Fig. 6: PRV of ZVDDD at wn = 2 w0 (periodic, back "
                  "to 100 %)", float(analysis.prv(zv_power(4), wn=2 * W0)), 100.0, 1e-9,
                  "closed form |cos(pi)|^4", unit="%"))
    for axis, (m, d, k) in ROBOT.items():
        poles = plants.cartesian_axis(m=m, d=d, k=k).poles()
        wn = float(np.abs(poles[0]))
        delta = float(-poles[0].real / wn)
        pw, pd = ROBOT_PAPER[axis]
        sec.add(Claim(f"robot.{axis}.wn", f"Table I: axis {axis} natural frequency", wn, pw, 0.05,
                      "paper (2 digits)", unit="rad/s", paper=pw),
                Claim(f"robot.{axis}.delta", f"Table I: axis {axis} damping ratio", delta, pd,
                      5e-4, "paper (3 decimals)", paper=pd))
    data["r5"], data["zvddd"] = r5, zvddd
    _via_points(sec, data)
    sec.body = _body(data)
    if fig_dir is not None:
        _figures(sec, Path(fig_dir), data)
    return sec


def _via_points(sec, data):
    """Sec. IV robot example (smoothshaper.trajectory.BSpline, see seed003_robot)."""
    from . import seed003_multi_axis
    data["via"] = robot_run(sec)
    data["multi"] = seed003_multi_axis.run(sec, robot_via_points())


def _body(d) -> str:
    lines = [f"w0 = {W0:g} rad/s (T = {2 * math.pi / W0:.4f} s, the paper's Fig. 3). "
             f"M^3's PRV stays at or below 5 % for every wn >= {d['r5']:.4f} w0 (infinite "
             f"insensitivity upward), ZVDDD's only on [{d['zvddd'].low / W0:.4f}, "
             f"{d['zvddd'].high / W0:.4f}] w0 and is back to 100 % at 2 w0."]
    lines += ["", d["via"]["body"], "", d["multi"]["body"]]
    return "\n".join(lines)


def _figures(sec, fig_dir, d):
    with figure(fig_dir / "fig5_fig6_prv.png", "Seed 003 Fig. 5 and 6: PRV of the B-spline "
                "filters M^p (p = 1..4) and of ZV^p shapers against wn/w0 (undamped)",
                sec.figures, ncols=2, size=(11, 4)) as (f, ax):
        for p in range(1, 5):
            ax[0].plot(R, d["prv_m"][p], label=f"M^{p}")
        ax[1].plot(R, d["prv_m"][3], color="tab:blue", lw=2.5, label="M^3 (cubic B-spline)")
        for p, name in zip(range(1, 5), ("ZV", "ZVD", "ZVDD", "ZVDDD")):
            ax[1].plot(R, d["prv_zv"][p], color=COLORS[name.lower()], label=name)
        ax[1].axhline(5, color="k", ls="--", lw=0.8, label="5 %")
        for a in ax:
            a.set_xlabel("wn / w0 [-]")
            a.set_ylabel("percent residual vibration [%]")
            a.set_ylim(0, 100)
        # the ZV^p curves fill the whole panel: the legend goes beside it
        ax[1].legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    d["via"]["figures"](sec, fig_dir)
    d["multi"]["figures"](sec, fig_dir)
