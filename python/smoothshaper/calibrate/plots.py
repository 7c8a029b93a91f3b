# SPDX-License-Identifier: Apache-2.0
"""The two calibration figures (matplotlib, Agg).

``calibrate_psd.png``: per axis, the measured PSD (frequency axis in Hz, rad/s in the legend),
the identified modes, the PSD left after the recommended filter and, on the right axis, the
residual vibration of the top candidates versus the mode frequency (the picture users know from
3-D printer tuning). ``calibrate_band.png``: per axis, each top candidate's remaining vibration
as the first mode's natural frequency moves across its uncertainty band.
"""
from __future__ import annotations

import math
import os

import numpy as np

from .. import _optional
from .._plotting import percent_axis
from .candidates import BOX, candidate_taps

__all__ = ["COLORS", "write"]

COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")


def _R(h, Ts, wn, zeta):
    zeta = np.broadcast_to(zeta, np.shape(wn))
    p = -zeta * wn + 1j * wn * np.sqrt(1 - zeta * zeta)
    k = np.arange(h.size)
    return np.abs(np.exp(-np.outer(p, k) * Ts) @ h)


def _spectrum(res):
    if res.spectrum is not None:
        return res.spectrum.f, res.spectrum.P, "PSD" if res.record.kind != "frf" else "|H|^2"
    import scipy.signal
    x = res.record.signals[:, 0]
    f, P = scipy.signal.periodogram(x - x.mean(), fs=1 / res.record.Ts, window="hann")
    return f, P, "periodogram of the decay"


def _top(res, n):
    top = [c for c in res.candidates if (c.stages or c.firmware is not None) and c.meets][:n]
    if res.recommended is not None and res.recommended not in top:
        top = [res.recommended] + top[: n - 1]
    return top


def _modes(res):
    """The fitted modes, or (none confirmed) the spectrum's largest bin as one, zeta 0.1."""
    if res.modes:
        return res.modes
    from .modes import Mode
    f, P = res.spectrum.f, res.spectrum.P
    inb = (f >= res.band[0]) & (f <= res.band[1]) & (f > 0)
    fp = float(f[inb][np.argmax(P[inb])]) if inb.any() else float(np.mean(res.band))
    return [Mode(wn=2 * math.pi * fp, zeta=0.1, wn_std=0.0, zeta_std=0.0)]


