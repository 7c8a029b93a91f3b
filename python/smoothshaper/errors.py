"""The one exception type of the package for invalid arguments.

Every function and class that validates its arguments raises :class:`ParameterError`, a
``ValueError`` subclass, so ``except ValueError`` keeps working. Its message starts with the
offending parameter's name, and :attr:`ParameterError.parameter` holds that name (for data
files, the CLI adds the file and row).
"""
from __future__ import annotations

__all__ = ["ParameterError"]


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
