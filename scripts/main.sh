#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The main job: set up, build the FMUs, validate them against the NumPy reference with fmpy,
# reproduce the seed papers' claims and run the system co-simulation. Results land in
# out/validation, out/report and out/cosim.
# Needs: python3 >= 3.10 (with venv), a C compiler, cmake >= 3.16. Idempotent: reuses .venv.
set -euo pipefail
cd "$(dirname "$0")/.."

python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "python3 >= 3.10 is required")'
[ -x .venv/bin/python ] || python3 -m venv .venv
. .venv/bin/activate
python -m pip install -q --upgrade pip
python -m pip install -q -e ".[validate]"

# The FMUs (SmoothShaper, TrajectoryGenerator, MultiAxisGenerator, ElasticPlant, ServoDrive)
# with CMake; validate and the system co-simulations reuse this build.
cmake -S . -B build/fmu -DCMAKE_BUILD_TYPE=Release -DSMS_BUILD_TESTS=OFF -DSMS_BUILD_SHARED=OFF
cmake --build build/fmu -j2

status=0
smoothshaper validate --out out/validation --build-dir build/fmu || status=$?
smoothshaper report --out out/report || status=$?
# System co-simulations: TrajectoryGenerator -> SmoothShaper -> ElasticPlant, and -> ServoDrive
# (a drive in closed loop), connected by SSP files, run in libcosim and fmpy with and without the
# shaper; plots and tables.
python -m smoothshaper.cosim --out out/cosim --build-dir build/fmu || status=$?
if [ "$status" -eq 0 ]; then
    echo "main.sh: done; see out/validation, out/report and out/cosim"
else
    echo "main.sh: a step failed (exit $status); see the messages above" >&2
fi
exit "$status"
