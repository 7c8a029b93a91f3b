# SPDX-License-Identifier: Apache-2.0
"""``python -m smoothshaper.report --out DIR [--only KEY ...]``: write the seed report."""
from __future__ import annotations

import argparse
import sys

from . import SECTIONS, run


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m smoothshaper.report",
                                     description="Reproduce the seed papers' numbers and figures.")
    parser.add_argument("--out", required=True, help="output folder (README.md + figures/)")
    parser.add_argument("--only", nargs="+", choices=SECTIONS, help="build only these sections")
    args = parser.parse_args(argv)
    try:
        readme = run(args.out, only=args.only)
    except RuntimeError as exc:
        print(exc, file=sys.stderr)
        return 1
    print(readme)
    return 0


if __name__ == "__main__":
    sys.exit(main())
