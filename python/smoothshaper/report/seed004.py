# SPDX-License-Identifier: Apache-2.0
"""Seed 004 (Bascetta, "Motion control: advanced control techniques"): input shaping and notch;
the closed-loop part (TDO, pole placement, LQG vs PID, shaping on the drive) is
:mod:`.seed004_servo`.

Claims and numbers extracted from the seed (it prints formulas and figures, no residual values):

====================================================  =========================================
seed                                                  what we check
====================================================  =========================================
ZV: t = 0, DT/2; k = 1/(1+a), a/(1+a),                amplitudes/times of the library's ZV
a = exp(-xi pi/sqrt(1-xi^2))                          against this closed form (1e-12)
ZVD: t = 0, DT/2, DT; k = (1, 2a, a^2)/(1+a)^2        same for ZVD
example wn = 1 rad/s, xi = 0.05                       PRV = 0 at the nominal mode (both)
"error of 10 % on wn and of 20 % on xi": ZV leaves    PRV at the four error corners vs the
oscillation, ZVD "good damping even with errors"      closed form; ZVD below ZV at each
servo wz = 200 rad/s, xi_z = 0.1; notch zeros on      matched: H(e^{p Ts}) = 0; Tustin
the poles; digitising distorts the frequency,         pre-warped: |H(e^{j wn Ts})| = xi1/xi2
pre-warping overcomes it                              exactly; un-warped notch lands at
                                                      (2/Ts) atan(wn Ts/2)
====================================================  =========================================
"""
from __future__ import annotations

import math

import numpy as np

from .. import stages as st
from ..reference.filtering import discrete_transfer
from ..reference.shapers import shaper_impulses
from .. import analysis
from .claims import Claim, Section
from .figures import COLORS, figure

__all__ = ["COMMAND", "build"]

WN, XI = 1.0, 0.05               # shaping example
WN_ERR, XI_ERR = 0.10, 0.20      # relative errors of the seed
SERVO_WZ, SERVO_XI = 200.0, 0.1  # servo of the notch example
NOTCH_POLE_XI = 0.7              # not given by the seed: a common choice
NOTCH_TS = 5e-3                  # coarse on purpose (wz Ts = 1) so warping is visible

COMMAND = "python -m smoothshaper.report --out report --only seed004"


def zv_closed_form(xi: float, wn: float):
    a = math.exp(-xi * math.pi / math.sqrt(1 - xi * xi))
    td = 2 * math.pi / (wn * math.sqrt(1 - xi * xi))
    return a, np.array([1, a]) / (1 + a), np.array([0, td / 2])


def zvd_closed_form(xi: float, wn: float):
    a, _, t = zv_closed_form(xi, wn)
    return np.array([1, 2 * a, a * a]) / (1 + a) ** 2, np.array([0, t[1], 2 * t[1]])


def prv_closed_form(amps, times, wn, xi) -> float:
    """100 |sum_i k_i e^{-p t_i}| for the true mode (wn, xi): the seed's A_t over the
    single-impulse amplitude, written from its superposition argument."""
    p = complex(-xi * wn, wn * math.sqrt(1 - xi * xi))
    return 100 * abs(sum(k * np.exp(-p * t) for k, t in zip(amps, times)))


def error_corners():
    """The four true modes (wn, xi) when the estimate (1, 0.05) is off by 10 % / 20 %."""
    return [(WN * (1 + sw * WN_ERR), XI * (1 + sx * XI_ERR)) for sw in (-1, 1) for sx in (-1, 1)]


