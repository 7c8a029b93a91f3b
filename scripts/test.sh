#!/usr/bin/env bash
# Set up from scratch and run every test: the C suite under ctest (double and float, then again
# under AddressSanitizer + UndefinedBehaviorSanitizer) and the Python suite under pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m venv .venv
. .venv/bin/activate
python -m pip install -q --upgrade pip
python -m pip install -q -e ".[test]"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j2
ctest --test-dir build/release --output-on-failure -j2
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=Debug -DSMS_SANITIZE=ON
cmake --build build/sanitize -j2
ctest --test-dir build/sanitize --output-on-failure -j2
python -m pytest tests/python -q
