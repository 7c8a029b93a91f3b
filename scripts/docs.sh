#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Build the API references into out/docs/html, failing on any warning:
# - Python, from the docstrings (Sphinx autodoc + napoleon). Needs the package installed with
#   the docs extra: pip install -e ".[docs]"   (scripts/test.sh does this and runs this script)
# - C, from the public headers (Doxygen, docs/Doxyfile) into out/docs/html/c. Needs doxygen
#   (Debian: apt-get install doxygen; scripts/install-cross-tools.sh installs it as root).
#   Without it the C reference is skipped with a message, except in CI (CI=true), which must
#   build it and fails instead.
set -euo pipefail
cd "$(dirname "$0")/.."
python -m sphinx -E -q -W --keep-going -b html docs/api out/docs/html
echo "API reference: out/docs/html/index.html"
if command -v doxygen >/dev/null; then
    mkdir -p out/docs/html
    rm -rf out/docs/html/c
    doxygen docs/Doxyfile   # WARN_AS_ERROR: exits non-zero on any warning
    echo "C API reference: out/docs/html/c/index.html"
elif [ "${CI:-}" = true ]; then
    echo "docs.sh: doxygen is not installed, so the C API reference cannot be built;" \
         "CI must build it (scripts/install-cross-tools.sh installs doxygen as root)" >&2
    exit 1
else
    echo "docs.sh: SKIPPED the C API reference: doxygen is not installed" \
         "(Debian: apt-get install doxygen). The Python reference above was built." >&2
fi
