#!/usr/bin/env bash
# The main job: set up, build the FMUs, validate them against the NumPy reference with fmpy,
# and reproduce the seed papers' claims. Results land in out/validation and out/report.
# Needs: python3 >= 3.10 (with venv), a C compiler, cmake >= 3.16. Idempotent: reuses .venv.
set -euo pipefail
cd "$(dirname "$0")/.."

python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "python3 >= 3.10 is required")'
[ -x .venv/bin/python ] || python3 -m venv .venv
. .venv/bin/activate
python -m pip install -q --upgrade pip
python -m pip install -q -e ".[validate]"

# Both FMUs (SmoothShaper.fmu, TrajectoryGenerator.fmu) with CMake; validate reuses this build.
cmake -S . -B build/fmu -DCMAKE_BUILD_TYPE=Release -DSMS_BUILD_TESTS=OFF -DSMS_BUILD_SHARED=OFF
cmake --build build/fmu -j2

status=0
smoothshaper validate --out out/validation --build-dir build/fmu || status=$?
smoothshaper report --out out/report || status=$?
if [ "$status" -eq 0 ]; then
    echo "main.sh: done; see out/validation and out/report"
else
    echo "main.sh: a step failed (exit $status); see the messages above" >&2
fi
exit "$status"