def build(fig_dir=None) -> Section:
    sec = Section(
        key="seed004",
        title="Seed 004: input shaping, the notch filter and the servo in closed loop",
        claim=("A ZV shaper (two positive impulses, the second half a damped period later) "
               "cancels the mode it is designed for; with 10 % error on wn and 20 % on xi it "
               "leaves an oscillation, which the three-impulse ZVD shaper largely removes. A "
               "notch cancels a pair of lightly damped poles; digitising it distorts its "
               "frequency unless the bilinear transform is pre-warped. In closed loop, a torque "
               "disturbance observer rejects load torque on the rigid model (high-pass "
               "sT_f/(1+sT_f)) but leaves the elastic load oscillating at the locked "
               "frequency; observer-based pole placement with integral action and "
               "feed-forward, and LQG, act on every state, and LQG beats PID on three "
               "trapezoidal moves."),
        command=COMMAND)
    zv = st.shaper("zv", wn=WN, zeta=XI)
    zvd = st.shaper("zvd", wn=WN, zeta=XI)

    a, k_zv, t_zv = zv_closed_form(XI, WN)
    k_zvd, t_zvd = zvd_closed_form(XI, WN)
    A, t = shaper_impulses(zv)
    sec.add(Claim("zv.alpha", "ZV amplitude ratio k2/k1 = alpha", A[1] / A[0], a, 1e-12,
                  "closed form exp(-xi pi/sqrt(1-xi^2))"),
            Claim("zv.k1", "ZV first amplitude k1", A[0], k_zv[0], 1e-12,
                  "closed form 1/(1+alpha)"),
            Claim("zv.t2", "ZV second impulse time", t[1], t_zv[1], 1e-12,
                  "closed form DT/2 = pi/wd", unit="s"))
    A2, t2 = shaper_impulses(zvd)
    sec.add(Claim("zvd.k2", "ZVD middle amplitude k2", A2[1], k_zvd[1], 1e-12,
                  "closed form 2 alpha/(1+alpha)^2"),
            Claim("zvd.t3", "ZVD third impulse time", t2[2], t_zvd[2], 1e-12,
                  "closed form DT = 2 pi/wd", unit="s"))
    for name, stage in (("zv", zv), ("zvd", zvd)):
        sec.add(Claim(f"{name}.nominal", f"{name.upper()} PRV at the nominal mode",
                      float(analysis.prv([stage], wn=WN, zeta=XI)), 0.0, 1e-10,
                      "exact cancellation", unit="%"))

    rows, worst = [], {}
    for wn, xi in error_corners():
        p_zv = float(analysis.prv([zv], wn=wn, zeta=xi))
        p_zvd = float(analysis.prv([zvd], wn=wn, zeta=xi))
        tag = f"wn={wn:g},xi={xi:g}"
        sec.add(Claim(f"zv.err.{tag}", f"ZV PRV, true mode wn = {wn:g}, xi = {xi:g}", p_zv,
                      prv_closed_form(k_zv, t_zv, wn, xi), 1e-9, "closed form", unit="%"),
                Claim(f"zvd.err.{tag}", f"ZVD PRV, true mode wn = {wn:g}, xi = {xi:g}", p_zvd,
                      prv_closed_form(k_zvd, t_zvd, wn, xi), 1e-9, "closed form", unit="%"))
        rows.append((wn, xi, p_zv, p_zvd))
        worst["zv"] = max(worst.get("zv", 0), p_zv)
        worst["zvd"] = max(worst.get("zvd", 0), p_zvd)
    sec.add(Claim("zvd.better", "worst ZVD PRV over the four error corners, over the worst ZV",
                  worst["zvd"] / worst["zv"], 0.25, 0.0,
                  "seed: ZVD keeps 'a good damping even in the presence of parameter errors'",
                  relation="<="))

    _pulse_simulation(sec, zv, zvd)
    notch_rows = _notch(sec)
    from . import seed004_servo
    servo_body = seed004_servo.run(sec, fig_dir)
    sec.body = _body(rows, notch_rows) + "\n\n" + servo_body
    if fig_dir is not None:
        _figures(sec, fig_dir, zv, zvd)
    return sec


PULSE_TS = 0.01


def _pulse_simulation(sec, zv, zvd):
    """The seed's rectangular torque pulse, shaped, into the mode (exact ZOH): the residual over
    the unshaped pulse's is the discrete shaper's |H(e^{p Ts})|, nominal and with the errors."""
    from .. import plants
    from ..reference import filter as ref_filter
    Ts = PULSE_TS
    t = np.arange(0, 80, Ts)
    u = ((t >= 1) & (t < 11)).astype(float)
    for wn, xi in ((WN, XI), (1.1 * WN, 0.8 * XI)):
        plant = plants.mode(wn=wn, zeta=xi)
        _, y0 = plants.simulate_zoh(plant, u, Ts=Ts)
        a0 = plants.residual_amplitude(t, y0, wn=wn, zeta=xi, t_start=20.0)
        for name, stage in (("zv", zv), ("zvd", zvd)):
            _, y = plants.simulate_zoh(plant, ref_filter([stage], u, Ts=Ts), Ts=Ts)
            ratio = 100 * plants.residual_amplitude(t, y, wn=wn, zeta=xi, t_start=20.0) / a0
            sec.add(Claim(f"{name}.sim.wn={wn:g},xi={xi:g}", f"{name.upper()}: shaped pulse, "
                          f"simulated residual over the unshaped one, true wn = {wn:g}, "
                          f"xi = {xi:g}", ratio,
                          float(analysis.prv([stage], wn=wn, zeta=xi, Ts=Ts)), 1e-6,
                          "discrete |H(e^{p Ts})| (Ts = 10 ms)", unit="%"))


