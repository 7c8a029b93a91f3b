# SPDX-License-Identifier: Apache-2.0
"""``python -m smoothshaper``: the same as the ``smoothshaper`` command."""
import sys

from .cli import main

sys.exit(main())
