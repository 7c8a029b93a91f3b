#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Debian/Ubuntu, as root (.ci/run runs it before scripts/test.sh):
# - doxygen, which scripts/docs.sh needs for the C API reference (in CI a missing doxygen
#   fails the docs step; elsewhere docs.sh skips the C reference and says so);
# - optional: the mingw-w64 cross compiler (builds binaries/win64 into the FMUs), wine64 (runs
#   that binary through a minimal importer in tests/python/test_fmu_win64.py) and the Cortex-M
#   toolchain with newlib (ctest cortex_m_compile). Without them the FMUs carry linux64 only
#   and those tests are skipped with their stated reason.
# doxygen is installed on its own first, so an unavailable cross tool cannot keep it out.
set -euo pipefail
have_cross_tools() {
    # Debian's wine64 package puts wine64 in /usr/lib/wine, off PATH (the tests look there).
    command -v x86_64-w64-mingw32-gcc >/dev/null \
        && { command -v wine64 >/dev/null || [ -x /usr/lib/wine/wine64 ]; } \
        && command -v arm-none-eabi-gcc >/dev/null
}
if command -v doxygen >/dev/null && have_cross_tools; then
    exit 0
fi
if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null; then
    echo "install-cross-tools: needs root and apt-get; skipping (no doxygen: docs.sh skips the" \
         "C API reference; FMUs will be linux64 only)" >&2
    exit 0
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
if ! command -v doxygen >/dev/null; then
    apt-get install -y -qq --no-install-recommends doxygen >/dev/null
fi
if ! have_cross_tools; then
    apt-get install -y -qq --no-install-recommends gcc-mingw-w64-x86-64 wine64 \
        gcc-arm-none-eabi libnewlib-arm-none-eabi >/dev/null
fi
