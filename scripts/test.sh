#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Set up from scratch and run every test: the C suite under ctest (double and float, then again
# under AddressSanitizer + UndefinedBehaviorSanitizer) and the Python suite under pytest.
# Needs: python3 >= 3.10 (with venv), a C compiler, cmake >= 3.16. Idempotent: reuses .venv.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS

python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "python3 >= 3.10 is required")'
[ -x .venv/bin/python ] || python3 -m venv .venv
. .venv/bin/activate
python -m pip install -q --upgrade pip
# Editable install: builds the cffi extensions smoothshaper._core/_core_float from c/src.
python -m pip install -q -e ".[test,docs]"

# The load average, so that the step times below can be read on a shared machine.
load() { cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown; }

# CPU seconds (user + sys) of this script's finished children (cutime + cstime of this shell,
# read from /proc, as `times` in a command substitution would count the subshell's). A step in
# the foreground has finished when it returns, so the difference around it is its CPU time;
# the pytest run in the background counts when it has been waited for.
cpu() { awk -v hz="$(getconf CLK_TCK)" '{ sub(/^.*\) /, ""); printf "%d", ($14 + $15) / hz }' \
        /proc/$$/stat 2>/dev/null || echo 0; }

# Every suite runs even if an earlier one fails, so one report shows all failures. Each step
# prints the time since the start when it begins, and its wall and CPU time when it ends.
printf '== [%4d s] set up: %d s CPU; load average %s\n' $((SECONDS - start)) "$(cpu)" "$(load)"
failed=()
step() {
    local name=$1; shift
    local t0=$SECONDS c0; c0=$(cpu)
    printf '== [%4d s] %s\n' $((SECONDS - start)) "$name"
    "$@" || failed+=("$name")
    printf '== [%4d s] %s: %d s wall, %d s CPU; load average %s\n' $((SECONDS - start)) \
        "$name" $((SECONDS - t0)) $(($(cpu) - c0)) "$(load)"
}

# The release tree first: its FMUs are the ones pytest tests (built once, not again in
# build-pytest-fmu). The Python suite then runs on two worker processes (pytest-xdist, -n 2;
# the tests that share a built tree take its lock, smoothshaper.fmi.build_fmus) beside the rest,
# which runs in this order: ctest, the sanitizer build and its ctest, the API references and
# the wheel in a fresh venv (so no step runs alone on the two cores at the end); pytest's
# output is shown when it ends.
mkdir -p build
step "C build (release)" cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
step "C build (release)" cmake --build build/release -j2
fmu_dir=build-pytest-fmu
[ -d build/release/fmus ] && fmu_dir=build/release
printf '== [%4d s] pytest -n 2 (in the background, FMUs of %s, output in build/pytest.log)\n' \
    $((SECONDS - start)) "$fmu_dir"
SMOOTHSHAPER_TEST_FMU_DIR=$PWD/$fmu_dir python -m pytest tests/python -q -n 2 --durations=15 \
    >build/pytest.log 2>&1 &
pytest_pid=$!

step "ctest (release)" ctest --test-dir build/release --output-on-failure -j2 -LE long

# The sanitizer tree runs the same C suites on instrumented code; what does not depend on the
# instrumentation (the shared libraries' exports, the headers compiled alone, the per-sample
# link probes, the Cortex-M build) the release tree has checked already, so it is not built here.
step "C build (sanitize)" cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=Debug -DSMS_SANITIZE=ON \
    -DSMS_BUILD_SHARED=OFF
step "C build (sanitize)" cmake --build build/sanitize -j2
step "ctest (sanitize)" ctest --test-dir build/sanitize --output-on-failure -j2 -LE long

step "API references (sphinx and doxygen, warnings as errors)" bash scripts/docs.sh
# What `pip install .` gives a user: the wheel in a fresh venv with the base dependencies only.
step "wheel in a fresh venv" bash tests/install/fresh_venv.sh

pytest_rc=0
c0=$(cpu)
wait "$pytest_pid" || pytest_rc=$?
printf '== [%4d s] pytest (finished): %d s CPU; load average %s\n' $((SECONDS - start)) \
    $(($(cpu) - c0)) "$(load)"
cat build/pytest.log
# An empty collection (pytest exit code 5) must fail loudly, never pass as "nothing to do".
if [ "$pytest_rc" -eq 5 ]; then
    echo "test.sh: pytest collected no tests from tests/python" >&2
    failed+=("pytest collection")
elif [ "$pytest_rc" -ne 0 ]; then
    failed+=("pytest")
fi

if [ ${#failed[@]} -gt 0 ]; then
    # One line whatever the number of failed suites (printf would reuse its format per name).
    echo "test.sh: FAILED after $((SECONDS - start)) s wall, $(cpu) s CPU: $(IFS=';'; echo "${failed[*]}")" >&2
    exit 1
fi
echo "test.sh: all suites passed in $((SECONDS - start)) s wall, $(cpu) s CPU"
