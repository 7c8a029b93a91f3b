# SPDX-License-Identifier: Apache-2.0
"""``python -m smoothshaper.cosim``: the system co-simulation of :mod:`smoothshaper.fmi.cosim`
under its former name (the names of that module are importable from here too)."""
from .fmi.cosim import *  # noqa: F401,F403
from .fmi.cosim import KIND_NONE, KIND_ZV, __all__, main  # noqa: F401

if __name__ == "__main__":
    raise SystemExit(main())
