# SPDX-License-Identifier: Apache-2.0
"""Configuration text per firmware for :func:`.firmware.config_text`: Klipper's
``[input_shaper]`` section, Marlin's ``M493`` / ``M593``, RepRapFirmware's ``M593 P``, Prusa's
``M593 T``. Works on picks :func:`.firmware.config_text` has checked; every pick ends up applied
or written as a comment with a warning, never dropped."""
from __future__ import annotations

import math

from . import firmware_defs as defs

__all__ = ["lines"]

#: Klipper's find_shaper_max_accel: the smoothing [mm] a suggested max_accel may cause, and the
#: square_corner_velocity [mm/s] it assumes (shaper_calibrate.py).
TARGET_SMOOTHING = 0.12
SCV = 5.0

# Axes each firmware shapes separately (Marlin FT Motion: X, Y, Z with FTM_SHAPER_Z; classic:
# X, Y, Z; RepRapFirmware: one shaper for all axes)
_AXES = {"klipper": ("x", "y", "z"), "marlin": ("x", "y", "z"), "prusa": ("x", "y", "z")}
_COMMENT = {"klipper": "#", "marlin": ";", "rrf": ";", "prusa": ";"}


def _axis(name: str) -> str:
    """The machine axis a record column names: "x", "accel_x", "psd_x", "file.csv:x" -> "x"."""
    key = name.rsplit(":", 1)[-1].strip().lower()
    for prefix in ("accel_", "psd_", "acc_"):
        if key.startswith(prefix):
            key = key[len(prefix):]
    return key


def _line_axis(name: str, axes) -> str:
    """The axis to write a not-applied pick's lines for: its own, or <axis> when the firmware
    has no such axis (the user puts it where it was measured)."""
    axis = _axis(name)
    return axis if axis in axes else "<axis>"


def _num(x: float) -> str:
    return f"{x:.6g}"


def _accel_text(x: float) -> str:
    """A max_accel suggestion rounded down to 100 mm/s^2 (never above the rule)."""
    return "unlimited" if math.isinf(x) else f"{int(x // 100) * 100}"


def _limits_problem(p) -> str | None:
    """Why a pick lies outside its shaper's frequency or damping range, or None."""
    s = p.shaper
    if not s.min_freq <= p.freq <= s.max_freq:
        return (f"{s.name} at {_num(p.freq)} Hz is outside its frequency range, "
                f"{_num(s.min_freq)} to {_num(s.max_freq)} Hz (the firmware refuses or clamps "
                "others)")
    lo, hi = s.damping_range()
    if not lo <= p.damping <= hi:
        return (f"{s.name} with damping ratio {_num(p.damping)} is outside its damping range, "
                f"{_num(lo)} to {hi:.6g}")
    return None


def lines(fw: str, picks) -> tuple[list[str], list[str]]:
    """(lines, warnings) of ``fw``'s configuration for checked picks (axis name -> Pick)."""
    out, warnings = _WRITERS[fw](picks)
    c = _COMMENT[fw]
    accels = [(a, p.max_accel) for a, p in picks.items() if p.shaper is not None]
    if accels:
        out.append(f"{c} suggested max acceleration (smoothing <= {TARGET_SMOOTHING:g} mm at a "
                   f"square corner velocity of {SCV:g} mm/s, Klipper's rule), mm/s^2: "
                   + ", ".join(f"{a} <= {_accel_text(x)}" for a, x in accels))
    out += [f"{c} WARNING: {w}" for w in warnings]
    return out, warnings


def _assign(fw, picks, axes):
    """Split picks into (axis, pick) the firmware takes and warnings for the rest."""
    taken, rest, warnings = {}, [], []
    for name, p in picks.items():
        axis = _axis(name)
        if p.shaper is None:
            warnings.append(f"axis {name}: no {fw} shaper suits it (nothing written)")
            continue
        problem = _limits_problem(p)
        if axis not in axes:
            rest.append((name, p, f"axis {name}: {fw} has no axis '{axis}' (its axes: "
                                  f"{', '.join(axes)}); set it on the axis it was measured on"))
        elif axis in taken:
            rest.append((name, p, f"axis {name}: {fw} has one shaper per axis and axis "
                                  f"{axis} already takes {taken[axis][0]}'s pick"))
        elif problem:
            rest.append((name, p, f"axis {name}: {problem}"))
        else:
            taken[axis] = (name, p)
    return taken, rest, warnings


def _m201(taken):
    """The suggested max accelerations as a (commented) M201, for the axes applied."""
    acc = [(axis, p.max_accel) for axis, (_, p) in taken.items() if math.isfinite(p.max_accel)]
    if not acc:
        return []
    return ["; to limit acceleration as suggested: M201 "
            + " ".join(f"{axis.upper()}{_accel_text(x)}" for axis, x in acc)]


def _gcode_rest(lines, warnings, taken, rest, line, fw, store):
    """A G-code configuration's end: the picks not applied as comments with their warnings,
    the suggested M201, how to store the settings."""
    for name, p, why in rest:
        warnings.append(why)
        lines += [f"; not applied: {why}:", "; " + line(_line_axis(name, _AXES[fw]), p)]
    return lines + _m201(taken) + [store], warnings


