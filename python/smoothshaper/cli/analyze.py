# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper analyze``: PRV curve, spectrum and step response of a chain as PNG plots."""
from __future__ import annotations

import math
import os

import numpy as np

from .. import stages as _stages
from ..stages import Stage
from .chain import add_chain_options, chain_from_args, stage_rows
from .common import EXIT_UNAVAILABLE, CliError, decimate, format_table, pyplot as _pyplot
from .cost import add_options as add_cost_options

__all__ = ["SPECTRUM_POINTS", "BAND_POINTS", "MAX_SWEEP_POINTS", "cmd_analyze", "add_parser"]


def _analysis():
    try:
        from .. import analysis
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
    from .._plotting import percent_axis, prv_map
    from .cost import LIMIT_SECONDS, PLOT_POINTS, analyze_cost, chain_taps, start
    stages = chain_from_args(args)
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

    from ..filters import Chain
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


def add_parser(sub) -> None:
    """The ``analyze`` subcommand."""
    p = sub.add_parser("analyze", help="PRV curve, spectrum and step response as PNG plots",
                       description="Analyse a chain (--stage/--kind) against a vibration mode "
                       "(--wn, --zeta): writes prv.png (percent residual vibration over the "
                       "actual-to-nominal frequency ratio, with the insensitivity band at "
                       "--tolerance), spectrum.png (magnitude of the discrete chain in dB over "
                       "frequency) "
                       "and step.png (step response), and prints the insensitivity band. "
                       "--surface adds prv_surface.png over frequency ratio and damping. "
                       "Residual vibration and PRV are defined in docs/analysis.md.")
    add_chain_options(p)
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
