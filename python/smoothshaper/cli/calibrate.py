# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper calibrate``: from measured records to a recommended filter.

    smoothshaper calibrate FILE... [--kind auto|raw|decay|psd|frf] [--axis auto|xyz|all|x|y|z|DIR]
        [--band FMIN FMAX] [--firmware none|klipper|marlin|rrf|prusa] [--ranking auto|spectrum|modal]
        [--max-delay S] [--max-smoothing D] [--accel A] [--corner-velocity V] [--spread FRAC]
        [--Ts S] [--combine | --separate] [--out DIR] [--json FILE] [--schedule V1,V2,...]

Prints the identified modes and the ranked candidates per axis; ``--out`` writes the two
figures, ``config_<axis>.c``, ``coeffs_<axis>.c`` (precomputed coefficients for
``sms_chain_init_coeffs``), ``fmu_start_values_<axis>.json`` (for
``fmpy.simulate_fmu(start_values=...)``) and, with ``--firmware``, the firmware's configuration
for every analysed axis (``firmware_<name>.txt``); ``--json`` writes everything
(docs/calibrate.md). ``--schedule`` (one value per record) prints the schedule table of a
scheduled shaper instead (docs/scheduled.md).
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
    p.add_argument("--axis", default="auto",
                   help="auto (default: the summed x+y+z analysis, named by the test's axis "
                   "when the file name tells it), xyz (the same), all (each column on its own), "
                   "x, y, z (one column), or a direction such as 1,-1 or 1,1,0 (the projection "
                   "of a raw record's acceleration onto it)")
    p.add_argument("--band", nargs=2, type=float, metavar=("FMIN", "FMAX"),
                   help="frequency band to analyse [Hz], replacing the automatic one (the part "
                   "of the spectrum the test excited)")
    p.add_argument("--firmware", choices=("none", "klipper", "marlin", "rrf", "prusa"),
                   default="none", help="rank only the shapers this firmware runs, with its own "
                   "definitions, and write its configuration (default none: every filter family "
                   "and chain of the library, for the C library and the FMUs)")
    p.add_argument("--ranking", choices=("auto", "spectrum", "modal"), default="auto",
                   help="the figure that ranks: auto (default: the modal fit where it explains "
                   "the spectrum, else the measured spectrum), spectrum or modal")
    group = p.add_mutually_exclusive_group()
    group.add_argument("--combine", dest="combine", action="store_const", const=True,
                       default=None,
                       help="analyse all FILEs as one axis, one data set each (several test "
                       "points), every filter scored by the worst, as Klipper's "
                       "calibrate_shaper.py FILE1 FILE2 ... does (default when every file is "
                       "a resonance test named for the same axis, resonances_x_*.csv)")
    group.add_argument("--separate", dest="combine", action="store_const", const=False,
                       help="analyse each FILE on its own")
    p.add_argument("--max-delay", type=float, metavar="S",
                   help="longest filter impulse response allowed [s] (default, when neither "
                   "this nor --max-smoothing is given: per axis, the length of the shaper "
                   "Klipper's calibrate_shaper.py trade-off of remaining vibration against "
                   "smoothing picks on the record's spectrum, docs/calibrate.md; every "
                   "candidate then competes within it, so the "
                   "pick is never longer than that shaper and leaves no more by the ranking "
                   "figure; without a limit the least vibration is always a longer filter)")
    p.add_argument("--max-smoothing", type=float, metavar="D",
                   help="largest corner rounding allowed (length unit of --accel; default: no "
                   "limit; giving it replaces the default delay limit)")
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
    p.add_argument("--schedule", metavar="V1,V2,...",
                   help="one scheduling value per FILE (its position, load, ...): print the "
                   "table (value, wn, zeta) of the dominant mode of --axis (default x) for a "
                   "scheduled shaper instead of recommending a filter; with --out, write it "
                   "as schedule.csv (docs/scheduled.md)")
    add_cost_options(p)
    p.set_defaults(func=cmd_calibrate, figures_option="--out")


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


def _schedule_values(args) -> list:
    try:
        values = [float(v) for v in args.schedule.split(",")]
    except ValueError:
        raise CliError(f"--schedule must be numbers separated by commas, got "
                       f"{args.schedule!r}") from None
    if len(values) != len(args.files):
        raise CliError(f"--schedule gives {len(values)} value(s) for {len(args.files)} FILE(s): "
                       "one per record")
    return values


def cmd_schedule(args) -> int:
    """--schedule: the table of the dominant mode per record."""
    from ..calibrate import schedule
    values = _schedule_values(args)
    axis = "x" if args.axis == "all" else args.axis
    table = schedule.schedule_table(args.files, values, axis=axis, kind=args.kind,
                                    band=tuple(args.band) if args.band else None)
    print(schedule.format_table(table), end="")
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        path = os.path.join(args.out, "schedule.csv")
        with open(path, "w", encoding="utf-8") as f:
            f.write("value,wn,zeta\n")
            for value, wn, zeta in table:
                f.write(f"{float(value)!r},{float(wn)!r},{float(zeta)!r}\n")
        print(f"wrote {path}")
    return 0


def _looks_like_decay(path) -> bool:
    """For the time estimate only, from the head of the file: two columns, neither named as an
    acceleration nor a frequency (the reader decides from the whole record)."""
    from ..calibrate.tables import _head
    try:
        header, _, _, values = _head(path)
    except (OSError, ValueError):
        return False
    if values is None or len(values) != 2:
        return False
    names = " ".join(header).lower() if header else ""
    return not any(w in names for w in ("accel", "freq", "psd", "hz"))


def cmd_calibrate(args) -> int:
    from .. import calibrate
    from ..calibrate import outputs
    from .cost import record_cost, start as start_request
    _check_options(args)
    if args.schedule is not None:
        return cmd_schedule(args)
    nbytes = sum(os.path.getsize(f) for f in args.files if os.path.isfile(f))
    # analyses to tune: one per file, up to three with --axis all
    axes = len(args.files) * (3 if args.axis == "all" else 1)
    decay = args.kind == "decay" or (args.kind == "auto" and any(_looks_like_decay(f)
                                                                  for f in args.files))
    bar = start_request(record_cost("calibrate", nbytes=nbytes, axes=axes, decay=decay), args,
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
                            spread=args.spread, firmware=args.firmware, ranking=args.ranking,
                            combine=args.combine, progress=progress)
    except (MemoryError, ValueError) as exc:
        if isinstance(exc, ValueError) and "Maximum allowed size" not in str(exc):
            raise            # numpy's refusal of an array too large to index
        raise CliError(f"--Ts={args.Ts:.3g}: the filters' impulse responses at this sample "
                       "period do not fit in memory; use a larger --Ts") from None
    bar.finish()
    elapsed = time.process_time() - start
    print(outputs.report_text(cal), end="")
    fw_text = outputs.firmware_config(cal)
    if fw_text is not None:
        print(f"{args.firmware} configuration:")
        print(fw_text, end="")
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
        for res in cal.axes:
            c = res.recommended
            if c is None or not c.stages:
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
        if fw_text is not None:
            path = os.path.join(args.out, f"firmware_{args.firmware}.txt")
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(fw_text)
            written.append(path)
        print("wrote " + ", ".join(written))
    if any(res.recommended is None for res in cal.axes):
        return 1
    return 0
