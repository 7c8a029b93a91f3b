# SPDX-License-Identifier: Apache-2.0
"""The one exception type of the package for invalid arguments, and the one warning of the
online generators (a target they dropped).

Every function and class that validates its arguments raises :class:`ParameterError`, a
``ValueError`` subclass, so ``except ValueError`` keeps working. Its message starts with the
offending parameter's name, and :attr:`ParameterError.parameter` holds that name (for data
files, the CLI adds the file and row). The constructor keeps the rule: a message that does not
start with the name gets it as a prefix (``"amax: ..."``).
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
        if not starts_with_name(message, parameter):    # the one rule, kept by construction
            message = f"{parameter}: {message}"
        super().__init__(message)
        self.parameter = parameter
        self.status = status


def starts_with_name(message: str, parameter: str) -> bool:
    """Whether ``message`` starts with ``parameter`` as a whole name.

    Parameters
    ----------
    message : str
        An error message.
    parameter : str
        A parameter's name (``"T"``, ``"vmax[1]"``).

    Returns
    -------
    bool
        ``"T must be > 0"`` does for ``T``; ``"Ts=0.1: ..."`` does not (it names ``Ts``).
    """
    if not message.startswith(parameter):
        return False
    rest = message[len(parameter):]
    return not rest or not (rest[0].isalnum() or rest[0] == "_")


class DroppedTargetWarning(RuntimeWarning):
    """A target of an online generator's ``process`` was dropped: its move cannot be
    represented in the build's floats (it would last more than 2^52 samples, or a value on
    the way would overflow). The generator keeps its previous goal until the target changes;
    ``refused`` and ``dropped`` on the generator say the same."""