def _klipper(picks):
    taken, rest, warnings = _assign("klipper", picks, _AXES["klipper"])
    lines = ["# Klipper input shaping (printer.cfg), shapers as defined in",
             "# klippy/extras/shaper_defs.py", "[input_shaper]"]

    def entry(axis, p):
        return [f"shaper_type_{axis}: {p.shaper.name}", f"shaper_freq_{axis}: {_num(p.freq)}",
                f"damping_ratio_{axis}: {_num(p.damping)}"]
    for axis, (name, p) in taken.items():
        s = p.shaper
        lines += entry(axis, p)
        if s.suggested_min_freq is not None and p.freq < s.suggested_min_freq:
            lines.append(f"#   {_num(p.freq)} Hz is below {_num(s.suggested_min_freq)} Hz, "
                         f"the lowest Klipper's own calibration proposes for {s.name} "
                         "(Klipper runs it; mind the max_accel below)")
    for name, p, why in rest:
        warnings.append(why)
        lines.append(f"# not applied: {why}:")
        lines += ["#   " + line for line in entry(_line_axis(name, _AXES["klipper"]), p)]
    accels = [p.max_accel for _, p in taken.values()]
    if accels and math.isfinite(min(accels)):
        lines.append(f"# [printer] max_accel applies to every axis: max_accel: "
                     f"{_accel_text(min(accels))}")
    return lines, warnings


def _marlin(picks):
    def is_classic(p):
        return p.shaper is not None and p.shaper.name == "M593 ZV"
    classic = {n: p for n, p in picks.items() if is_classic(p)}
    ftm = {n: p for n, p in picks.items() if not is_classic(p)}
    # FT Motion replaces the classic stepper path: one configuration uses one of the two, the
    # one most axes picked
    use_ftm = sum(p.shaper is not None for p in ftm.values()) >= len(classic)
    active, inactive = (ftm, classic) if use_ftm else (classic, ftm)
    taken, rest, warnings = _assign("marlin", active, _AXES["marlin"])
    names = {True: "FT Motion (M493)", False: "classic input shaping (M593)"}
    for name, p in inactive.items():
        if p.shaper is None:
            warnings.append(f"axis {name}: no marlin shaper suits it (nothing written)")
        else:
            rest.append((name, p, f"axis {name}: {p.shaper.name} is {names[not use_ftm]}, "
                                  f"the other axes use {names[use_ftm]}, and Marlin shapes "
                                  "with one of the two at a time"))

    def line(axis, p):
        s = p.shaper
        if s.name == "M593 ZV":
            return f"M593 {axis.upper()} F{_num(p.freq)} D{_num(p.damping)}"
        q = f" Q{defs.EI_TOLERANCE:g}" if s.name in ("EI", "2HEI", "3HEI") else ""
        return (f"M493 {axis.upper()} C{defs.MARLIN_FTM_CODES[s.name]} A{_num(p.freq)} "
                f"I{_num(p.damping)}{q} ; {s.name}")
    if use_ftm:
        lines = ["; Marlin Fixed-Time Motion input shaping (M493, FT Motion version 2),",
                 "; shapers as defined in src/module/ft_motion/shaping.cpp"]
        lines += ["M493 S1"] if taken else []
    else:
        lines = ["; Marlin input shaping (M593, ZV; src/module/stepper.cpp); with FT_MOTION",
                 "; built, it runs while Fixed-Time Motion is off (M493 S0)"]
    for axis, (name, p) in taken.items():
        lines.append(line(axis, p))
        if p.shaper.name == "M593 ZV":
            lines.append(f";   needs SHAPING_MIN_FREQ <= {_num(p.freq)} in Configuration_adv.h")
    return _gcode_rest(lines, warnings, taken, rest, line, "marlin", "; M500 stores the settings")


def _rrf_line(p):
    s = p.shaper
    if s.name != "custom":
        return f'M593 P"{s.name}" F{_num(p.freq)} S{_num(p.damping)}'
    A, t = s.impulses(p.freq, p.damping)
    h = ":".join(f"{a:.6g}" for a in A[:-1])
    return f'M593 P"custom" H{h} T' + ":".join(f"{x:.7g}" for x in t[1:])


def _rrf(picks):
    lines = ['; RepRapFirmware input shaping (config.g), shapers as defined in',
             '; src/Movement/AxisShaper.cpp: one shaper for all axes']
    warnings, active = [], None
    for name, p in picks.items():
        if p.shaper is None:
            warnings.append(f"axis {name}: no rrf shaper suits it (nothing written)")
            continue
        problem = _limits_problem(p)
        same = active is not None and _rrf_line(p) == _rrf_line(active[1])
        if problem:
            why = f"axis {name}: {problem}"
        elif active is None or same:
            if active is None:
                active = (name, p)
                lines.append(_rrf_line(p) + f" ; for {name}")
            else:
                lines.append(f"; axis {name} takes the same shaper")
            continue
        else:
            why = (f"axis {name}: RepRapFirmware has one input shaper for all axes and it is "
                   f"set for {active[0]}")
        warnings.append(why)
        lines += [f"; not applied: {why}:", "; " + _rrf_line(p)]
    if active is not None and math.isfinite(active[1].max_accel):
        x = _accel_text(active[1].max_accel)
        lines.append(f"; to limit acceleration as suggested (the shaper acts on every axis): "
                     f"M201 X{x} Y{x}")
    return lines, warnings


def _prusa(picks):
    taken, rest, warnings = _assign("prusa", picks, _AXES["prusa"])

    def line(axis, p):
        s = p.shaper
        r = f" R{1 / defs.EI_TOLERANCE:g}" if s.name.startswith("EI") else ""
        return (f"M593 {axis.upper()} T{defs.PRUSA_CODES[s.name]} F{_num(p.freq)} "
                f"D{_num(p.damping)}{r} ; {s.name}")
    lines = ["; Prusa input shaping (M593), shapers as defined in",
             "; lib/Marlin/Marlin/src/feature/input_shaper/input_shaper.cpp"]
    for axis, (name, p) in taken.items():
        lines.append(line(axis, p))
    return _gcode_rest(lines, warnings, taken, rest, line, "prusa", "; M593 W stores the settings")


_WRITERS = {"klipper": _klipper, "marlin": _marlin, "rrf": _rrf, "prusa": _prusa}
