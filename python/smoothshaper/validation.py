# SPDX-License-Identifier: Apache-2.0
"""The FMU validation API under its former name: every name of :mod:`smoothshaper.fmi`
(``from smoothshaper import validation`` keeps working)."""
from .fmi import *  # noqa: F401,F403
from .fmi import __all__  # noqa: F401
