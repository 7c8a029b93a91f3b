#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The main job: set up, build the FMUs, validate them against the NumPy reference with fmpy,
# reproduce the seed papers' claims and run the system co-simulation. Results land in
# out/validation, out/report and out/cosim. Prints one line per phase with the time since the
# start; the compilers' output goes to build/main-*.log (shown when a step fails).
# Needs: python3 >= 3.10 (with venv), a C compiler, cmake >= 3.16. Idempotent: reuses .venv.
set -euo pipefail
cd "$(dirname "$0")/.."

start=$SECONDS
phase() { printf 'main.sh [%4d s] %s\n' $((SECONDS - start)) "$*"; }
# Run a quiet step; on failure show the end of its log and stop.
logged() {
    local log=$1; shift
    "$@" >"$log" 2>&1 || { tail -n 40 "$log" >&2; echo "main.sh: failed, see $log" >&2; exit 1; }
}
mkdir -p build

python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "python3 >= 3.10 is required")'
phase "Python environment (.venv)"
[ -x .venv/bin/python ] || python3 -m venv .venv
. .venv/bin/activate
logged build/main-pip.log python -m pip install --upgrade pip
phase "installing the package and its validate extra (compiles the C core into the extension)"
logged build/main-pip.log python -m pip install -e ".[validate]"

# The FMUs (SmoothShaper, TrajectoryGenerator, MultiAxisGenerator, ElasticPlant, ServoDrive),
# FMI 2.0 in build/fmu/fmus and FMI 3.0 in build/fmu/fmus/3.0, only their CMake targets;
# validate (fmpy validate, fmutool -check and fmpy runs of both versions, the FMI 2.0 importers
# libcosim and fmpy) and the system co-simulations reuse this build. The build runs in the
# background beside `report`, which needs no FMU: the two keep both cores busy.
phase "building the FMUs in the background (CMake, build/fmu)"
python -c 'from pathlib import Path; from smoothshaper.fmi.build import build_fmus
for v in ("2.0", "3.0"): build_fmus(Path("build/fmu"), fmi_version=v)' >build/main-fmu.log 2>&1 &
fmu_pid=$!

status=0
phase "smoothshaper report --out out/report (beside the FMU build)"
smoothshaper report --out out/report || status=$?
phase "waiting for the FMUs"
wait "$fmu_pid" || { tail -n 40 build/main-fmu.log >&2; echo "main.sh: failed, see build/main-fmu.log" >&2; exit 1; }
# System co-simulations: TrajectoryGenerator -> SmoothShaper -> ElasticPlant, and -> ServoDrive
# (a drive in closed loop), connected by SSP files, run in libcosim and fmpy with and without the
# shaper; plots and tables. They run beside validate (their output is shown after it); both
# take the FMUs of build/fmu, whose build they take in turn (build_fmus locks the tree).
phase "python -m smoothshaper.cosim --out out/cosim (in the background, output in build/main-cosim.log)"
python -m smoothshaper.cosim --out out/cosim --build-dir build/fmu >build/main-cosim.log 2>&1 &
cosim_pid=$!
phase "smoothshaper validate --out out/validation"
smoothshaper validate --out out/validation --build-dir build/fmu || status=$?
cosim_rc=0
wait "$cosim_pid" || cosim_rc=$?
phase "python -m smoothshaper.cosim finished (exit $cosim_rc):"
cat build/main-cosim.log
[ "$cosim_rc" -eq 0 ] || status=$cosim_rc
if [ "$status" -eq 0 ]; then
    phase "done; see out/validation, out/report and out/cosim"
else
    phase "a step failed (exit $status); see the messages above" >&2
fi
exit "$status"