def _notch(sec: Section):
    """Both discretisations of the notch that cancels the servo mode (200 rad/s, 0.1)."""
    Ts, wz, xi1, xi2 = NOTCH_TS, SERVO_WZ, SERVO_XI, NOTCH_POLE_XI
    p = complex(-xi1 * wz, wz * math.sqrt(1 - xi1 * xi1))
    zp = np.exp(p * Ts)
    out = {}
    for disc in ("matched", "tustin"):
        stage = st.notch(wn=wz, zeta=xi1, notch_pole_zeta=xi2, discretization=disc)
        out[disc] = (stage,
                     abs(complex(discrete_transfer(stage, zp, Ts=Ts))),
                     abs(complex(discrete_transfer(stage, np.exp(1j * wz * Ts), Ts=Ts))))
    sec.add(Claim("notch.matched.pole", "matched notch: |H| at the sampled mode e^{p Ts}",
                  out["matched"][1], 0.0, 1e-12, "zeros placed exactly on e^{p Ts}"))
    sec.add(Claim("notch.tustin.centre", "pre-warped Tustin notch: |H(e^{j wz Ts})|",
                  out["tustin"][2], xi1 / xi2, 1e-12,
                  "closed form xi1/xi2 = |G_nf(j wz)|: pre-warping maps wz exactly"))
    # Tustin's zeros are the bilinear images of the continuous zeros, not e^{p Ts}: closed form.
    c = wz / math.tan(wz * Ts / 2)
    s_roots = np.roots([1, 2 * xi1 * wz, wz * wz])
    s_poles = np.roots([1, 2 * xi2 * wz, wz * wz])
    zz = (c + s_roots) / (c - s_roots)
    zpl = (c + s_poles) / (c - s_poles)
    gain = np.prod(1 - zpl) / np.prod(1 - zz)
    closed = abs(gain * np.prod(zp - zz) / np.prod(zp - zpl))
    sec.add(Claim("notch.tustin.pole", "pre-warped Tustin notch: |H| at e^{p Ts} (the mode leaks)",
                  out["tustin"][1], closed, 1e-12,
                  "closed form from the bilinear images of the zeros"))
    # Without pre-warping the bilinear transform puts the notch at (2/Ts) atan(wz Ts/2).
    warped = 2 / Ts * math.atan(wz * Ts / 2)
    sec.add(Claim("notch.unwarped.centre", "Tustin without pre-warping: notch centre",
                  _unwarped_notch_centre(wz, xi1, xi2, Ts), warped, 1e-6 * wz,
                  "closed form (2/Ts) atan(wz Ts/2)", unit="rad/s"))
    return out


def _unwarped_notch_centre(wz, xi1, xi2, Ts) -> float:
    """Frequency of the minimum of |H| for the plain bilinear notch (scipy's bilinear, the
    textbook transform the seed warns about; not a library filter)."""
    from scipy.signal import bilinear, freqz
    from scipy.optimize import minimize_scalar
    b, a = bilinear([1, 2 * xi1 * wz, wz * wz], [1, 2 * xi2 * wz, wz * wz], fs=1 / Ts)

    def mag(w):
        return abs(freqz(b, a, worN=[w * Ts])[1][0])
    res = minimize_scalar(mag, bounds=(0.5 * wz, 1.2 * wz), method="bounded",
                          options={"xatol": 1e-9})
    return float(res.x)


def _body(rows, notch) -> str:
    lines = ["The shapers are `smoothshaper.shaper('zv'|'zvd', wn=1, zeta=0.05)`; PRV is "
             "`100 |H(p)|` at the true pole p (the residual amplitude over the unshaped one). "
             "The seed shows the error case only as a plot and does not say in which direction "
             "the estimates are wrong, so all four corners are computed:", "",
             "| true wn [rad/s] | true xi | ZV PRV [%] | ZVD PRV [%] |", "|---|---|---|---|"]
    lines += [f"| {wn:g} | {xi:g} | {a:.2f} | {b:.2f} |" for wn, xi, a, b in rows]
    lines += ["", f"Notch for the servo mode wz = {SERVO_WZ:g} rad/s, xi_z = {SERVO_XI:g}, pole "
              f"damping xi2 = {NOTCH_POLE_XI:g} (the seed gives none), Ts = {NOTCH_TS * 1e3:g} ms "
              "(wz Ts = 1, coarse on purpose). Matched zeros sit on the sampled mode and cancel "
              f"it (|H(e^(pTs))| = {notch['matched'][1]:.1e}); the pre-warped Tustin notch is "
              "exact at the centre frequency but its zeros are the bilinear images of the "
              f"continuous zeros, so |H(e^(pTs))| = {notch['tustin'][1]:.3f}: for cancelling a "
              "damped mode the matched form is the right one."]
    return "\n".join(lines)


