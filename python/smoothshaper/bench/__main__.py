# SPDX-License-Identifier: Apache-2.0
"""``python -m smoothshaper.bench``: the benchmark suite of docs/benchmarks.md."""
import sys

from .suite import main

sys.exit(main())
