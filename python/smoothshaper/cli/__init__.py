# SPDX-License-Identifier: Apache-2.0
"""The smoothshaper command line: design, analyze, identify, calibrate, validate, report.

A stage is written KIND:key=value,key=value (--stage, repeatable; stages chain in the given
order). KIND is one of rectangular, harmonic, damped_harmonic, exponential, zv, zvd, zvdd, zvn,
ei, ei2, ei3, mzv, gmzv, si, impulses, the input smoothers smooth_zv, smooth_mzv, smooth_ei,
smooth_ei2 (or smooth_2hump_ei), smooth_zvd_ei, smooth_si, notch_tustin, notch_matched
('notch' means notch_matched). Keys: T [s], sigma [1/s], k, wn [rad/s], f [Hz] (instead of
wn), zeta, order, tolerance, duration (gmzv, si: in damped periods), insensitivity (si: the
band to keep the residual under tolerance; order and duration are then designed),
notch_pole_zeta, timing (exact, paper, or bounded for rectangular and exponential), and for
impulses amplitudes=[...] and times=[...] (seconds; a firmware's shaper_a/shaper_t lists as
they are). A smoother given wn (and optionally zeta, k) instead of T is designed for that
mode. Examples: harmonic:T=0.05, zv:wn=100,zeta=0.05, damped_harmonic:wn=125,zeta=0.12,
si:f=40,zeta=0.1,insensitivity=0.6, smooth_mzv:f=45,zeta=0.1,
impulses:amplitudes=[0.2,0.5,0.3],times=[0,0.006,0.012].

Trajectory forms: 'design generator' runs via-points through the online generator, 'design
bspline' interpolates them with a B-spline (see 'smoothshaper design generator --help' and
'smoothshaper design bspline --help').

Exit codes: 0 success, 1 invalid input or failed run (one line on stderr), 2 bad usage,
3 the subcommand's module is not available in this installation.
"""
from __future__ import annotations

import argparse
import os
import sys

from . import analyze, calibrate, campaigns, design, identify
from .analyze import cmd_analyze
from .campaigns import cmd_report, cmd_validate
from .chain import parse_stage, stage_rows
from .common import (EXIT_ERROR, EXIT_UNAVAILABLE, EXIT_USAGE, CliError,  # noqa: F401
                     Parser as _Parser)
from .design import cmd_design
from .identify import cmd_identify, first_two_peaks, read_record
from .messages import option_for as _option_for, os_error as _os_error, readable as _readable
from .. import _optional
from ..errors import ParameterError

__all__ = ["parse_stage", "stage_rows", "cmd_design", "cmd_analyze",
           "read_record", "first_two_peaks", "cmd_identify", "cmd_validate", "cmd_report",
           "build_parser", "main"]



def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="smoothshaper", description=__doc__,
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    from .. import __version__
    parser.add_argument("--version", action="version", version=f"smoothshaper {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    for module in (design, analyze, identify, calibrate):   # the order of the help
        module.add_parser(sub)
    campaigns.add_parsers(sub)
    return parser


#: Longest error line (longer ones keep their start and end around " [...] ").
MAX_MESSAGE = 600


def _require_figures(args) -> None:
    """Exit 3 (CliError) before any work when the option that asks a subcommand for figures
    is given and matplotlib is not installed. A subcommand names that option in its parser's
    defaults (``figures_option``: design generator / bspline ``--plot``, calibrate ``--out``,
    whose folder would otherwise be half written); analyze, report and validate check their
    own needs as they start."""
    option = getattr(args, "figures_option", None)
    if option is not None and getattr(args, option.lstrip("-").replace("-", "_"), None):
        from .common import pyplot
        pyplot(f"{args.command} {option}")


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the exit code (errors: one line on stderr, no traceback). A
    library ParameterError is prefixed with the option the user gave for it (``--jmax=...``)
    and every number in an error is printed readably (at most 7 significant digits)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = build_parser().parse_args(argv)
        args.argv = argv        # the command line, for files that say how they were written
        _require_figures(args)
        return args.func(args)
    except BrokenPipeError:
        # The reader went away (e.g. `| head`): not an error worth a message.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_ERROR
    except CliError as exc:
        code, message = exc.code, str(exc)
    except ModuleNotFoundError as exc:
        explained = _optional.explain(exc, "this command")
        if explained is None:
            raise
        code, message = EXIT_UNAVAILABLE, str(explained)
    except ParameterError as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, str(exc)
        option = _option_for(exc.parameter, message, argv)
        if option is not None and not message.startswith(option):
            message = f"{option}: {message}"
    except OSError as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, _os_error(exc, argv)
    except (ValueError, RuntimeError, ImportError) as exc:
        if os.environ.get("SMOOTHSHAPER_DEBUG"):
            raise
        code, message = EXIT_ERROR, str(exc)
    except KeyboardInterrupt:
        code, message = 130, "interrupted"
    message = _readable(" ".join(message.split()))
    if len(message) > MAX_MESSAGE:     # an echoed argument of 100 kB (--stage xxx...)
        message = message[:MAX_MESSAGE - 100] + " [...] " + message[-93:]
    if not message.startswith("smoothshaper"):
        message = f"smoothshaper: error: {message}"
    sys.stderr.write(message + "\n")
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