def _figures(sec, fig_dir, zv, zvd):
    from pathlib import Path
    from ..reference.filtering import filter as ref_filter
    from scipy.signal import cont2discrete, lfilter
    fig_dir = Path(fig_dir)
    Ts = 0.01
    t = np.arange(0, 60, Ts)
    u = ((t >= 1) & (t < 11)).astype(float)     # the seed's rectangular torque profile
    with figure(fig_dir / "shaped_pulse.png", "Seed 004: load velocity for a rectangular "
                "torque pulse, unshaped / ZV / ZVD, nominal mode and with 10 % error on wn and "
                "20 % on xi (true wn = 1.1, xi = 0.04)", sec.figures, nrows=2,
                size=(8, 6)) as (f, ax):
        for row, (wn, xi, label) in enumerate(((WN, XI, "nominal wn = 1, xi = 0.05"),
                                               (1.1, 0.04, "true wn = 1.1, xi = 0.04"))):
            num, den = [wn * wn], [1, 2 * xi * wn, wn * wn]
            b, a, _ = cont2discrete((num, den), Ts, method="zoh")
            for name, stages, color in (("unshaped", None, "0.6"), ("ZV", [zv], COLORS["zv"]),
                                        ("ZVD", [zvd], COLORS["zvd"])):
                x = u if stages is None else ref_filter(stages, u, Ts=Ts)
                ax[row].plot(t, lfilter(b.ravel(), a, x), color=color, label=name)
            ax[row].set_title(label, fontsize=9)
            ax[row].set_xlabel("time [s]")
            ax[row].set_ylabel("load velocity [rad/s per N m]")
    r = np.linspace(0.5, 1.5, 801)
    with figure(fig_dir / "sensitivity.png", "Seed 004: PRV of ZV and ZVD against the true "
                "natural frequency (design wn = 1 rad/s, xi = 0.05), true xi = 0.05 and 0.06",
                sec.figures) as (f, ax):
        for stage, name in ((zv, "ZV"), (zvd, "ZVD")):
            for xi, ls in ((XI, "-"), (1.2 * XI, "--")):
                ax.plot(r, analysis.prv([stage], wn=r * WN, zeta=xi), ls, color=COLORS[stage.kind],
                        label=f"{name}, true xi = {xi:g}")
        ax.axvline(1.1, color="0.5", lw=0.8)
        ax.set_xlabel("true wn / design wn [-]")
        ax.set_ylabel("percent residual vibration [%]")
    w = np.linspace(1, 0.99 * math.pi / NOTCH_TS, 2000)
    with figure(fig_dir / "notch.png", f"Seed 004: notch for wz = {SERVO_WZ:g} rad/s, xi1 = "
                f"{SERVO_XI:g}, xi2 = {NOTCH_POLE_XI:g} at Ts = {NOTCH_TS * 1e3:g} ms: continuous, "
                "pre-warped Tustin, pole-zero matched, and plain Tustin", sec.figures) as (f, ax):
        notch = st.notch(wn=SERVO_WZ, zeta=SERVO_XI, notch_pole_zeta=NOTCH_POLE_XI)
        g = abs(analysis.transfer([notch], 1j * w))
        ax.plot(w, 20 * np.log10(g), color="k", label="continuous")
        for disc, color in (("tustin", "tab:blue"), ("matched", "tab:red")):
            stage = st.notch(wn=SERVO_WZ, zeta=SERVO_XI, notch_pole_zeta=NOTCH_POLE_XI,
                             discretization=disc)
            hd = np.abs(discrete_transfer(stage, np.exp(1j * w * NOTCH_TS), Ts=NOTCH_TS))
            ax.plot(w, 20 * np.log10(hd), "--", color=color, label=f"{disc} (library)")
        from scipy.signal import bilinear, freqz
        b, a = bilinear([1, 2 * SERVO_XI * SERVO_WZ, SERVO_WZ ** 2],
                        [1, 2 * NOTCH_POLE_XI * SERVO_WZ, SERVO_WZ ** 2], fs=1 / NOTCH_TS)
        ax.plot(w, 20 * np.log10(np.abs(freqz(b, a, worN=w * NOTCH_TS)[1])), ":", color="0.4",
                label="Tustin without pre-warping (seed's warning)")
        ax.set_xlabel("frequency [rad/s]")
        ax.set_ylabel("magnitude [dB]")
