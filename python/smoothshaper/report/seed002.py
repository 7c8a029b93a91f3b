# SPDX-License-Identifier: Apache-2.0
"""Seed 002 (Béarée, Control Eng. Practice 2014): the Damped-Jerk profile.

The seed text stops after its Sec. 2; its claims, and the reading of Sec. 3 in docs/filters.md:

=====================================================  ==========================================
seed                                                   check
=====================================================  ==========================================
eq. 1-6: a jerk-limited profile is an acceleration-    PRV of the jerk stage M(T_J) on the
limited one through M(T_J); T_J = k 2 pi/w1 cancels    undamped mode is 0 for k = 1, 2, 3
an undamped mode
"these elegant properties vanish when the damping      PRV of M(T_J = Td) on the damped mode:
is not negligible"                                     closed form 100 (e^{zeta wn Td} - 1)/(wn Td)
Damped-Jerk (docs/filters.md reading): jerk stage             PRV 0, continuous and in an exact ZOH
exponential, sigma = -zeta wn, T_J = Td                simulation of the load (plants.mode)
(consequence) the jerk decays inside each jerk phase   peak jerk ratio |sigma| Td/(1 - e^{sigma Td})
=====================================================  ==========================================

The example motion and mode are ours (the seed's simulation section is not in the text):
h = 0.5 rad, v = 1 rad/s, a = 4 rad/s^2, mode 5 Hz with zeta = 0.1.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import analysis, plants
from .. import reference as ref
from .. import stages as st
from .claims import Claim, Section
from .figures import COLORS, figure

__all__ = ["COMMAND", "build"]

COMMAND = "python -m smoothshaper.report --out report --only seed002"
H, VMAX, AMAX = 0.5, 1.0, 4.0
WN, ZETA = 2 * math.pi * 5.0, 0.1
TS = 1e-4


def profiles():
    """Jerk-limited (rectangular jerk stage, T_J = Td) and Damped-Jerk (exponential jerk stage,
    sigma = -zeta wn, T_J = Td) after the same acceleration-limited chain h/v, v/a."""
    wd = WN * math.sqrt(1 - ZETA ** 2)
    Td = 2 * math.pi / wd
    base = [st.rectangular(T=H / VMAX), st.rectangular(T=VMAX / AMAX)]
    return {"jerk-limited": base + [st.rectangular(T=Td)],
            "Damped-Jerk": base + [st.exponential(T=Td, sigma=-ZETA * WN)]}, Td


def build(fig_dir=None) -> Section:
    sec = Section(
        key="seed002", title="Seed 002: jerk-limited vs Damped-Jerk profile (Béarée 2014)",
        claim=("The jerk time T_J = k 2 pi/w1 of a jerk-limited profile cancels an undamped "
               "mode; with damping it does not. Replacing the rectangular jerk stage by an "
               "exponential one (sigma = -zeta wn, T_J = Td) restores exact cancellation for an "
               "underdamped mode."),
        command=COMMAND)
    for k in (1, 2, 3):
        jerk = st.rectangular(T=k * 2 * math.pi / WN)
        sec.add(Claim(f"eq6.k{k}", f"eq. 6: PRV of M(T_J = {k} * 2 pi/w1) on the undamped mode",
                      float(analysis.prv([jerk], wn=WN)), 0.0, 1e-10, "exact zero", unit="%"))
    prof, Td = profiles()
    jl, dj = prof["jerk-limited"][-1], prof["Damped-Jerk"][-1]
    closed = 100 * math.expm1(ZETA * WN * Td) / (WN * Td)
    sec.add(Claim("damped.JL", "PRV of the rectangular jerk stage (T_J = Td) on the damped mode",
                  float(analysis.prv([jl], wn=WN, zeta=ZETA)), closed, 1e-9,
                  "closed form 100 (e^{zeta wn Td} - 1)/(wn Td)", unit="%"),
            Claim("damped.DJ", "PRV of the exponential jerk stage (Damped-Jerk)",
                  float(analysis.prv([dj], wn=WN, zeta=ZETA)), 0.0, 1e-10, "exact zero", unit="%"))
    base = prof["jerk-limited"][:2]
    p = complex(-ZETA * WN, WN * math.sqrt(1 - ZETA ** 2))
    closed_base = 100 * math.prod(abs(-np.expm1(-p * s.T)) / abs(p * s.T) for s in base)
    sec.add(Claim("base.acc_limited", "acceleration-limited part alone (M(h/v) M(v/a)): PRV on the "
                  "mode", float(analysis.prv(base, wn=WN, zeta=ZETA)), closed_base, 1e-9,
                  "closed form 100 prod |1 - e^{-pT}|/|pT|", unit="%"))
    sim = {}
    for name, chain in prof.items():
        sim[name] = _simulate(chain)
        sec.add(Claim(f"sim.{name}", f"{name}: residual of the load (exact ZOH simulation) over "
                      "the unfiltered step's", sim[name][0],
                      float(analysis.prv(chain, wn=WN, zeta=ZETA, Ts=TS)), 1e-6,
                      "discrete |H(e^{p Ts})|", unit="%"))
    sec.add(Claim("sim.DJ_zero", "Damped-Jerk: simulated residual", sim["Damped-Jerk"][0], 0.0,
                  1e-8, "exact zero on the sampled mode", unit="%"))
    sigma = -ZETA * WN
    ratio_closed = -sigma * Td / -math.expm1(sigma * Td)
    t = np.linspace(0, Td, 100001)
    ratio = (ref.continuous_impulse_response(dj, t).max()
             / ref.continuous_impulse_response(jl, t[:-1]).max())
    sec.add(Claim("jerk_ratio", "peak jerk, Damped-Jerk over jerk-limited (same T_J, a_max)",
                  ratio, ratio_closed, 1e-9, "closed form |sigma| Td/(1 - e^{sigma Td})"))
    sec.body = (f"Mode wn = {WN:.4f} rad/s (5 Hz), zeta = {ZETA}, Td = {Td:.5f} s; motion "
                f"h = {H} rad, v = {VMAX} rad/s, a = {AMAX} rad/s^2, so T = ({H / VMAX:g}, "
                f"{VMAX / AMAX:g}, {Td:.5f}) s. The jerk-limited profile leaves "
                f"{sim['jerk-limited'][0]:.2f} % of the unfiltered step's vibration (its "
                f"acceleration-limited part alone would leave "
                f"{float(analysis.prv(prof['jerk-limited'][:2], wn=WN, zeta=ZETA)):.1f} %); the "
                f"Damped-Jerk profile leaves {sim['Damped-Jerk'][0]:.1e} %, at the price of a "
                f"{100 * (ratio - 1):.0f} % higher peak jerk for the same T_J and a_max. "
                "Simulation: exact zero-order hold of the load position "
                "(2 zeta wn s + wn^2)/(s^2 + 2 zeta wn s + wn^2), Ts = 0.1 ms, exact timing.")
    if fig_dir is not None:
        _figures(sec, Path(fig_dir), prof, sim, Td)
    return sec


def _simulate(chain):
    plant = plants.mode(wn=WN, zeta=ZETA)
    n = int((sum(s.T for s in chain) + 1.0) / TS)
    u = np.full(n, H)
    q = ref.filter(chain, u, Ts=TS)
    t, y = plants.simulate_zoh(plant, q, Ts=TS)
    _, y0 = plants.simulate_zoh(plant, u, Ts=TS)
    L = sum(ref.impulse_response(s, Ts=TS).size for s in chain)
    a = plants.residual_amplitude(t, y, wn=WN, zeta=ZETA, t_start=(L + 2) * TS)
    a0 = plants.residual_amplitude(t, y0, wn=WN, zeta=ZETA, t_start=(L + 2) * TS)
    return 100 * a / a0, t, q, y


def _figures(sec, fig_dir, prof, sim, Td):
    with figure(fig_dir / "profiles.png", "Seed 002: jerk-limited and Damped-Jerk profiles "
                "(h = 0.5 rad, v = 1 rad/s, a = 4 rad/s^2, T_J = Td; acceleration and jerk by "
                "finite differences of the paper-timing chain) and the load's deviation from the "
                "command on a 5 Hz, zeta = 0.1 mode (exact ZOH simulation)", sec.figures,
                nrows=2, ncols=2, size=(11, 6)) as (f, ax):
        for name, color in (("jerk-limited", COLORS["rectangular"]),
                            ("Damped-Jerk", COLORS["exponential"])):
            _, t, q, y = sim[name]
            # derivatives of the paper-timing chain: exact timing's end-tap correction
            # (T_J/Ts = 2010.08) puts one-sample spikes into finite differences
            qp = ref.filter([s.with_(timing="paper") for s in prof[name]], np.full(t.size, H),
                            Ts=TS)
            v = np.diff(qp, prepend=0.0) / TS
            a = np.diff(v, prepend=0.0) / TS
            j = np.diff(a, prepend=0.0) / TS
            ax[0].plot(t, a, color=color, label=name)
            ax[1].plot(t, j, color=color, label=name)
            ax[2].plot(t, y - q, color=color, label=name)
            ax[3].plot(t, y - H, color=color, label=name)
        for a_, lab in zip(ax, ("acceleration [rad/s^2]", "jerk [rad/s^3]",
                                "load - command [rad]", "load - target [rad]")):
            a_.set_xlabel("time [s]")
            a_.set_ylabel(lab)
        ax[3].set_xlim(0.9, 2.0)
        ax[3].set_ylim(-0.001, 0.001)
    r = np.linspace(0.5, 2.0, 1501)
    with figure(fig_dir / "sensitivity.png", "Seed 002: PRV of the jerk stage alone against "
                "the true natural frequency (design 5 Hz, zeta = 0.1)", sec.figures) as (f, ax):
        for name, color in (("jerk-limited", COLORS["rectangular"]),
                            ("Damped-Jerk", COLORS["exponential"])):
            ax.plot(r, analysis.prv(prof[name][-1:], wn=r * WN, zeta=ZETA), color=color,
                    label=f"{name} jerk stage")
        ax.set_xlabel("true wn / design wn [-]")
        ax.set_ylabel("percent residual vibration [%]")
