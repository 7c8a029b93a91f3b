# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper validate`` and ``smoothshaper report``: each runs a campaign module
(:mod:`smoothshaper.fmi.validate`, :mod:`smoothshaper.report`) that writes its results into a
folder, loaded only when the subcommand runs."""
from __future__ import annotations

import os

from .._optional import MissingDependency, explain, require_all
from .common import EXIT_ERROR, EXIT_UNAVAILABLE, CliError
from .cost import add_options as add_cost_options

__all__ = ["cmd_validate", "cmd_report", "add_parsers"]


def _run_module(name: str, module_name: str, out_dir: str, args, cost, sizes: str,
                **options) -> int:
    """Call smoothshaper.<module_name>.run(out_dir) for the subcommand ``name``: a missing
    module is reported (exit 3), not a crash; then the request's estimate (``cost(module)``,
    see :func:`smoothshaper.cli.cost.start`) and a bar whose phases the module names through
    ``run(..., progress=)``."""
    import importlib
    import inspect

    from .cost import start
    modname = f"smoothshaper.{module_name}"
    try:
        module = importlib.import_module(modname)
    except ModuleNotFoundError as exc:
        if exc.name == modname:
            raise CliError(f"{name} is unavailable: module {modname} is not part of this "
                           "installation yet", EXIT_UNAVAILABLE) from None
        explained = explain(exc, f"smoothshaper {name}")
        if explained is None:
            raise
        raise CliError(str(explained), EXIT_UNAVAILABLE) from None
    run = getattr(module, "run", None)
    if run is None:
        raise CliError(f"{name} is unavailable: {modname} has no run(out_dir)", EXIT_UNAVAILABLE)
    try:        # before the estimate: a missing package is named at once
        require_all(getattr(module, "REQUIRES", ()), f"smoothshaper {name}")
    except MissingDependency as exc:
        raise CliError(str(exc), EXIT_UNAVAILABLE) from None
    bar = start(cost(module), args, sizes)
    if bar is None:
        return 0
    if "progress" in inspect.signature(run).parameters:
        options["progress"] = lambda phase: bar.phase(phase)
    try:
        result = run(out_dir, **options)
    finally:
        bar.finish()
    if result is False or (isinstance(result, int) and not isinstance(result, bool) and result):
        return EXIT_ERROR
    print(f"{name}: results written to {out_dir}")
    return 0


def cmd_validate(args) -> int:
    from .cost import validate_cost
    build = args.build_dir or os.path.join(args.out, "build")
    built = os.path.isdir(os.path.join(build, "fmus"))
    options = {"build_dir": args.build_dir} if args.build_dir else {}
    return _run_module("validate", "fmi", args.out, args,
                       lambda module: validate_cost(built=built),
                       "FMUs already built" if built else "the FMUs to build first", **options)


def cmd_report(args) -> int:
    from .cost import report_cost

    def cost(module):
        sections = getattr(module, "SECTIONS", ())
        unknown = [k for k in args.only or () if k not in sections]
        if unknown:
            raise CliError(f"--only: unknown section {unknown[0]!r} (sections: "
                           f"{', '.join(sections)})")
        return report_cost(list(args.only or sections))

    options = {"only": args.only} if args.only else {}
    return _run_module("report", "report", args.out, args, cost,
                       f"{len(args.only)} section(s)" if args.only else "all sections", **options)


def add_parsers(sub) -> None:
    """The ``validate`` and ``report`` subcommands."""
    descriptions = {
        "validate": "Build the FMUs with CMake, check their model descriptions (fmpy, fmutool), "
                    "simulate every stage family and several chains with fmpy at several "
                    "communication step sizes and with libcosim, and compare with the NumPy "
                    "reference (docs/cosimulation.md). Writes README.md (tables of maximum "
                    "errors) and plots into --out; exit code 1 if any comparison fails.",
        "report": "Reproduce the numerical claims of the source papers (docs/references.md) "
                  "and of the shaper literature: every claim is recomputed, compared with its "
                  "closed form or published value within a stated tolerance, and listed with "
                  "figures in --out/README.md; exit code 1 if a claim fails."}
    for name, func, what in (("validate", cmd_validate, "build and validate the FMUs with fmpy"),
                             ("report", cmd_report, "reproduce the source papers' claims "
                              "(docs/references.md)")):
        p = sub.add_parser(name, help=what, description=descriptions[name])
        p.add_argument("--out", default=os.path.join("out", name),
                       help=f"output folder (default ./out/{name})")
        if name == "validate":
            p.add_argument("--build-dir", help="CMake build folder for the FMUs (default: "
                           "OUT/build); an existing build there is reused")
        if name == "report":
            p.add_argument("--only", nargs="+", metavar="SECTION",
                           help="build only these sections (e.g. seed000 seed004)")
        add_cost_options(p)
        p.set_defaults(func=func)
