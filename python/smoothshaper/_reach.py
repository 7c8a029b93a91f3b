# SPDX-License-Identifier: Apache-2.0
"""The message for limits with which no move can reach vmax, for both online generators.

``sms_generator_reach`` (trajectory.h) and ``sms_multi_generator_reach`` (multi_generator.h)
fill one ``sms_generator_reach_info``: the first derived quantity out of range, the arguments
it is formed from, its value and bound. :func:`refused` turns it into the ParameterError the
Generator and the MultiAxisGenerator raise: the user's arguments with their values first
(``jmax=1e-300, vmax=1.0`` or, for an axis, ``jmax[1]=1e-300, vmax[1]=1.0 (axis 1)``), the one
the error names first, then the quantity as explanation.
"""
from __future__ import annotations

from .errors import ParameterError

#: The limits a quantity may be formed from, in the order the arguments are named.
LIMITS = ("vmax", "amax", "jmax", "vmin", "amin")
#: Durations: reaching a velocity bound does not fit the plan's samples (asymmetric limits
#: pair each velocity bound with each acceleration bound).
DURATIONS = tuple(f"{v}/{a}" for v in ("vmax", "vmin") for a in ("amax", "amin")) + tuple(
    f"sqrt({pi}{v}/{j})" for v in ("vmax", "vmin") for pi, j in (("", "jmax"),
                                                                  ("pi ", "(2 jmax)")))
#: The multi-axis planner's capped ratios limit/change.
RATIOS = ("amax/vmax", "jmax/vmax", "amax/h", "jmax/h")


def named(quantity: str, arguments, duration: float) -> str:
    """The argument a refused limit set names, from the quantity out of range, the arguments
    it is formed from (in the order vmax, amax, jmax) and the duration to reach vmax [s]:
    ``Ts`` when reaching vmax takes more samples than a plan holds although it lasts at most
    1e9 s (a plausible machine: Ts is extreme), else the limit to change."""
    if quantity.startswith("the "):     # the duration or the distance to reach vmax (vmin)
        return "vmin" if quantity.endswith("vmin") else "vmax"
    if quantity in DURATIONS:
        return "Ts" if duration <= 1e9 else arguments[-1]
    if quantity in ("vmax*jmax", "vmin*jmax"):
        return arguments[-1]
    return min((n for n in LIMITS if n in quantity), key=quantity.find,
               default=arguments[-1])         # the first limit the quantity names


def refused(ffi, info, limits: dict, Ts: float, st: int, axis: int | None = None):
    """ParameterError for limits outside the feasible region.

    Parameters
    ----------
    ffi : cffi.FFI
        The module's FFI (strings, ``sizeof(sms_real)``).
    info : sms_generator_reach_info *
        Filled by ``sms_generator_reach`` or ``sms_multi_generator_reach``.
    limits : dict
        The user's ``vmax``, ``amax``, ``jmax`` (of the refused axis).
    Ts : float
        The sample period [s].
    st : int
        The status of the refused init.
    axis : int or None
        The refused axis of a MultiAxisGenerator (arguments named ``vmax[axis]``), None for
        the Generator.

    Returns
    -------
    ParameterError
        Naming the argument to change: ``Ts`` when reaching vmax takes more samples than a
        plan holds although it lasts at most 1e9 s, else the limit the quantity is formed
        from (``vmax[1]`` for an axis).
    """
    sub = "" if axis is None else f"[{axis}]"
    tail = "" if axis is None else f" (axis {axis})"
    # the velocity bound the refused move reaches (vmin for a move of asymmetric limits)
    vmax = f"vmin{sub}" if info.quantity != ffi.NULL and "vmin" in ffi.string(
        info.quantity).decode() else f"vmax{sub}"
    if info.quantity == ffi.NULL:  # a limit not finite and > 0 (checked before the region)
        bad = next((n for n in ("vmax", "amax", "jmax") if not 0 < limits[n] < float("inf")),
                   "vmax")
        values = ", ".join(f"{n}{sub}={limits[n]!r}" for n in ("vmax", "amax", "jmax"))
        return ParameterError(bad + sub, f"{bad}{sub}={limits[bad]!r}: the limits{tail} "
                              f"{values} must be finite and > 0", st)
    quantity = ffi.string(info.quantity).decode()
    names = ffi.string(info.arguments).decode().split(", ")
    if quantity == "Ts":   # refused for every axis (the C core checks the limits first)
        tail = ""
    parameter = named(quantity, names, info.duration)
    # the argument the error names first (the message starts with it), then the others
    order = sorted(names, key=lambda n: n != parameter)
    values = ", ".join(f"{n}={Ts!r}" if n == "Ts" else f"{n}{sub}={limits[n]!r}"
                       for n in order if n in limits or n == "Ts") + tail
    value, bound = info.value, info.bound
    real = "float" if ffi.sizeof("sms_real") == 4 else "double"
    if quantity in ("vmin", "amin"):
        upper = "vmax" if quantity == "vmin" else "amax"
        msg = (f"{values}: {quantity} must be < 0 with its magnitude a normal {real} at most "
               f"the largest over 16 (room for a reversal)" if "profile" not in names else
               f"{quantity}{sub}={limits[quantity]!r}: the trigonometric profile takes "
               f"symmetric limits only ({quantity} 0 or -{upper})")
        return ParameterError(quantity + sub, msg, st)
    if quantity in names:
        msg = (f"{values}: below {bound:.6g}, the smallest normal {real}" if value < bound else
               f"{values}: above {bound:.6g} = 2^967, the largest Ts a generator takes (2^56 "
               "Ts, its longest time sum, must stay finite)" if quantity == "Ts" and st == -55 else
               f"{values}: above {bound:.6g}, the largest {real}" if quantity == "Ts" else
               f"{values}: above {bound:.6g}, the largest {real} over 16 (room for a reversal)")
    elif quantity in DURATIONS:
        move = "move" if axis is None else f"move of axis {axis}"
        values = values if "Ts" in names else (
            f"{values[:len(values) - len(tail)]}, Ts={Ts!r}{tail}" if parameter != "Ts" else
            f"Ts={Ts!r}, {values}")
        msg = (f"{values}: {quantity} = {value:.6g} s, so reaching {vmax} from rest "
               f"takes {info.duration:.6g} s = {info.samples:.6g} samples of Ts, more than "
               f"the 2^50 a plan can hold with room for a reversal (its limit is 2^52): no "
               f"{move} that reaches {vmax} can be planned")
    elif quantity in RATIOS and value > bound:
        whose = "the" if axis is None else f"axis {axis}'s"
        msg = (f"{values}: {quantity} = {value:.6g} exceeds {bound:.6g} = 2^56 (h = "
               f"{info.distance:.6g}, the distance to reach {vmax}): the planner caps its "
               f"ratios limit/change at 2^60, so {whose} moves would be lengthened beyond "
               "their plan")
    elif value < bound:
        why = (f"h = {info.distance:.6g}, the distance to reach {vmax}" if "/h" in quantity
               else f"the smallest normal {real}" if quantity == "the duration to reach vmax"
               else f"the smallest normal {real} over its epsilon")
        msg = (f"{values}: {quantity} = {value:.6g} is below {bound:.6g} ({why}): the "
               "planner's products would underflow")
    else:
        why = ("over 16^2, for moves up to 16 times as long" if "squared" in quantity
               else "over 16, room for a reversal")
        msg = (f"{values}: {quantity} = {value:.6g} exceeds {bound:.6g} (the largest {real} "
               f"{why}): the planner's values would overflow")
    return ParameterError(parameter if parameter == "Ts" else parameter + sub, msg, st)
