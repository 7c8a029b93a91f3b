#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Build the Python API reference from the docstrings (Sphinx autodoc + napoleon) into
# out/docs/html, failing on any warning. Needs the package installed with the docs extra:
#   pip install -e ".[docs]"   (scripts/test.sh does this and runs this script)
set -euo pipefail
cd "$(dirname "$0")/.."
python -m sphinx -E -q -W --keep-going -b html docs/api out/docs/html
echo "API reference: out/docs/html/index.html"