def write(cal, out_dir: str) -> list[str]:
    plt = _optional.pyplot("calibrate's figures (--out)")
    os.makedirs(out_dir, exist_ok=True)
    Ts = cal.reference.Ts
    n = len(cal.axes)
    paths = []

    fig, axes = plt.subplots(n, 1, figsize=(10, 5.6 * n), squeeze=False)
    for ax, res in zip(axes[:, 0], cal.axes):
        f, P, label = _spectrum(res)
        lo, hi = res.band
        modes = _modes(res)
        m0 = modes[0]
        show = (f >= max(lo, 0.2 * m0.f_hz) * 0.8) & (f <= min(hi, 3.0 * modes[-1].f_hz
                                                                 if len(res.modes) else hi))
        show &= f > 0
        ax.semilogy(f[show], P[show], color="black", lw=1.2, label=f"measured {label}")
        rec = res.recommended
        # the residual at each frequency for the damping of the nearest mode
        fm = np.array([m.f_hz for m in modes])
        near = np.argmin(np.abs(np.log(np.maximum(f[show], 1e-9)[:, None] / fm)), axis=1)
        zeta_for_curves = np.array([m.zeta for m in modes])[near]
        if rec is not None:
            h = candidate_taps(rec, Ts)
            R = _R(h, Ts, 2 * math.pi * f[show], zeta_for_curves)
            ax.semilogy(f[show], np.maximum(P[show] * R ** 2, 1e-300), color="tab:gray", lw=1.2,
                        ls="--", label=f"after {rec.name} ({rec.vibration:.2g} % remains)")
        for i, m in enumerate(res.modes):
            ax.axvline(m.f_hz, color="tab:red", lw=0.8, ls=":")
            ax.annotate(f"mode {i + 1}", (m.f_hz, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(3, -12), textcoords="offset points", color="tab:red", fontsize=8)
        ax.plot([], [], color="tab:red", lw=0.8, ls=":", label="modes: " + "; ".join(
            f"{m.f_hz:.3g} Hz = {m.wn:.4g} rad/s, zeta {m.zeta:.2g}" for m in res.modes))
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(f"{label} [unit^2/Hz]")
        ax.set_title(f"axis {res.name}: measured spectrum and candidate filters")
        ax.grid(True, which="both", alpha=0.3)
        ax2 = ax.twinx()
        for c, col in zip(_top(res, 4), COLORS):
            h = candidate_taps(c, Ts)
            R = _R(h, Ts, 2 * math.pi * f[show], zeta_for_curves)
            design = (f"{c.firmware[1]:.3g} Hz" if c.firmware is not None else
                      " + ".join(f"{s.wn / (2 * math.pi):.3g} Hz = {s.wn:.4g} rad/s" if s.wn
                                 else f"T = {s.T:.3g} s" if s.T
                                 else f"{c.design[0][0]:.3g} Hz" for s in c.stages))
            ax2.plot(f[show], 100 * R, color=col, lw=1.0,
                     label=f"{c.name} @ {design}: {c.vibration:.2g} %, {1e3 * c.length:.3g} ms")
        ax2.set_ylabel("residual vibration [%] (zeta of the nearest mode; log above 1 %)")
        percent_axis(ax2, top=110.0)
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=7.5, loc="upper center", ncol=2,
                  bbox_to_anchor=(0.5, -0.14), frameon=False)
    fig.tight_layout()
    p = os.path.join(out_dir, "calibrate_psd.png")
    fig.savefig(p, dpi=110, bbox_inches="tight")   # the legends sit outside the axes
    plt.close(fig)
    paths.append(p)

    fig, axes = plt.subplots(n, 1, figsize=(11, 3.8 * n), squeeze=False)
    for ax, res in zip(axes[:, 0], cal.axes):
        m = _modes(res)[0]
        half = max(4 * m.wn_std, 0.08 * m.wn)
        wn = np.linspace(m.wn - half, m.wn + half, 301)
        for c, col in zip(_top(res, 5), COLORS):
            h = candidate_taps(c, Ts)
            ax.plot(wn / (2 * math.pi), 100 * _R(h, Ts, wn, m.zeta), color=col,
                    label=f"{c.name} ({1e3 * c.length:.3g} ms)")
        ax.axvspan((m.wn - BOX * m.wn_std) / (2 * math.pi), (m.wn + BOX * m.wn_std) / (2 * math.pi),
                   color="tab:red", alpha=0.15,
                   label=f"mode 1 +- 3 sd: {m.f_hz:.4g} Hz = {m.wn:.4g} +- {BOX * m.wn_std:.2g} "
                         "rad/s")
        ax.axvline(m.f_hz, color="tab:red", lw=0.8, ls=":")
        ax.set_xlabel("natural frequency of mode 1 [Hz]")
        ax.set_ylabel("remaining vibration [%]")
        ax.set_title(f"axis {res.name}: remaining vibration over the uncertainty band of mode 1 "
                     f"(zeta = {m.zeta:.2g}; log scale above 1 %)", fontsize=10)
        ax.grid(True, alpha=0.3)
        top = max(10.0, 1.2 * max((float(np.max(line.get_ydata())) for line in ax.lines
                                   if len(line.get_ydata()) > 2), default=10.0))
        percent_axis(ax, top=top)
        ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.tight_layout()
    p = os.path.join(out_dir, "calibrate_band.png")
    fig.savefig(p, dpi=110, bbox_inches="tight")   # the legends sit outside the axes
    plt.close(fig)
    paths.append(p)
    return paths
