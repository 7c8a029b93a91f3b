#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What `pip install .` gives a user: builds the wheel as pip does (an isolated build of the
# C core into the extensions), installs it into a fresh virtual environment that has nothing
# but the base dependencies (numpy, scipy, cffi) and checks it there, away from the source
# tree: every module imports, the README's Python examples run, every subcommand answers
# --help, the commands that need an extra exit 3 naming it (tests/install/wheel_smoke.py).
# Usage: bash tests/install/fresh_venv.sh [python]   (default: .venv/bin/python, else python3)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
python=${1:-$([ -x .venv/bin/python ] && echo .venv/bin/python || echo python3)}
work=build/wheel
rm -rf "$work"
mkdir -p "$work"
"$python" -m pip wheel -q --no-deps -w "$work/dist" .
wheels=("$work"/dist/smoothshaper-*.whl)
[ ${#wheels[@]} -eq 1 ] || { echo "fresh_venv: expected one wheel, got ${wheels[*]}" >&2; exit 1; }
"$python" -m venv "$work/venv"
"$work/venv/bin/python" -m pip install -q "${wheels[0]}"
cd "$work"      # not the repository: only what the wheel installed can be imported
venv/bin/python "$root/tests/install/wheel_smoke.py" --wheel "$root/${wheels[0]}" \
    --readme "$root/README.md" --examples "$root/examples"
