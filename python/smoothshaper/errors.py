# SPDX-License-Identifier: Apache-2.0
"""The one exception type of the package for invalid arguments, and the one warning of the
online generators (a target they dropped).

Every function and class that validates its arguments raises :class:`ParameterError`, a
``ValueError`` subclass, so ``except ValueError`` keeps working. Its message starts with the
offending parameter's name, and :attr:`ParameterError.parameter` holds that name (for data
files, the CLI adds the file and row).
"""
from __future__ import annotations

__all__ = ["ParameterError", "DroppedTargetWarning"]


class ParameterError(ValueError):
    """An invalid argument.

    Attributes
    ----------
    parameter : str
        Name of the offending parameter (``"Ts"``, ``"wn"``, ``"stages[1]"``, ``"state"``, ...).
    status : int or None
        The C library's ``sms_status`` code when the C core rejected the value, else None.
    """

    def __init__(self, parameter: str, message: str, status: int | None = None):
        super().__init__(message)
        self.parameter = parameter
        self.status = status


class DroppedTargetWarning(RuntimeWarning):
    """A target of an online generator's ``process`` was dropped: its move cannot be
    represented in the build's floats (it would last more than 2^52 samples, or a value on
    the way would overflow). The generator keeps its previous goal until the target changes;
    ``refused`` and ``dropped`` on the generator say the same."""
