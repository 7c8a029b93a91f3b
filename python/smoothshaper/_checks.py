# SPDX-License-Identifier: Apache-2.0
"""Argument checks shared by every public function: each raises
:class:`~smoothshaper.errors.ParameterError` naming the parameter, so callers get the same
message for the same mistake everywhere. Booleans, complex numbers and strings are refused
(``T=True`` is a mistake, not 1 s), and numbers are shown plainly (``nan``, not
``np.float64(nan)``)."""
from __future__ import annotations

import math
import numbers

import numpy as np

from .errors import ParameterError


def show(value) -> str:
    """``value`` for an error message: NumPy scalars as plain Python numbers, and an int of
    more than 64 bits by its size (``10**400`` would be 401 digits)."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 64:
        return f"{'a negative' if value < 0 else 'an'} int of {value.bit_length()} bits"
    return repr(value)


def _type_text(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return f"a boolean ({bool(value)!r})"
    if isinstance(value, (complex, np.complexfloating)):
        return f"a complex number ({show(value)})"
    return f"{type(value).__name__} {show(value)}"


def real(name: str, value) -> float:
    """``value`` as a float; ParameterError naming ``name`` unless it is a real number
    (int, float, NumPy real scalar or 0-d real array; not bool, complex or str)."""
    if type(value) is float or type(value) is np.float64:
        return float(value)         # the common case, first: every Stage checks seven fields
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_, np.timedelta64)) \
            or not isinstance(value, (numbers.Real, np.number)) \
            or isinstance(value, (complex, np.complexfloating)):
        raise ParameterError(name, f"{name} must be a real number, got {_type_text(value)}")
    try:
        return float(value)
    except OverflowError:   # an int (or a Fraction) beyond the largest float (about 1.8e308)
        if isinstance(value, numbers.Integral):
            raise ParameterError(name, f"{name} must be finite, got an int of "
                                 f"{int(value).bit_length()} bits, beyond the largest float "
                                 "(about 1.8e308)") from None
        raise ParameterError(name, f"{name} must be finite, got a {type(value).__name__} beyond "
                             "the largest float (about 1.8e308)") from None
    except (TypeError, ValueError):     # a Real whose __float__ fails
        raise ParameterError(name, f"{name} must be a real number, got "
                             f"{_type_text(value)}") from None


def finite(name: str, value) -> float:
    """A finite real number (see :func:`real`)."""
    v = real(name, value)
    if not math.isfinite(v):
        raise ParameterError(name, f"{name} must be finite, got {v!r}")
    return v


def positive(name: str, value) -> float:
    """A finite real number > 0."""
    v = finite(name, value)
    if v <= 0:
        raise ParameterError(name, f"{name} must be > 0, got {v!r}")
    return v


def nonnegative(name: str, value) -> float:
    """A finite real number >= 0."""
    v = finite(name, value)
    if v < 0:
        raise ParameterError(name, f"{name} must be >= 0, got {v!r}")
    return v


def integer(name: str, value, minimum: int | None = None) -> int:
    """An integer (int, NumPy integer, or a float with an integral value), optionally
    ``>= minimum``; never a bool."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if type(value) is int:          # the common case, without the ABC checks (bool is not int)
        n = value
    elif isinstance(value, (bool, np.bool_, np.timedelta64)) \
            or not isinstance(value, (numbers.Real, np.number)) \
            or isinstance(value, (complex, np.complexfloating)):
        raise ParameterError(name, f"{name} must be an integer, got {_type_text(value)}")
    elif isinstance(value, (numbers.Integral, np.integer)):
        n = int(value)
    else:
        v = real(name, value)
        if not math.isfinite(v) or v != int(v):
            raise ParameterError(name, f"{name} must be an integer, got {v!r}")
        n = int(v)
    if minimum is not None and n < minimum:
        raise ParameterError(name, f"{name} must be an integer >= {minimum}, got {show(n)}")
    return n


def choice(name: str, value, options) -> str:
    """``value`` lower-cased if it is one of ``options`` (names compare case-insensitively)."""
    if not isinstance(value, str):
        raise ParameterError(name, f"{name} must be one of {', '.join(options)}; "
                             f"got {_type_text(value)}")
    key = value.strip().lower()
    if key not in options:
        raise ParameterError(name, f"{name} must be one of {', '.join(options)}; got {value!r}")
    return key


def real_array(name: str, values, ndim: int | None = None) -> np.ndarray:
    """``values`` as a float64 array; ParameterError naming ``name`` if it holds anything but
    real numbers (complex, boolean, strings or objects are refused, not cast), or is a masked
    array with masked entries (np.asarray would take the values under the mask)."""
    if isinstance(values, np.ma.MaskedArray) and np.ma.is_masked(values):
        raise ParameterError(name, f"{name} has masked entries: fill or drop them first "
                             "(numpy.ma.filled or .compressed())")
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError):
        raise ParameterError(name, f"{name} must be an array of real numbers") from None
    if raw.dtype.kind in "c":
        raise ParameterError(name, f"{name} must be real, got a complex array")
    if raw.dtype.kind == "b":
        raise ParameterError(name, f"{name} must hold numbers, got a boolean array")
    if raw.dtype.kind not in "iuf":
        raise ParameterError(name, f"{name} must be an array of real numbers, "
                             f"got dtype {raw.dtype}")
    with np.errstate(over="ignore"):    # a longdouble beyond 1.8e308 becomes inf: callers
        x = raw.astype(np.float64, copy=False)   # that need finite values name it then
    if ndim is not None and x.ndim != ndim:
        what = {1: "one-dimensional", 2: "two-dimensional"}.get(ndim, f"{ndim}-dimensional")
        raise ParameterError(name, f"{name} must be {what}, got shape {x.shape}")
    return x


