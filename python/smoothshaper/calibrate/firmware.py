# SPDX-License-Identifier: Apache-2.0
"""What 3-D printer firmware runs: its own input shaper definitions, the maximum acceleration
their smoothing allows, and its configuration lines (``smoothshaper calibrate --firmware``).

>>> from smoothshaper.calibrate import firmware
>>> ei = firmware.by_name("klipper", "ei")
>>> A, t = ei.impulses(50.0, 0.1)            # Klipper's own EI, amplitudes summing to 1
>>> round(firmware.max_accel(A, t))          # Klipper's rule: smoothing <= 0.12 mm
4552

Each firmware's shapers are re-derived from its source (:mod:`.firmware_defs` cites project,
file and commit); where a firmware differs from the papers or from this library (Klipper's
fitted EI family, Marlin's MZV damping and 1 ms time grid, RepRapFirmware's reversed MZV),
the firmware's formula is what is implemented, since it is what the printer runs.
docs/calibrate.md, "Firmware shaper definitions", tabulates them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Mapping, NamedTuple

import numpy as np

from .._checks import choice, finite, finite_signal, integer, nonnegative, positive, real
from ..errors import ParameterError
from . import firmware_config as _config
from . import firmware_defs as defs

__all__ = ["FIRMWARES", "FirmwareShaper", "Pick", "ConfigText", "shapers", "by_name", "rrf_si",
           "klipper_mzv", "klipper_ei", "rrf_custom", "max_accel", "config_text",
           "TARGET_SMOOTHING", "SCV"]

FIRMWARES = ("klipper", "marlin", "rrf", "prusa", "none")
#: Klipper's find_shaper_max_accel: the smoothing [mm] a suggested max_accel may cause, and the
#: square_corner_velocity [mm/s] it assumes (shaper_calibrate.py).
TARGET_SMOOTHING = _config.TARGET_SMOOTHING
SCV = _config.SCV


@dataclass(frozen=True)
class FirmwareShaper:
    """One input shaper as a firmware defines it.

    Attributes
    ----------
    firmware : str
        One of :data:`FIRMWARES` (not ``"none"``).
    name : str
        The firmware's own name (Klipper ``shaper_type``, Marlin ``M493`` mode name or
        ``"M593 ZV"`` for classic input shaping, RepRapFirmware ``M593 P`` name, Prusa ``M593 T``
        type name).
    min_freq, max_freq : float
        Frequencies the firmware accepts for it [Hz] (inclusive; a frequency must also be > 0).
    damping_limits : (float, float)
        The damping ratios the firmware accepts (inclusive); see :meth:`damping_range`.
    formula : callable
        ``formula(freq, damping) -> (amplitudes, times)``, the firmware's equations
        (:mod:`.firmware_defs`), before normalisation.
    suggested_min_freq : float or None
        Klipper only: the lowest frequency its own calibration proposes (shaper_defs.py
        ``min_freq``, "chosen to have projected max_accel ~= 1500"); the firmware runs lower ones.
    source : str
        Project, file and commit of the definition.
    """
    firmware: str
    name: str
    min_freq: float
    max_freq: float
    damping_limits: tuple = field(default=(0.0, defs.BELOW_ONE), repr=False)
    formula: Callable = field(default=None, repr=False, compare=False)
    suggested_min_freq: float | None = None
    source: str = ""

    def damping_range(self) -> tuple[float, float]:
        """The damping ratios the firmware accepts for this shaper.

        Returns
        -------
        (float, float)
            (lo, hi), inclusive. Klipper caps EI at 0.4, 2-hump EI at 0.3, 3-hump EI at 0.2
            (max_damping_ratio), the others at 0.99; Marlin's M493 takes 0.01 to below 1, its
            M593 0 to 1; RepRapFirmware 0 to 0.99 (ei2 / ei3: 0.4 / 0.3, where their fitted
            coefficients stay a valid sequence); Prusa 0 to below 1.
        """
        return self.damping_limits

    def impulses(self, freq, damping) -> tuple[np.ndarray, np.ndarray]:
        """The firmware's impulse sequence for a shaper tuned to ``freq`` and ``damping``.

        Parameters
        ----------
        freq : float
            Shaper frequency [Hz], as the firmware's configuration takes it.
        damping : float
            Damping ratio, as the firmware's configuration takes it.

        Returns
        -------
        A : ndarray, shape (n,)
            Amplitudes, summing to 1 (every firmware normalises them before use).
        t : ndarray, shape (n,)
            Times [s], ``t[0] = 0``, non-decreasing; on the firmware's time grid where it has
            one (Marlin FT Motion: whole 1 ms samples; RepRapFirmware: whole step clocks).

        Raises
        ------
        ParameterError
            ``freq`` unless a finite number in [min_freq, max_freq] and > 0; ``damping``
            unless a finite number in :meth:`damping_range`.
        """
        f = positive("freq", freq)
        if not self.min_freq <= f <= self.max_freq:
            raise ParameterError("freq", f"freq must be in [{self.min_freq:g}, "
                                 f"{self.max_freq:g}] Hz for {self.firmware} {self.name}, "
                                 f"got {f!r}")
        z = finite("damping", damping)
        lo, hi = self.damping_limits
        if not lo <= z <= hi:
            raise ParameterError("damping", f"damping must be in [{lo:g}, {hi:.6g}] for "
                                 f"{self.firmware} {self.name}, got {z!r}")
        a, t = self.formula(f, z)
        A = np.asarray(a, dtype=np.float64)
        return A / A.sum(), np.asarray(t, dtype=np.float64)


def _build(firmware, table, source, suggested=False):
    return tuple(FirmwareShaper(firmware, name, lo if not suggested else 0.0, hi, damp, func,
                                lo if suggested else None, source)
                 for name, func, lo, hi, damp in table)


_SHAPERS = {
    "klipper": _build("klipper", defs.KLIPPER, "Klipper3d/klipper klippy/extras/shaper_defs.py "
                      "(84104bb, 2026-08-07)", suggested=True),
    "marlin": _build("marlin", defs.MARLIN, "MarlinFirmware/Marlin src/module/ft_motion/"
                     "shaping.cpp and src/module/stepper.cpp (bugfix-2.1.x, 2025)"),
    "rrf": _build("rrf", defs.RRF, "Duet3D/RepRapFirmware src/Movement/AxisShaper.cpp "
                  "(3.6-dev, 8875b7e, 2024-10-24)"),
    "prusa": _build("prusa", defs.PRUSA, "prusa3d/Prusa-Firmware-Buddy lib/Marlin/Marlin/src/"
                    "feature/input_shaper/input_shaper.cpp (818d812, 2025-03-28)"),
    "none": (),
}


def _firmware(firmware) -> str:
    return choice("firmware", firmware, FIRMWARES)


def shapers(firmware: str) -> tuple[FirmwareShaper, ...]:
    """Every shaper ``firmware`` runs, under its own name.

    RepRapFirmware's user-defined ``custom`` shaper is not listed (it has no formula of its
    own): :func:`rrf_custom` makes one from any impulse sequence of at most 5 impulses.

    Parameters
    ----------
    firmware : {"klipper", "marlin", "rrf", "prusa", "none"}
        Case-insensitive.

    Returns
    -------
    tuple of FirmwareShaper
        Its shapers; ``()`` for ``"none"``, meaning no firmware restriction: every family and
        chain of the library.

    Raises
    ------
    ParameterError
        ``firmware`` unless one of :data:`FIRMWARES` (case-insensitive).
    """
    return _SHAPERS[_firmware(firmware)]


def by_name(firmware: str, name: str) -> FirmwareShaper:
    """The shaper ``firmware`` calls ``name``.

    Parameters
    ----------
    firmware : {"klipper", "marlin", "rrf", "prusa"}
        Case-insensitive.
    name : str
        The firmware's name of the shaper (:attr:`FirmwareShaper.name`), case-insensitive.

    Returns
    -------
    FirmwareShaper

    Raises
    ------
    ParameterError
        Naming ``firmware`` or ``name`` when unknown.
    """
    options = {s.name.lower(): s for s in shapers(firmware)}
    if not isinstance(name, str) or name.strip().lower() not in options:
        known = ", ".join(s.name for s in options.values())
        raise ParameterError("name", f"name must be one of {known} for {_firmware(firmware)}, "
                             f"got {name!r}")
    return options[name.strip().lower()]


def _plain(x: float) -> str:
    """x with at most 6 decimals and no exponent: Klipper reads shaper arguments as [0-9.]+."""
    return f"{x:.6f}".rstrip("0").rstrip(".")


def klipper_mzv(n, t) -> FirmwareShaper:
    """Klipper's generalised MZV, ``shaper_type: mzv(n=N, t=T)`` (shaper_defs.py
    get_mzv_shaper, since 2026-03; this library's ``gmzv`` with ``order`` n and ``duration`` t).

    Parameters
    ----------
    n : int
        Number of impulses, >= 3.
    t : float
        Duration in damped periods, 0 < t < (n - 1)/2; ``mzv(n=3, t=0.75)`` is the plain mzv.

    Returns
    -------
    FirmwareShaper
        Named ``"mzv(n=N, t=T)"``, as Klipper's configuration takes it; damping 0 to 0.99,
        suggested minimum 23 Hz (Klipper's mzv entry).

    Raises
    ------
    ParameterError
        ``n`` or ``t`` where Klipper refuses them (n < 3, t >= (n-1)/2, or amplitudes that come
        out negative).
    """
    nn = integer("n", n, minimum=3)
    tt = float(_plain(positive("t", t)))     # the t written is the t modelled
    try:
        formula = defs.klipper_gmzv(nn, tt)
    except ValueError as exc:
        raise ParameterError("t", f"t: Klipper refuses mzv(n={nn}, t={tt:g}): {exc}") from None
    base = by_name("klipper", "mzv")
    return FirmwareShaper("klipper", f"mzv(n={nn}, t={_plain(tt)})", 0.0, math.inf,
                          base.damping_limits, formula, base.suggested_min_freq, base.source)


def klipper_ei(v_tol) -> FirmwareShaper:
    """Klipper's EI with its own vibration tolerance, ``shaper_type: ei(v_tol=V)``
    (get_ei_shaper's fitted polynomials in V and the damping ratio).

    Parameters
    ----------
    v_tol : float
        Vibration tolerance, 0 < v_tol < 1 (Klipper's default 0.05 is :func:`by_name`'s ei).

    Returns
    -------
    FirmwareShaper
        Named ``"ei(v_tol=V)"``; damping 0 to 0.4, suggested minimum 29 Hz.

    Raises
    ------
    ParameterError
        ``v_tol`` unless in (0, 1).
    """
    v = positive("v_tol", v_tol)
    if not v < 1:
        raise ParameterError("v_tol", f"v_tol must be in (0, 1), got {v!r}")
    v = float(_plain(v))
    if v == 0:
        raise ParameterError("v_tol", f"v_tol must be at least 1e-6 (it is written with 6 "
                             f"decimals), got {v_tol!r}")
    base = by_name("klipper", "ei")
    return FirmwareShaper("klipper", f"ei(v_tol={_plain(v)})", 0.0, math.inf, base.damping_limits,
                          lambda f, z: defs.klipper_ei(f, z, v), base.suggested_min_freq,
                          base.source)


def rrf_custom(A, t=None) -> FirmwareShaper:
    """RepRapFirmware's ``M593 P"custom"`` shaper for a given impulse sequence.

    Parameters
    ----------
    A : array_like, shape (n,)
        Amplitudes, 2 <= n <= 5 (the firmware's MaxImpulses), any scale with a positive sum.
    t : array_like, shape (n,), optional
        Times [s], ``t[0] = 0``, increasing. Without it the impulses fall at multiples of half
        the damped period of the frequency and damping passed to
        :meth:`FirmwareShaper.impulses`, as the firmware places them without ``T``.

    Returns
    -------
    FirmwareShaper
        Named ``"custom"``; its impulses are ``A`` normalised to sum 1, at ``t`` rounded to
        step clocks; :func:`config_text` writes ``M593 P"custom" H.. T..``.

    Raises
    ------
    ParameterError
        ``A`` unless 2 to 5 finite amplitudes with a positive sum; ``t`` unless as many finite
        times as ``A``, starting at 0 and increasing.
    """
    a = finite_signal("A", A)
    if not 2 <= a.size <= 5 or not a.sum() > 0:
        raise ParameterError("A", f"A must be 2 to 5 amplitudes with a positive sum (the "
                             f"firmware's MaxImpulses is 5), got {a.size} summing to {a.sum():g}")
    a = a / a.sum()
    delays = None
    if t is not None:
        tt = finite_signal("t", t)
        if tt.size != a.size or tt[0] != 0 or np.any(np.diff(tt) <= 0):
            raise ParameterError("t", f"t must be {a.size} increasing times starting at 0, "
                                 f"got {tt.tolist()}")
        delays = tt[1:].tolist()
    lo, hi = defs.RRF_MIN_FREQ, 1000.0
    return FirmwareShaper("rrf", "custom", lo, hi, (0.0, 0.99),
                          defs.rrf_custom(a[:-1].tolist(), delays),
                          source=_SHAPERS["rrf"][0].source)


def rrf_si(order: int, duration: float) -> FirmwareShaper:
    """A specified-insensitivity shaper (Singhose, Seering and Singer 1996; the library's
    ``si`` kind) as RepRapFirmware runs it: its user-defined ``M593 P"custom"`` shaper with the
    SI impulses of the configured frequency and damping, delays in whole step clocks and the
    last amplitude ``1 - sum`` of the others (as :func:`rrf_custom`).

    Parameters
    ----------
    order : {3, 5}
        Number of impulses (the firmware runs at most 5).
    duration : float
        Span in damped periods, in [(order - 1)/4, (order - 1)/2].

    Returns
    -------
    FirmwareShaper
        Named ``"custom"`` (:func:`config_text` writes ``M593 P"custom" H.. T..``).

    Raises
    ------
    ParameterError
        ``order`` unless 3 or 5, ``duration`` out of its range.
    """
    from ..reference.shapers import impulses_unchecked
    from ..stages import Stage
    n = integer("order", order)
    if n not in (3, 5):
        raise ParameterError("order", f"order must be 3 or 5 for RepRapFirmware's custom shaper "
                             f"(at most 5 impulses, si takes odd counts), got {order!r}")
    Stage("si", wn=1.0, order=n, duration=duration)          # validates the span

    def formula(f, zeta):
        A, t = impulses_unchecked(Stage("si", wn=2 * math.pi * f, zeta=zeta, order=n,
                                        duration=float(duration)))
        A = np.asarray(A, float) / float(np.sum(A))
        return defs.rrf_custom(A[:-1].tolist(), np.asarray(t, float)[1:].tolist())(f, zeta)
    return FirmwareShaper("rrf", "custom", defs.RRF_MIN_FREQ, 1000.0, (0.0, 0.99), formula,
                          source=_SHAPERS["rrf"][0].source + "; M593 P\"custom\" with the "
                          "specified-insensitivity impulses")


def _smoothing_terms(A, t, scv):
    """Klipper's _get_shaper_smoothing is max(c90 + accel k90, accel k180): returns the three."""
    D = A.sum()
    ts = float(np.dot(A, t)) / D
    dt = t - ts
    # impulses at one time: ts carries rounding, not spread (else a 1e35 mm/s^2 "limit")
    dt[np.abs(dt) <= 8 * np.finfo(float).eps * np.abs(t).max()] = 0.0
    late = t >= ts
    c90 = math.sqrt(2.0) * scv * float(np.sum(A[late] * dt[late])) / D
    k90 = math.sqrt(2.0) * 0.5 * float(np.sum(A[late] * dt[late] ** 2)) / D
    k180 = 0.5 * float(np.sum(A * dt * dt)) / D
    return c90, k90, k180


def max_accel(A, t, *, scv=SCV, target_smoothing=TARGET_SMOOTHING) -> float:
    """The largest acceleration [mm/s^2] whose smoothing stays within ``target_smoothing``:
    Klipper's suggested ``max_accel`` (shaper_calibrate.py ``find_shaper_max_accel``), in
    closed form for any impulse sequence.

    Rule: with D = sum(A), the shift ts = sum(A t) / D and accel a, Klipper's smoothing is
    ``max(sqrt(2) / D * sum over t_i >= ts of A_i (scv + a/2 (t_i - ts)) (t_i - ts),
    1 / D * sum of A_i a/2 (t_i - ts)^2)`` [mm] (the corner offsets of a 90 and a 180 degree
    turn), affine in a; the suggestion is the largest a keeping it <= ``target_smoothing``
    (0.12 mm at scv = 5 mm/s by default, as in Klipper), 0 if the scv term alone exceeds it,
    and inf for a sequence without spread (a single impulse). Klipper bisects to 1e-8 mm/s^2;
    this is the exact root.

    Parameters
    ----------
    A, t : array_like, shape (n,)
        Amplitudes (any scale, positive sum) and times [s].
    scv : float, keyword-only
        Square corner velocity [mm/s], >= 0.
    target_smoothing : float, keyword-only
        Smoothing allowed [mm], > 0.

    Returns
    -------
    float
        The suggested maximum acceleration [mm/s^2], >= 0, or inf.

    Raises
    ------
    ParameterError
        ``A`` or ``t`` unless finite, one-dimensional, of one length >= 1, ``sum(A) > 0``;
        ``scv``, ``target_smoothing`` when out of range.
    """
    a = finite_signal("A", A)
    tt = finite_signal("t", t)
    if a.size == 0:
        raise ParameterError("A", "A must hold at least one amplitude")
    if tt.size != a.size:
        raise ParameterError("t", f"t must have as many times as A has amplitudes ({a.size}), "
                             f"got {tt.size}")
    if not a.sum() > 0:
        raise ParameterError("A", f"A must have a positive sum, got {a.sum():g}")
    v = nonnegative("scv", scv)
    target = positive("target_smoothing", target_smoothing)
    c90, k90, k180 = _smoothing_terms(a, tt, v)
    if c90 > target:
        return 0.0
    a90 = (target - c90) / k90 if k90 > 0 else math.inf
    a180 = target / k180 if k180 > 0 else math.inf
    return max(0.0, min(a90, a180))


class Pick(NamedTuple):
    """One axis's choice: a firmware shaper (None if nothing the firmware runs suits the
    axis), its frequency [Hz] and damping ratio, and the suggested max acceleration [mm/s^2]."""
    shaper: FirmwareShaper | None
    freq: float
    damping: float
    max_accel: float


class ConfigText(str):
    """The configuration text; ``warnings`` lists (as plain sentences) every pick the firmware
    cannot express as given, each also written into the text as a comment."""
    warnings: tuple[str, ...]

    def __new__(cls, text: str, warnings=()):
        obj = super().__new__(cls, text)
        obj.warnings = tuple(warnings)
        return obj


def _check_pick(firmware, axis, pick):
    if not isinstance(axis, str) or not axis.strip():
        raise ParameterError("picks", f"picks must map axis names (text) to picks, got key "
                             f"{axis!r}")
    try:
        shaper, freq, damping, accel = pick
    except (TypeError, ValueError):
        raise ParameterError(f"picks[{axis}]", f"picks[{axis}] must be (shaper, freq, damping, "
                             f"max_accel), got {pick!r}") from None
    if shaper is not None:
        if not isinstance(shaper, FirmwareShaper):
            raise ParameterError(f"picks[{axis}].shaper", f"picks[{axis}].shaper must be a "
                                 f"FirmwareShaper or None, got {type(shaper).__name__}")
        if shaper.firmware != firmware:
            raise ParameterError(f"picks[{axis}].shaper", f"picks[{axis}].shaper is "
                                 f"{shaper.firmware}'s {shaper.name}, not {firmware}'s")
    freq = positive(f"picks[{axis}].freq", freq)
    damping = nonnegative(f"picks[{axis}].damping", damping)
    accel = real(f"picks[{axis}].max_accel", accel)
    if not accel >= 0:      # inf: no limit from smoothing (a pick without spread)
        raise ParameterError(f"picks[{axis}].max_accel", f"picks[{axis}].max_accel must be "
                             f">= 0 (inf allowed), got {accel!r}")
    return Pick(shaper, freq, damping, accel)


def config_text(firmware: str, picks: Mapping[str, Pick]) -> ConfigText:
    """The firmware's configuration lines for every analysed axis.

    Parameters
    ----------
    firmware : {"klipper", "marlin", "rrf", "prusa"}
        ``"none"`` has no configuration lines and is refused.
    picks : mapping of str to Pick
        Axis name (``"x"``, ``"accel_y"``, ``"file.csv:x"``, ...) to its :class:`Pick`.

    Returns
    -------
    ConfigText
        A ``str``: Klipper's ``[input_shaper]`` section, Marlin's ``M493`` (FT Motion) or
        ``M593`` (classic) lines, RepRapFirmware's ``M593 P"name" F.. S..``, Prusa's
        ``M593 X T.. F.. D..``; each axis's suggested max acceleration as a comment. A pick the
        firmware cannot express as given (an axis it has no shaper for, two picks for one
        axis, different picks where it has one shaper for all axes, a frequency or damping it
        refuses or clamps, no shaper at all) is written as a comment saying why, never
        dropped, and listed in ``.warnings``.

    Raises
    ------
    ParameterError
        ``firmware`` unless one of the four; ``picks`` unless a non-empty mapping of text to
        (FirmwareShaper of that firmware or None, freq > 0, damping >= 0, max_accel >= 0).
    """
    fw = _firmware(firmware)
    if fw == "none":
        raise ParameterError("firmware", "firmware 'none' has no configuration lines: choose "
                             "klipper, marlin, rrf or prusa")
    if not isinstance(picks, Mapping) or not picks:
        raise ParameterError("picks", "picks must be a non-empty mapping of axis name to Pick")
    checked = {axis: _check_pick(fw, axis, p) for axis, p in picks.items()}
    lines, warnings = _config.lines(fw, checked)
    return ConfigText("\n".join(lines) + "\n", warnings)
