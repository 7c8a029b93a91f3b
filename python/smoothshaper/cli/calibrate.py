# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper calibrate``: from measured records to a recommended filter.

    smoothshaper calibrate FILE... [--kind auto|raw|decay|psd|frf] [--axis x|y|z|all]
        [--band FMIN FMAX] [--max-delay S] [--max-smoothing D] [--accel A]
        [--corner-velocity V] [--spread FRAC] [--Ts S] [--out DIR] [--json FILE]

Prints the identified modes and the ranked candidates per axis; ``--out`` writes the two
figures, ``config_<axis>.c``, ``fmu_start_values_<axis>.json`` (for
``fmpy.simulate_fmu(start_values=...)``) and ``input_shaper.cfg`` when firmware knows the
shaper; ``--json`` writes everything (docs/calibrate.md).
"""
from __future__ import annotations

import json
import math
import os
import time

from .common import CliError
from .cost import add_options as add_cost_options

__all__ = ["add_parser", "cmd_calibrate"]


def add_parser(sub) -> None:
    p = sub.add_parser(
        "calibrate", help="identify the modes in measured records and recommend a filter",
        description="Identify every significant mode (wn, zeta, uncertainty) in measured "
        "records (accelerometer resonance tests, free decays, PSD tables, frequency responses), "
        "tune every filter family to them and recommend the one that leaves the least "
        "vibration within the delay and smoothing limits.")
    p.add_argument("files", nargs="+", metavar="FILE", help="CSV record(s)")
    p.add_argument("--kind", choices=("auto", "raw", "decay", "psd", "frf"), default="auto",
                   help="record kind (default auto: from the header and the signal)")
    p.add_argument("--axis", default="all", help="x, y, z (a column name) or all (default)")
    p.add_argument("--band", nargs=2, type=float, metavar=("FMIN", "FMAX"),
                   help="frequency band to search [Hz] (default: the part of the spectrum a "
                   "resonance test excited, the table's range for a frequency response)")
    p.add_argument("--max-delay", type=float, metavar="S",
                   help="longest filter impulse response allowed [s] (default: no limit)")
    p.add_argument("--max-smoothing", type=float, metavar="D",
                   help="largest corner rounding allowed (length unit of --accel; default: no "
                   "limit)")
    p.add_argument("--accel", type=float, default=3000.0, metavar="A",
                   help="acceleration of the reference move (default 3000, e.g. mm/s^2)")
    p.add_argument("--corner-velocity", type=float, default=5.0, metavar="V",
                   help="square-corner velocity of the reference corner (default 5, e.g. mm/s)")
    p.add_argument("--distance", type=float, default=10.0, metavar="D",
                   help="length of the reference rest-to-rest move (default 10, e.g. mm)")
    p.add_argument("--spread", type=float, default=0.0, metavar="FRAC",
                   help="expected variation of the mode frequencies over the workspace as a "
                   "fraction (e.g. 0.05), added to the fit's uncertainty (default 0)")
    p.add_argument("--Ts", type=float, default=1e-4, metavar="S",
                   help="sample period the filter will run at [s] (default 1e-4)")
    p.add_argument("--out", metavar="DIR", help="write figures and config files here")
    p.add_argument("--json", metavar="FILE", help="write all results as JSON")
    add_cost_options(p)
    p.set_defaults(func=cmd_calibrate)


#: The reference rest-to-rest move is sampled at Ts: at most this many samples.
MAX_REFERENCE_SAMPLES = 1 << 24


def _check_options(args) -> None:
    """Every number of the reference move and the limits, in O(1); CliError naming the
    option (numbers as %.3g)."""
    positive = [("--Ts", args.Ts), ("--accel", args.accel),
                ("--corner-velocity", args.corner_velocity), ("--distance", args.distance),
                ("--max-delay", args.max_delay), ("--max-smoothing", args.max_smoothing)]
    for option, value in positive:
        if value is not None and not (math.isfinite(value) and value > 0):
            raise CliError(f"{option} must be finite and > 0, got {value:.3g}")
    if not (math.isfinite(args.spread) and 0 <= args.spread < 1):
        raise CliError(f"--spread must be a fraction in [0, 1), got {args.spread:.3g}")
    if args.band is not None:
        fmin, fmax = args.band
        if not (math.isfinite(fmin) and math.isfinite(fmax) and 0 < fmin < fmax):
            raise CliError(f"--band must be two frequencies 0 < FMIN < FMAX [Hz], got "
                           f"{fmin:.3g} {fmax:.3g}")
        if not fmax < 0.5 / args.Ts:
            raise CliError(f"--band={fmin:.3g},{fmax:.3g}, --Ts={args.Ts:.3g}: FMAX lies at or "
                           f"above the Nyquist frequency 1/(2 Ts) = {0.5 / args.Ts:.3g} Hz")
    # the reference move: 2 sqrt(distance/accel) long, sampled at Ts
    move = 2 * math.sqrt(args.distance / args.accel)
    if not move / args.Ts <= MAX_REFERENCE_SAMPLES:
        option = (f"--Ts={args.Ts:.3g}" if move / 1e-4 <= MAX_REFERENCE_SAMPLES else
                  f"--distance={args.distance:.3g}, --accel={args.accel:.3g}")
        raise CliError(f"{option}: the reference move lasts {move:.3g} s = {move / args.Ts:.3g} "
                       f"samples of Ts, more than {MAX_REFERENCE_SAMPLES:.3g}; shorten "
                       "--distance, raise --accel or use a larger --Ts")


def cmd_calibrate(args) -> int:
    from .. import calibrate
    from ..calibrate import outputs
    from .cost import record_cost, start as start_request
    _check_options(args)
    nbytes = sum(os.path.getsize(f) for f in args.files if os.path.isfile(f))
    # columns to tune: one with --axis x/y/z, up to three per file with --axis all
    axes = len(args.files) * (3 if args.axis == "all" else 1)
    bar = start_request(record_cost("calibrate", nbytes=nbytes, axes=axes), args,
                        f"{len(args.files)} file(s), {nbytes} bytes")
    if bar is None:
        return 0
    bar.phase("read and fit")

    def progress(done, total):
        if bar.label != "tune":
            bar.phase("tune", total)
        bar.advance(done - bar.done)

    ref = calibrate.Reference(Ts=args.Ts, accel=args.accel,
                              corner_velocity=args.corner_velocity, distance=args.distance)
    start = time.process_time()
    try:
        cal = calibrate.run(args.files, kind=args.kind, axis=args.axis,
                            band=tuple(args.band) if args.band else None, reference=ref,
                            max_delay=args.max_delay, max_smoothing=args.max_smoothing,
                            spread=args.spread, progress=progress)
    except (MemoryError, ValueError) as exc:
        if isinstance(exc, ValueError) and "Maximum allowed size" not in str(exc):
            raise            # numpy's refusal of an array too large to index
        raise CliError(f"--Ts={args.Ts:.3g}: the filters' impulse responses at this sample "
                       "period do not fit in memory; use a larger --Ts") from None
    bar.finish()
    elapsed = time.process_time() - start
    print(outputs.report_text(cal), end="")
    print(f"analysis: {elapsed:.2f} s of CPU time")
    if args.json:
        try:
            outputs.write_json(cal, args.json)
        except OSError as exc:     # a failed write (a full disk) carries no file name
            raise CliError(f"--json={args.json}: {exc.strerror or exc}") from None
        print(f"wrote {args.json}")
    if args.out:
        from ..calibrate import plots
        os.makedirs(args.out, exist_ok=True)
        written = plots.write(cal, args.out)
        firmware = []
        for res in cal.axes:
            c = res.recommended
            if c is None:
                continue
            ident = outputs._ident(res.name)
            path = os.path.join(args.out, f"config_{ident}.c")
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(outputs.c_config(c, ref.Ts, ident))
            written.append(path)
            path = os.path.join(args.out, f"coeffs_{ident}.c")   # the firmware path, coeffs.h
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(outputs.c_coeffs(c, ref.Ts, ident))
            written.append(path)
            path = os.path.join(args.out, f"fmu_start_values_{ident}.json")
            with open(path, "w", encoding="utf-8") as fh:
                json.dump(outputs.fmu_start_values(c, ref.Ts), fh, indent=1)
            written.append(path)
            lines = calibrate.candidates.firmware_lines(c, ident)
            if lines:
                firmware += lines
        if firmware:
            path = os.path.join(args.out, "input_shaper.cfg")
            with open(path, "w", encoding="utf-8") as fh:
                fh.write("[input_shaper]\n" + "\n".join(firmware) + "\n")
            written.append(path)
        print("wrote " + ", ".join(written))
    if any(res.recommended is None for res in cal.axes):
        return 1
    return 0