def finite_array(name: str, values) -> np.ndarray:
    """A float64 array of finite real values, any shape (times, frequencies); the first
    non-finite entry is named by its flat index."""
    x = real_array(name, values)
    bad = np.flatnonzero(~np.isfinite(x.ravel()))
    if bad.size:
        raise ParameterError(name, f"{name} must be finite: {name}[{bad[0]}] = "
                             f"{float(x.ravel()[bad[0]])!r}" + (" (flat index)" if x.ndim > 1 else ""))
    return x


def finite_vector(name: str, values) -> np.ndarray:
    """A non-empty one-dimensional float64 vector of finite values (a scalar is one value,
    as for per-axis quantities); the first non-finite entry is named by its index."""
    v = np.atleast_1d(real_array(name, values))
    if v.ndim != 1 or v.size == 0:
        raise ParameterError(name, f"{name} must be a value or a non-empty vector, got shape "
                             f"{v.shape}")
    bad = np.flatnonzero(~np.isfinite(v))
    if bad.size:
        raise ParameterError(name, f"{name}[{bad[0]}] must be finite, got {float(v[bad[0]])!r}")
    return v


def finite_signal(name: str, values) -> np.ndarray:
    """A one-dimensional float64 array of finite real values."""
    x = real_array(name, values, ndim=1)
    bad = np.flatnonzero(~np.isfinite(x))
    if bad.size:
        raise ParameterError(name, f"{name} must be finite: {name}[{bad[0]}] = "
                             f"{float(x[bad[0]])!r}")
    return x


def complex_array(name: str, values) -> np.ndarray:
    """``values`` as a complex128 array of finite numbers (any shape); ParameterError naming
    ``name`` for text, objects, booleans, NaN or inf."""
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError):
        raise ParameterError(name, f"{name} must be an array of numbers") from None
    if raw.dtype.kind == "b":
        raise ParameterError(name, f"{name} must hold numbers, got a boolean array")
    if raw.dtype.kind not in "iufc":
        raise ParameterError(name, f"{name} must be an array of numbers, got dtype {raw.dtype}")
    with np.errstate(over="ignore"):
        x = raw.astype(np.complex128, copy=False)
    bad = np.flatnonzero(~np.isfinite(x.ravel()))
    if bad.size:
        raise ParameterError(name, f"{name} must be finite: {name}[{bad[0]}] = "
                             f"{complex(x.ravel()[bad[0]])!r} (flat index)")
    return x


def representable(name: str, values, what: str) -> np.ndarray:
    """``values``, or ParameterError naming ``name`` when an entry is NaN or inf: a result of
    finite arguments beyond the range of a float is refused, never returned."""
    bad = np.flatnonzero(~np.isfinite(np.ravel(values)))
    if bad.size:
        raise ParameterError(name, f"{name}: {what} at (flat) index {bad[0]} is beyond the "
                             "range of a float for these arguments (it came out NaN or inf)")
    return values


def position_limits(qmin, qmax, profile: str, real, precision: str):
    """(qmin, qmax) as the C config takes them: (0, 0) for none (both None); else both
    finite, qmin < qmax (also in the build's floats), each at most the largest float over 16,
    and a linear-ramp profile; ``real`` is the build's NumPy float type."""
    if qmin is None and qmax is None:
        return 0.0, 0.0
    for name, value, other in (("qmin", qmin, "qmax"), ("qmax", qmax, "qmin")):
        if value is None:
            raise ParameterError(name, f"{name} must be given with {other} (position limits "
                                       f"[qmin, qmax]; both None: none)")
    lo, hi = finite("qmin", qmin), finite("qmax", qmax)
    big = float(np.finfo(real).max) / 16
    for name, value in (("qmin", lo), ("qmax", hi)):
        if not abs(value) <= big:
            raise ParameterError(name, f"{name}={value!r}: its magnitude must be at most "
                                       f"{big:.6g}, the largest {precision} over 16")
    if not real(lo) < real(hi):
        raise ParameterError("qmax", f"qmax={qmax!r} must be above qmin={qmin!r} (in "
                                     f"{precision})")
    if profile == "trigonometric":
        raise ParameterError("qmin", f"qmin={qmin!r}, qmax={qmax!r}: position limits take a "
                                     "linear-ramp profile (polynomial or damped), not the "
                                     "trigonometric one")
    return lo, hi
