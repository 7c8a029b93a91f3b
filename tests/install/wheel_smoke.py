# SPDX-License-Identifier: Apache-2.0
"""Checks an installed smoothshaper wheel in an environment with only its base dependencies
(run by tests/install/fresh_venv.sh; prints one line per check, exits 1 on the first
failure)."""
import argparse
import importlib
import os
import pkgutil
import re
import subprocess
import sys
import time
import zipfile
from pathlib import Path

START = time.perf_counter()


def say(text: str) -> None:
    print(f"[{time.perf_counter() - START:5.1f} s] {text}", flush=True)


def fail(text: str) -> None:
    print(f"wheel_smoke: FAILED: {text}", file=sys.stderr)
    sys.exit(1)


def run(argv, expect: int = 0, contains: str = ""):
    done = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    if done.returncode != expect or contains not in done.stdout + done.stderr:
        fail(f"{' '.join(argv)} exited {done.returncode} (expected {expect}"
             + (f", output with {contains!r}" if contains else "") + f"):\n{done.stdout}\n"
             f"{done.stderr}")
    return done


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--wheel", required=True, type=Path)
    ap.add_argument("--readme", required=True, type=Path)
    ap.add_argument("--examples", required=True, type=Path)
    args = ap.parse_args()

    # The wheel carries the compiled extensions and no C sources: it is self-contained.
    names = zipfile.ZipFile(args.wheel).namelist()
    for ext in ("_core", "_core_float", "_kinematic_fastpath"):
        if not any(re.fullmatch(rf"smoothshaper/{ext}\..*(so|pyd)", n) for n in names):
            fail(f"the wheel has no compiled smoothshaper/{ext}")
    say(f"{args.wheel.name}: {len(names)} files, the three compiled extensions")

    import smoothshaper
    where = Path(smoothshaper.__file__).resolve()
    if Path(sys.prefix).resolve() not in where.parents:
        fail(f"smoothshaper was imported from {where}, not from this environment")
    extras = [m for m in ("matplotlib", "fmpy", "libcosimpy", "ruckig")
              if importlib.util.find_spec(m) is not None]
    if extras:
        fail(f"the environment is not bare: {extras} are installed")

    # Every module imports with the base dependencies alone (the optional ones load lazily).
    count = 0
    for info in pkgutil.walk_packages(smoothshaper.__path__, "smoothshaper."):
        leaf = info.name.rsplit(".", 1)[-1]
        # a program; the build-time modules (setup.py's, they import setuptools)
        if leaf in ("__main__", "_build_core", "_build_library"):
            continue
        importlib.import_module(info.name)
        count += 1
    for name in smoothshaper.SUBMODULES:
        getattr(smoothshaper, name)
    say(f"imported {count} modules (numpy, scipy and cffi only)")

    # The README's Python examples, in order, in one namespace.
    text = args.readme.read_text()
    namespace: dict = {}
    python_blocks = re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)
    if len(python_blocks) < 2:
        fail(f"{args.readme} has {len(python_blocks)} Python examples, expected at least 2")
    for block in python_blocks:
        exec(compile(block, str(args.readme), "exec"), namespace)
    say(f"the README's {len(python_blocks)} Python examples ran")

    exe = Path(sys.executable).with_name("smoothshaper")
    from smoothshaper.cli import build_parser
    parser = build_parser()
    commands = [[c] for c in parser._subparsers._group_actions[0].choices]
    commands += [["design", "generator"], ["design", "bspline"]]
    for command in [[]] + commands:
        run([str(exe), *command, "--help"], contains="usage:")
    for module in ("smoothshaper", "smoothshaper.bench", "smoothshaper.bench.trajectory",
                   "smoothshaper.report", "smoothshaper.cosim"):
        run([sys.executable, "-m", module, "--help"], contains="usage:")
    say(f"--help of the command and its {len(commands)} subcommands, and of 5 -m programs")

    run([str(exe), "design", "--kind", "zvd", "--wn", "100", "--zeta", "0.05"], contains="zvd")
    run([str(exe), "identify", str(args.examples / "decay.csv")], contains="wn")
    for argv, extra in ((["report", "--out", "out"], "plot"),
                        (["validate", "--out", "out"], "validate"),
                        (["analyze", "--stage", "zv:wn=100", "--Ts", "1e-3", "--out", "out"],
                         "plot")):
        done = run([str(exe), *argv], expect=3, contains=f"pip install 'smoothshaper[{extra}]'")
        if done.stderr.count("\n") != 1 or os.path.exists("out/README.md"):
            fail(f"{argv[0]} without its extra: {done.stderr!r}")
    for argv, leftover in ((["design", "generator", "--via", "0,20,40", "--vmax", "250",
                             "--amax", "5000", "--jmax", "200000", "--Ts", "1e-3", "--plot",
                             "g.png", "--csv", "g.csv"], "g.csv"),
                           (["calibrate", str(args.examples / "resonance_xy.csv"), "--axis",
                             "y", "--out", "cal"], "cal")):
        done = run([str(exe), *argv], expect=3, contains="pip install 'smoothshaper[plot]'")
        if done.stdout or os.path.exists(leftover):
            fail(f"{argv[0]} without matplotlib worked before exiting: {done.stdout!r}")
    done = run([sys.executable, "-m", "smoothshaper.cosim", "--out", "c"], expect=3,
               contains="pip install 'smoothshaper[validate]'")
    if done.stderr.count("\n") != 1 or os.path.exists("c"):
        fail(f"the co-simulation without its extra: {done.stderr!r}")
    say("design and identify run; report, validate, analyze, design --plot, calibrate --out "
        "and the co-simulation exit 3 naming their extra, before any work")
    print("wheel_smoke: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
