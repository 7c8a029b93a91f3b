# SPDX-License-Identifier: Apache-2.0
"""Plain stage descriptions shared by the C-backed filters and the NumPy reference.

A :class:`Stage` is data only, like the C ``sms_stage_config``: it holds the physical
parameters of one stage and validates everything that does not depend on the sample period.
Checks that need ``Ts`` (``T >= Ts``, a mode below Nyquist) happen where ``Ts`` is known.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, fields, replace

from ._checks import choice as _choice, finite as _finite, integer as _integer, show as _show
from .errors import ParameterError

__all__ = ["KINDS", "SMOOTHERS", "SHAPERS", "NOTCHES", "INPUT_SMOOTHERS", "TIMINGS",
           "MAX_ZVN_ORDER", "MAX_IMPULSES", "SMOOTH_ZETA_MAX", "Stage", "kind_name", "rectangular",
           "harmonic", "damped_harmonic", "exponential", "shaper", "notch", "input_smoother",
           "impulse_shaper", "for_mode"]

#: Stage kinds, in the order of the C enumeration ``sms_kind`` (index == C value).
KINDS = (
    "rectangular", "harmonic", "damped_harmonic", "exponential",
    "zv", "zvd", "zvdd", "zvn", "ei", "ei2", "mzv",
    "notch_tustin", "notch_matched", "ei3", "gmzv",
    "smooth_zv", "smooth_mzv", "smooth_ei", "smooth_ei2", "smooth_zvd_ei", "smooth_si",
    "si", "impulses",
)
#: The smoothers of duration T (the trajectory smoothers of docs/filters.md).
SMOOTHERS = KINDS[:4]
#: Impulse shapers: a few impulses (si: specified insensitivity; impulses: user-defined).
SHAPERS = KINDS[4:11] + KINDS[13:15] + KINDS[21:23]
NOTCHES = KINDS[11:13]
#: The input smoothers of Klipper-derived firmware: polynomial kernels for a mode, every
#: sample a tap (docs/filters.md).
INPUT_SMOOTHERS = KINDS[15:21]
TIMINGS = ("exact", "paper", "bounded")
MAX_ZVN_ORDER = 8
#: Most impulses of a shaper design (ZV^8; the generalised MZV takes 3..MAX_IMPULSES, and so
#: many user-defined impulses at most).
MAX_IMPULSES = MAX_ZVN_ORDER + 1
#: Largest zeta of the smooth_zv, smooth_mzv and smooth_ei kernels (their cubic fits in zeta).
SMOOTH_ZETA_MAX = 0.25
#: The input smoothers whose kernel depends on zeta.
_SMOOTH_READS_ZETA = ("smooth_zv", "smooth_mzv", "smooth_ei")


# slots: a Stage is built once per design.kinematic call in online planning; without them,
# storing its fields in an instance dict and freeing that dict took about a third of the
# call in a profile (_kinematic_fastpath.c writes the slots directly).
@dataclass(frozen=True, slots=True)
class Stage:
    """One stage of a chain: the physical parameters of a filter, validated on construction.

    Data only, like the C ``sms_stage_config`` (``c/include/smoothshaper/config.h``); checks
    that need the sample period (``T >= Ts``, a mode below Nyquist) happen where ``Ts`` is
    known. The families and their sources are in docs/filters.md and docs/references.md.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS` (any case on input; ``"notch"`` means ``"notch_matched"``).
    T : float
        Smoothers: duration [s], > 0.
    sigma : float
        Damped smoothers: decay rate [1/s], <= 0.
    k : int
        Smoothers: the multiple of the zero pinned by exact timing (>= 1; odd for the
        harmonic families).
    wn : float
        Shapers and notches: natural frequency of the mode [rad/s], > 0.
    zeta : float
        Shapers and notches: damping ratio of the mode, in [0, 1).
    order : int or None
        n of ZV^n (1..8), number of impulses of gmzv (3..9); None means 1 (3 for gmzv).
    tolerance : float
        Vibration tolerance V of ei, ei2, ei3, in (0, 1) (default 0.05).
    notch_pole_zeta : float
        Damping of the notch's poles, > ``zeta`` (default 0.7).
    timing : {"exact", "paper", "bounded"}
        Discretisation of smoothers and shapers (docs/exact-mode.md); ``"bounded"`` (the
        rectangular and exponential smoothers only) pins the zero like ``"exact"`` with one
        more tap, none above the continuous response's peak density times ``Ts``.
    duration : float
        Span of gmzv in damped periods, in (0, (order - 1)/2) (0.75 with order 3 is MZV); of
        si in [(order - 1)/4, (order - 1)/2].
    amplitudes : tuple of float
        impulses: the impulse amplitudes (1 to :data:`MAX_IMPULSES`, finite, positive sum;
        normalised to sum 1 where the filter is built). Empty for every other kind.
    times : tuple of float
        impulses: the impulse times [s], as many as ``amplitudes``, >= 0, strictly increasing.

    Raises
    ------
    ParameterError
        Naming the field that is out of range, not finite, complex, boolean or not numeric.
    """

    kind: str
    T: float = 0.0
    sigma: float = 0.0
    k: int = 1
    wn: float = 0.0
    zeta: float = 0.0
    order: int | None = None
    tolerance: float = 0.05
    notch_pole_zeta: float = 0.7
    timing: str = "exact"
    duration: float = 0.75
    amplitudes: tuple = ()
    times: tuple = ()

    def __post_init__(self):
        object.__setattr__(self, "kind", kind_name(self.kind))
        object.__setattr__(self, "timing", _choice("timing", self.timing, TIMINGS))
        if self.kind == "impulses":
            _check_impulses(self)
        elif self.amplitudes or self.times:
            raise ParameterError(
                "amplitudes", f"amplitudes and times are for kind='impulses', got "
                f"kind={self.kind!r}")
        if self.order is None:
            object.__setattr__(self, "order", 3 if self.kind in ("gmzv", "si") else 1)
        for name in ("T", "sigma", "wn", "zeta", "tolerance", "notch_pole_zeta", "duration"):
            object.__setattr__(self, name, _finite(name, getattr(self, name)))
        object.__setattr__(self, "k", _integer("k", self.k, 1))
        object.__setattr__(self, "order", _integer("order", self.order))
        if self.timing == "bounded" and self.kind not in ("rectangular", "exponential"):
            raise ParameterError(
                "timing", f"timing='bounded' is for the rectangular and exponential smoothers "
                f"(a half sine peaks mid-window; shapers and notches have no such taps), got "
                f"kind={self.kind!r}")
        if self.timing == "paper" and self.kind in INPUT_SMOOTHERS:
            raise ParameterError(
                "timing", f"timing='paper' does not exist for {self.kind}: an input smoother is "
                "a continuous kernel, realised one way (timing='exact')")
        if self.kind == "impulses":
            pass                        # no mode: wn and zeta are not read
        elif self.kind in SMOOTHERS:
            if self.T <= 0:
                raise ParameterError("T", f"T must be > 0 s, got {self.T!r}")
            if self.sigma > 0:
                raise ParameterError(
                    "sigma", f"sigma must be <= 0 1/s (a decaying mode), got {self.sigma!r}")
            _check_odd(self.kind, self.k)
        else:
            if self.wn <= 0:
                raise ParameterError("wn", f"wn must be > 0 rad/s, got {self.wn!r}")
            if not 0.0 <= self.zeta < 1.0:
                raise ParameterError("zeta", f"zeta must be in [0, 1), got {self.zeta!r}")
            if self.kind in _SMOOTH_READS_ZETA and self.zeta > SMOOTH_ZETA_MAX:
                raise ParameterError(
                    "zeta", f"zeta must be in [0, {SMOOTH_ZETA_MAX}] for {self.kind} (the range "
                    f"of its kernel's fit in zeta), got {self.zeta!r}")
        if self.kind == "zvn" and not 1 <= self.order <= MAX_ZVN_ORDER:
            raise ParameterError(
                "order", f"order must be in 1..{MAX_ZVN_ORDER} for zvn, got {self.order!r}")
        if self.kind == "si":
            _check_si(self.order, self.duration)
        if self.kind in ("ei", "ei2", "ei3", "si") and not 0.0 < self.tolerance < 1.0:
            raise ParameterError(
                "tolerance", f"tolerance must be in (0, 1), got {self.tolerance!r}")
        if self.kind == "gmzv":
            if not 3 <= self.order <= MAX_IMPULSES:
                raise ParameterError(
                    "order", f"order (number of impulses) must be in 3..{MAX_IMPULSES} for "
                    f"gmzv, got {self.order!r}")
            if not 0.0 < self.duration < 0.5 * (self.order - 1):
                raise ParameterError(
                    "duration", f"duration must be in (0, {0.5 * (self.order - 1)!r}) damped "
                    f"periods for gmzv with order {self.order}, got {self.duration!r}")
        if self.kind in NOTCHES and not self.notch_pole_zeta > self.zeta:
            raise ParameterError(
                "notch_pole_zeta", f"notch_pole_zeta must be > zeta ({self.zeta!r}), "
                f"got {self.notch_pole_zeta!r}")

    @property
    def kind_index(self) -> int:
        """The C ``sms_kind`` value."""
        return KINDS.index(self.kind)

    def with_(self, **changes) -> "Stage":
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            Field names and new values (see the class attributes).

        Returns
        -------
        Stage
            The new stage; this one is unchanged.

        Raises
        ------
        ParameterError
            A new value is out of range (naming the field).
        TypeError
            A name is not a field.
        """
        return replace(self, **changes)


def _check_si(order: int, duration: float) -> None:
    if order not in (3, 5, 7, 9):
        raise ParameterError(
            "order", f"order (number of impulses) must be 3, 5, 7 or 9 for si, got {order!r}")
    d = (order - 1) / 2
    if not 0.5 * d <= duration <= d:
        raise ParameterError(
            "duration", f"duration must be in [{0.5 * d!r}, {d!r}] damped periods for si with "
            f"order {order}, got {duration!r}")


def _check_impulses(stage: "Stage") -> None:
    """Validate and store the impulses of an ``impulses`` stage as tuples of floats (order
    set to their count)."""
    if isinstance(stage.amplitudes, (str, bytes)) or isinstance(stage.times, (str, bytes)):
        raise ParameterError("amplitudes", "amplitudes and times must be sequences of numbers")
    try:
        amps, times = list(stage.amplitudes), list(stage.times)
    except TypeError:
        raise ParameterError(
            "amplitudes", f"amplitudes and times must be sequences of numbers, got "
            f"{_show(stage.amplitudes)} and {_show(stage.times)}") from None
    if not 1 <= len(amps) <= MAX_IMPULSES:
        raise ParameterError(
            "amplitudes", f"amplitudes: 1 to {MAX_IMPULSES} impulses, got {len(amps)}")
    if len(times) != len(amps):
        raise ParameterError(
            "times", f"times must have as many entries as amplitudes ({len(amps)}), got "
            f"{len(times)}")
    amps = tuple(_finite(f"amplitudes[{i}]", a) for i, a in enumerate(amps))
    times = tuple(_finite(f"times[{i}]", t) for i, t in enumerate(times))
    total = math.fsum(amps)
    if not total > 0 or not math.isfinite(total):
        raise ParameterError("amplitudes", f"amplitudes must sum to > 0, got sum {total!r}")
    for i, t in enumerate(times):
        if t < 0 or (i and not t > times[i - 1]):
            raise ParameterError(
                f"times[{i}]", f"times[{i}] must be >= 0 and above times[{i - 1}]" if i else
                f"times[0] must be >= 0, got {t!r}")
    if stage.order is not None and _integer("order", stage.order) != len(amps):
        raise ParameterError(
            "order", f"order must be the number of impulses ({len(amps)}) for impulses, got "
            f"{stage.order!r}")
    object.__setattr__(stage, "amplitudes", amps)
    object.__setattr__(stage, "times", times)
    object.__setattr__(stage, "order", len(amps))


class _UncheckedStage:
    """A blank with Stage's slots and no frozen-field guard, for building a Stage from values
    that are already valid (the C design's) without :meth:`Stage.__post_init__`.

    Set every field by plain assignment (a slot has no class-level default), then
    ``obj.__class__ = Stage`` (Python allows this between classes with the same slots). The
    result equals the validated Stage (``==``, hash, repr, pickle, every field).
    :func:`_unchecked_stage` builds one (design.kinematic's checked path; its fast path,
    ``_kinematic_fastpath.c``, builds the same objects in C)."""

    __slots__ = tuple(f.name for f in fields(Stage))


#: Stage's field defaults, in field order (what _unchecked_stage starts from).
_STAGE_DEFAULTS = tuple((f.name, f.default) for f in fields(Stage))


def _unchecked_stage(kind: str, T: float, sigma: float = 0.0, k: int = 1,
                     timing: str = "exact") -> Stage:
    """A smoother Stage from valid values (``kind`` canonical, ``T`` > 0 finite float,
    ``sigma`` <= 0 float, ``k`` >= 1 int, odd for the harmonic kinds, ``timing`` one of
    :data:`TIMINGS` that the kind has), not re-validated."""
    s = _UncheckedStage()
    for name, value in _STAGE_DEFAULTS:
        setattr(s, name, value)
    s.kind = kind
    s.T = T
    s.order = 1     # the constructor's None becomes 1 for smoothers
    if sigma:       # -0.0 (an undamped mode's -zeta wn) stays the default 0.0, as in C
        s.sigma = sigma
    s.k = k
    s.timing = timing
    s.__class__ = Stage
    return s


def _checked_mode(wn, zeta) -> tuple[float, float]:
    """A mode's (wn, zeta) as floats, wn > 0 rad/s and 0 <= zeta < 1; ParameterError naming
    the one that is not."""
    wn = _finite("wn", wn)
    zeta = _finite("zeta", zeta)
    if wn <= 0:
        raise ParameterError("wn", f"wn must be > 0 rad/s, got {wn!r}")
    if not 0.0 <= zeta < 1.0:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    return wn, zeta


def _with_mode(stage: Stage, wn, zeta, duration=None) -> Stage:
    """``stage.with_(wn=wn, zeta=zeta[, duration=duration])`` for a validated shaper or input
    smoother ``stage``, checking only the fields that change, as :meth:`Stage.__post_init__`
    checks them (the same ParameterError naming the same field, the same floats; the result
    equals the validated Stage). The calibration's tuning builds thousands of designs of one
    family that differ only in these fields; its kind, order, tolerance and timing were
    checked when ``stage`` was built."""
    kind = stage.kind
    if kind not in SHAPERS[:-1] and kind not in INPUT_SMOOTHERS:
        raise ParameterError("kind", f"_with_mode is for shapers and input smoothers, got "
                             f"kind={kind!r}")
    wn, zeta = _checked_mode(wn, zeta)
    if kind in _SMOOTH_READS_ZETA and zeta > SMOOTH_ZETA_MAX:
        raise ParameterError(
            "zeta", f"zeta must be in [0, {SMOOTH_ZETA_MAX}] for {kind} (the range of its "
            f"kernel's fit in zeta), got {zeta!r}")
    if duration is None:
        duration = stage.duration
    else:
        duration = _finite("duration", duration)
        if kind == "si":
            _check_si(stage.order, duration)
        elif kind == "gmzv" and not 0.0 < duration < 0.5 * (stage.order - 1):
            raise ParameterError(
                "duration", f"duration must be in (0, {0.5 * (stage.order - 1)!r}) damped "
                f"periods for gmzv with order {stage.order}, got {duration!r}")
    s = _UncheckedStage()
    for name, _ in _STAGE_DEFAULTS:
        setattr(s, name, getattr(stage, name))
    s.wn = wn
    s.zeta = zeta
    s.duration = duration
    s.__class__ = Stage
    return s


def kind_name(kind, allowed=KINDS, parameter: str = "kind") -> str:
    """The canonical (lower-case) name of a stage kind.

    Names compare case-insensitively and ``"notch"`` means ``"notch_matched"``.

    Parameters
    ----------
    kind : str
        The name as written by the user.
    allowed : sequence of str
        The kinds accepted here (default :data:`KINDS`).
    parameter : str
        The parameter name an error reports (default ``"kind"``).

    Returns
    -------
    str
        The name as it appears in ``allowed``.

    Raises
    ------
    ParameterError
        Naming ``parameter`` when ``kind`` is not a string among ``allowed``.
    """
    if isinstance(kind, str) and kind.strip().lower() == "notch" and "notch_matched" in allowed:
        return "notch_matched"
    return _choice(parameter, kind, allowed)


def rectangular(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Moving average of duration ``T``: ``m(t) = 1/T`` on ``[0, T)`` (docs/filters.md).

    Its zeros lie at ``2 pi k / T`` [rad/s]; a chain of rectangular stages is the classic
    trapezoidal / double-S planner (Biagiotti and Melchiorri, *Trajectory Planning for
    Automatic Machines and Robots*, 2008).

    Parameters
    ----------
    T : float, keyword-only
        Duration of the impulse response [s], > 0 (and >= Ts where it is run).
    k : int, keyword-only
        Which zero exact timing keeps on the sample grid when ``T`` is not a whole number
        of samples (>= 1, default 1; docs/exact-mode.md).
    timing : {"exact", "paper", "bounded"}, keyword-only
        ``"exact"`` (default): taps adjusted so the pinned zero stays exact for any Ts;
        ``"paper"``: the sampled continuous response, as the papers discretise it;
        ``"bounded"``: the exact zero with one more tap, none above the continuous peak
        density times Ts (for a stage that also bounds a derivative, docs/exact-mode.md).

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``T``, ``k`` or ``timing``.
    """
    return Stage("rectangular", T=T, k=k, timing=timing)


def harmonic(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Harmonic smoother ``s(t) = pi/(2T) sin(pi t / T)`` on ``[0, T]``.

    Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories with
    Trigonometric Blends", 2011, sec. 3.2; zeros at ``3 pi k / T`` for odd k
    (docs/filters.md).

    Parameters
    ----------
    T : float, keyword-only
        Duration of the impulse response [s], > 0 (and >= Ts where it is run).
    k : int, keyword-only
        Which zero exact timing keeps on the sample grid when ``T`` is not a whole number
        of samples (>= 1, default 1; docs/exact-mode.md).
    timing : {"exact", "paper"}, keyword-only
        ``"exact"`` (default): taps adjusted so the pinned zero stays exact for any Ts;
        ``"paper"``: the sampled continuous response, as the papers discretise it.

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``T``, ``k`` (must be odd) or ``timing``.
    """
    return Stage("harmonic", T=T, k=k, timing=timing)


def damped_harmonic(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Damped harmonic smoother ``s_sigma(t) ~ e^(sigma t) sin(pi t / T)`` on ``[0, T]``,
    normalised to unit gain.

    Biagiotti, Melchiorri and Moriello, "Damped Harmonic Smoother for Trajectory Planning and
    Vibration Suppression", 2020, eq. 10: with ``sigma = -zeta wn`` and ``T = 3 pi k / wd`` it
    cancels a damped mode exactly (docs/filters.md).

    Parameters
    ----------
    T : float, keyword-only
        Duration of the impulse response [s], > 0 (and >= Ts where it is run).
    k : int, keyword-only
        Which zero exact timing keeps on the sample grid when ``T`` is not a whole number
        of samples (>= 1, default 1; docs/exact-mode.md).
    timing : {"exact", "paper"}, keyword-only
        ``"exact"`` (default): taps adjusted so the pinned zero stays exact for any Ts;
        ``"paper"``: the sampled continuous response, as the papers discretise it.
    sigma : float, keyword-only
        Decay rate [1/s], <= 0.

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``T``, ``sigma``, ``k`` (must be odd) or ``timing``.
    """
    return Stage("damped_harmonic", T=T, sigma=sigma, k=k, timing=timing)


def exponential(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Exponential (damped rectangular) smoother ``m_sigma(t) ~ e^(sigma t)`` on ``[0, T)``,
    normalised to unit gain.

    The damped counterpart of the moving average (Biagiotti, Melchiorri and Moriello 2020;
    the jerk stage of Béarée, "New Damped-Jerk trajectory for vibration reduction", 2014); with
    ``sigma = -zeta wn`` and ``T = k Td`` its zeros sit on the damped
    mode (docs/filters.md).

    Parameters
    ----------
    T : float, keyword-only
        Duration of the impulse response [s], > 0 (and >= Ts where it is run).
    k : int, keyword-only
        Which zero exact timing keeps on the sample grid when ``T`` is not a whole number
        of samples (>= 1, default 1; docs/exact-mode.md).
    timing : {"exact", "paper", "bounded"}, keyword-only
        ``"exact"`` (default): taps adjusted so the pinned zero stays exact for any Ts;
        ``"paper"``: the sampled continuous response, as the papers discretise it;
        ``"bounded"``: the exact zero with one more tap, none above the continuous peak
        density times Ts (for a stage that also bounds a derivative, docs/exact-mode.md).
    sigma : float, keyword-only
        Decay rate [1/s], <= 0.

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``T``, ``sigma``, ``k`` or ``timing``.
    """
    return Stage("exponential", T=T, sigma=sigma, k=k, timing=timing)


def shaper(kind: str, *, wn: float, zeta: float = 0.0, order: int | None = None,
           tolerance: float = 0.05, duration: float = 0.75, timing: str = "exact") -> Stage:
    """Input shaper for the mode (``wn``, ``zeta``): a few impulses whose responses cancel on
    the mode.

    ZV, ZVD, ZVDD and ZV^n (Singer and Seering 1990; Singhose, Seering and Singer, "Residual
    vibration reduction using vector diagrams to generate shaped inputs", 1994), EI and
    two-/three-hump EI (Singhose, Porter, Tuttle and Singer, "Vibration reduction using
    multi-hump input shapers", 1997), MZV as Klipper defines it, the generalised MZV
    (n impulses over ``duration`` damped periods) and the specified-insensitivity shaper si
    (Singhose, Seering and Singer, "Input shaping for vibration reduction with specified
    insensitivity to modeling errors", 1996: residual <= ``tolerance`` over the widest band for
    ``order`` impulses over ``duration`` periods; :func:`smoothshaper.filters.si_shaper` picks
    them for a band). Amplitudes and times: docs/filters.md. User-defined impulses:
    :func:`impulse_shaper`.

    Parameters
    ----------
    kind : str
        One of zv, zvd, zvdd, zvn, ei, ei2, ei3, mzv, gmzv, si (any case).
    wn : float, keyword-only
        Natural frequency of the mode [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio of the mode, in [0, 1) (default 0).
    order : int or None, keyword-only
        n of ZV^n (zvn, 1..8) or the number of impulses of gmzv (3..9) and si (3, 5, 7, 9).
    tolerance : float, keyword-only
        Vibration tolerance V of the EI family and si, in (0, 1) (default 0.05).
    duration : float, keyword-only
        Span of gmzv and si in damped periods (default 0.75).
    timing : {"exact", "paper"}, keyword-only
        Impulses placed between samples by linear interpolation (exact) or rounded to the
        nearest sample (paper).

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``kind``, ``wn``, ``zeta``, ``order``, ``tolerance``, ``duration`` or
        ``timing``.
    """
    kind = kind_name(kind, SHAPERS[:-1])
    return Stage(kind, wn=wn, zeta=zeta, order=order, tolerance=tolerance, duration=duration,
                 timing=timing)


def input_smoother(kind: str, *, wn: float, zeta: float = 0.0) -> Stage:
    """Input smoother of Klipper-derived firmware for the mode (``wn``, ``zeta``): a polynomial
    kernel with zero end values (D. Butyugin's smooth_zv, smooth_mzv, smooth_ei,
    smooth_2hump_ei, smooth_zvd_ei, smooth_si; dmbutyugin/klipper ``shaper_defs.py``, 2024).

    Realised with every sample a tap: the kernel applied to the linear interpolation of the
    samples, corrected so that the residual at the mode is the continuous design's for any Ts
    (docs/filters.md).

    Parameters
    ----------
    kind : str
        One of smooth_zv, smooth_mzv, smooth_ei, smooth_ei2 (the firmware's smooth_2hump_ei),
        smooth_zvd_ei, smooth_si (any case).
    wn : float, keyword-only
        Design frequency [rad/s] (the firmware's ``smoother_freq`` times 2 pi), > 0.
    zeta : float, keyword-only
        Damping ratio; read by smooth_zv, smooth_mzv and smooth_ei, in [0, 0.25] (default 0).
        The others were designed for damping 0.1 and do not read it.

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``kind``, ``wn`` or ``zeta``.
    """
    if isinstance(kind, str) and kind.strip().lower() == "smooth_2hump_ei":
        kind = "smooth_ei2"
    return Stage(kind_name(kind, INPUT_SMOOTHERS), wn=wn, zeta=zeta)


def impulse_shaper(*, amplitudes, times, timing: str = "exact") -> Stage:
    """A shaper given as its impulses, e.g. a firmware's shaper pasted as amplitudes and times.

    The amplitudes are normalised to sum 1 where the filter is built (as Klipper's
    ``input_shaper`` divides by their sum); negative amplitudes are allowed. Exact timing
    splits an impulse between two samples linearly (sum and centroid exact); paper timing
    rounds each to the nearest sample.

    Parameters
    ----------
    amplitudes : sequence of float, keyword-only
        1 to :data:`MAX_IMPULSES` finite amplitudes of positive sum.
    times : sequence of float, keyword-only
        As many impulse times [s], >= 0, strictly increasing (a first time > 0 is a delay).
    timing : {"exact", "paper"}, keyword-only
        Realisation between samples (default ``"exact"``).

    Returns
    -------
    Stage
        The validated description (kind ``"impulses"``).

    Raises
    ------
    ParameterError
        Naming ``amplitudes``, ``times`` (or the entry, e.g. ``times[2]``) or ``timing``.
    """
    return Stage("impulses", amplitudes=amplitudes, times=times, timing=timing)


def notch(*, wn: float, zeta: float = 0.0, notch_pole_zeta: float = 0.7,
          discretization: str = "matched", pole_zeta: float | None = None) -> Stage:
    """Notch filter ``(s^2 + 2 zeta wn s + wn^2) / (s^2 + 2 notch_pole_zeta wn s + wn^2)``.

    Bascetta, "Motion control: advanced control techniques" (lecture notes, notch filter);
    discretised (Franklin, Powell and Workman, *Digital Control of Dynamic Systems*, 1998) by
    pole-zero matching (zeros exactly on the sampled mode) or Tustin pre-warped
    at ``wn`` (docs/filters.md).

    Parameters
    ----------
    wn : float, keyword-only
        Frequency of the notch [rad/s], > 0 and below the Nyquist frequency where it is run.
    zeta : float, keyword-only
        Damping of the zeros (the mode's damping ratio), in [0, 1) (default 0).
    notch_pole_zeta : float, keyword-only
        Damping of the poles, > ``zeta`` (default 0.7): sets the notch's width.
    discretization : {"matched", "tustin"}, keyword-only
        Discretisation (default ``"matched"``).
    pole_zeta : float or None, keyword-only
        Deprecated name of ``notch_pole_zeta`` (a DeprecationWarning).

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``wn``, ``zeta``, ``notch_pole_zeta`` or ``discretization``.
    """
    if pole_zeta is not None:
        warnings.warn("notch(pole_zeta=) is deprecated; use notch_pole_zeta=",
                      DeprecationWarning, stacklevel=2)
        notch_pole_zeta = pole_zeta
    discretization = _choice("discretization", discretization, ("matched", "tustin"))
    return Stage(f"notch_{discretization}", wn=wn, zeta=zeta, notch_pole_zeta=notch_pole_zeta)


def _check_odd(kind: str, k: int) -> None:
    if kind in ("harmonic", "damped_harmonic") and k % 2 == 0:
        raise ParameterError(
            "k", f"k must be odd for the {kind} family: zeros sit at odd multiples "
            f"of pi/T, so T = k*3*pi/wn with even k={_show(k)} puts no zero on wn")


def _mode_length(k: int, half_periods: int, wn: float, wd: float) -> float:
    """``k half_periods pi / wd``, the smoother length :func:`for_mode` places on the mode;
    ParameterError naming ``wn`` (the period itself is beyond a float) or ``k`` (the multiple
    is) when it is not a finite float, instead of an OverflowError or a message about ``T``,
    which the caller did not give."""
    try:
        T = k * half_periods * math.pi / wd
    except (OverflowError, ZeroDivisionError):
        T = math.inf
    if math.isfinite(T):
        return T
    if wd == 0 or not math.isfinite(half_periods * math.pi / wd):
        raise ParameterError("wn", f"wn = {wn!r} rad/s is too low: the mode's period is beyond "
                             "the largest float")
    raise ParameterError("k", f"k = {_show(k)}: k times the mode's period is beyond the "
                         "largest float")


def for_mode(kind: str, *, wn: float, zeta: float = 0.0, k: int = 1) -> Stage:
    """A stage of ``kind`` that cancels the mode (``wn``, ``zeta``), as ``sms_design_for_mode``.

    With ``wd = wn sqrt(1 - zeta^2)``: rectangular ``T = k 2 pi / wd``; harmonic
    ``T = k 3 pi / wd`` (k odd); damped harmonic ``sigma = -zeta wn``, ``T = k 3 pi / wd``
    (Biagiotti, Melchiorri and Moriello 2020); exponential ``sigma = -zeta wn``,
    ``T = k 2 pi / wd``; shapers, input smoothers and notches take the mode itself
    (docs/design.md); user-defined impulses have no mode (ParameterError naming ``kind``).

    Parameters
    ----------
    kind : str
        Any kind of :data:`KINDS` (any case).
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1) (default 0).
    k : int, keyword-only
        Multiple of the zero placed on the mode (>= 1; odd for the harmonic families; 1 for
        shapers and notches).

    Returns
    -------
    Stage
        The validated description (no C memory is allocated until a Chain is built).

    Raises
    ------
    ParameterError
        Naming ``kind``, ``wn``, ``zeta`` or ``k``.
    """
    kind = kind_name(kind)
    wn, zeta = _checked_mode(wn, zeta)
    return _for_mode(kind, wn, zeta, _integer("k", k, 1))


def _for_mode(kind: str, wn: float, zeta: float, k: int) -> Stage:
    """:func:`for_mode` of checked arguments (``kind`` canonical, ``wn`` finite > 0 and
    ``zeta`` in [0, 1) floats, ``k`` an int >= 1). A smoother is built without running the
    Stage's checks again: its T is a finite positive float here and its sigma <= 0; only the
    odd multiple of the harmonic families is left to check."""
    wd = wn * math.sqrt(1.0 - zeta * zeta)
    if kind in SMOOTHERS:
        T = _mode_length(k, 2 if kind in ("rectangular", "exponential") else 3, wn, wd)
        _check_odd(kind, k)
        stage = _unchecked_stage(kind, T, k=k)
        if kind in ("damped_harmonic", "exponential"):
            object.__setattr__(stage, "sigma", -zeta * wn)      # -0.0 too, as Stage keeps it
        return stage
    if kind == "impulses":
        raise ParameterError(
            "kind", "kind='impulses' has no mode to design for: give its amplitudes and times "
            "(impulse_shaper)")
    if k != 1:
        raise ParameterError(
            "k", f"k must be 1 for {kind}: shapers and notches are placed on the mode itself")
    return Stage(kind, wn=wn, zeta=zeta)
