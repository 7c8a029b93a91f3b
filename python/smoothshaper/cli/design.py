# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper design``: the stages for a mode or for kinematic limits (the forms
``design generator`` and ``design bspline`` are in :mod:`smoothshaper.cli.trajectory`)."""
from __future__ import annotations

import argparse

from .chain import add_chain_options, chain_from_args, duration, stage_rows
from .common import EXIT_UNAVAILABLE, CliError, Parser, format_table
from .trajectory import add_design_forms

__all__ = ["cmd_design", "add_parser", "write_c_coeffs"]


def cmd_design(args) -> int:
    kinematic = [args.h, args.vmax, args.amax, args.jmax]
    if any(v is not None for v in kinematic):
        if args.h is None or args.vmax is None:
            raise CliError("kinematic design needs at least --h and --vmax")
        if args.jmax is not None and args.amax is None:
            raise CliError("--jmax needs --amax (the bounds are consecutive derivatives: "
                           "--vmax, --amax, --jmax)")
        try:
            from ..design import kinematic as design_kinematic
        except ImportError as exc:
            raise CliError(f"kinematic design is unavailable in this installation ({exc})",
                           EXIT_UNAVAILABLE) from None
        stages = list(design_kinematic(h=args.h, vmax=args.vmax, amax=args.amax,
                                       jmax=args.jmax, profile=args.profile,
                                       wn=args.wn, zeta=args.zeta, Ts=args.Ts))
        stages += chain_from_args(argparse.Namespace(stage=args.stage, kind=None))
    else:
        stages = chain_from_args(args)
    if not stages:
        raise CliError("nothing to design: give --kind with --wn, --stage, or --h/--vmax limits")
    # the coefficients first: a file that cannot be written fails before anything is printed
    wrote = (write_c_coeffs(args.c_coeffs, stages, args.Ts, args.c_name,
                            getattr(args, "argv", [])) if args.c_coeffs else None)
    header, rows = stage_rows(stages, args.Ts)
    print(format_table(header, rows))
    total = sum(d for d in (duration(s) for s in stages) if d is not None)
    print(f"total duration (delay of the chain): {total:.6g} s")
    if args.Ts is not None:
        from ..filters import Chain
        chain = Chain(stages, Ts=args.Ts)
        print(f"chain FIR length at Ts={args.Ts:g} s: {chain.length} samples"
              + ("" if chain.is_fir else " (plus IIR notch)"))
    if wrote is not None:
        print(wrote)
    return 0


def write_c_coeffs(path: str, stages, Ts, name: str, argv: list[str]) -> str:
    """Write the chain's precomputed coefficients as C source (smoothshaper.coeffs), headed by
    the command line (``argv``, without the program) that wrote them; the line to report."""
    import shlex

    from ..coeffs import c_source
    if Ts is None:
        raise CliError("--c-coeffs needs --Ts: the coefficients are for one sample period")
    text = c_source(stages, Ts=Ts, name=name)
    line = " ".join(shlex.quote(a) for a in argv) or "design"
    try:
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(f"/* Written by: smoothshaper {line} */\n" + text)
    except OSError as exc:
        raise CliError(f"--c-coeffs={path}: {exc.strerror or exc}") from None
    return f"wrote {path} (precomputed coefficients {name}[], coeffs.h)"


def add_parser(sub) -> None:
    """The ``design`` subcommand and its forms."""
    p = sub.add_parser("design", help="print the stages for a mode or kinematic limits; "
                       "'design generator' / 'design bspline' run via-points (see their --help)",
                       description="Without FORM: the stages for a mode (--kind/--stage with "
                       "--wn) or for kinematic limits (--h, --vmax, ...). With FORM (optional): "
                       "'generator' runs via-points through the online generator, 'bspline' "
                       "interpolates them; see 'smoothshaper design FORM --help'.")
    add_chain_options(p)
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
    f = p.add_argument_group(
        "firmware", "The chain as precomputed coefficients: C source that a target builds its "
        "stages from with sms_chain_init_coeffs, no design on the target, no double arithmetic, "
        "no libm (docs/firmware.md).")
    f.add_argument("--c-coeffs", metavar="FILE", help="write the coefficients (needs --Ts)")
    f.add_argument("--c-name", default="smoothshaper_chain", metavar="NAME",
                   help="C name of the coefficient array (default smoothshaper_chain)")
    p.set_defaults(func=cmd_design)
    add_design_forms(p, Parser)
