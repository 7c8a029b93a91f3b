"""Plain stage descriptions shared by the C-backed filters and the NumPy reference.

A :class:`Stage` is data only, like the C ``sms_stage_config``: it holds the physical
parameters of one stage and validates everything that does not depend on the sample period.
Checks that need ``Ts`` (``T >= Ts``, a mode below Nyquist) happen where ``Ts`` is known.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from ._checks import choice as _choice, finite as _finite, integer as _integer
from .errors import ParameterError

__all__ = ["KINDS", "SMOOTHERS", "SHAPERS", "NOTCHES", "TIMINGS", "MAX_ZVN_ORDER", "MAX_IMPULSES",
           "Stage", "kind_name", "rectangular", "harmonic", "damped_harmonic", "exponential",
           "shaper", "notch", "for_mode"]

#: Stage kinds, in the order of the C enumeration ``sms_kind`` (index == C value).
KINDS = (
    "rectangular", "harmonic", "damped_harmonic", "exponential",
    "zv", "zvd", "zvdd", "zvn", "ei", "ei2", "mzv",
    "notch_tustin", "notch_matched", "ei3", "gmzv",
)
SMOOTHERS = KINDS[:4]
SHAPERS = KINDS[4:11] + KINDS[13:15]
NOTCHES = KINDS[11:13]
TIMINGS = ("exact", "paper")
MAX_ZVN_ORDER = 8
#: Most impulses of a shaper design (ZV^8; the generalised MZV takes 3..MAX_IMPULSES).
MAX_IMPULSES = MAX_ZVN_ORDER + 1


@dataclass(frozen=True)
class Stage:
    """One stage. Fields mirror ``sms_stage_config`` (see ``c/include/smoothshaper/config.h``).

    Smoothers use ``T`` [s], ``sigma`` [1/s] (damped families) and ``k`` (the zero pinned by
    exact timing); shapers and notches use ``wn`` [rad/s] and ``zeta``; ``order`` is the n of
    ZV^n and the number of impulses of ``gmzv`` (3..9; ``None`` means 1, or 3 for gmzv);
    ``tolerance`` the EI vibration tolerance (ei, ei2, ei3); ``duration`` the span of ``gmzv``
    in damped periods (0.75 with order 3 is MZV); ``notch_pole_zeta`` the notch pole damping.
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

    def __post_init__(self):
        object.__setattr__(self, "kind", kind_name(self.kind))
        object.__setattr__(self, "timing", _choice("timing", self.timing, TIMINGS))
        if self.order is None:
            object.__setattr__(self, "order", 3 if self.kind == "gmzv" else 1)
        for name in ("T", "sigma", "wn", "zeta", "tolerance", "notch_pole_zeta", "duration"):
            object.__setattr__(self, name, _finite(name, getattr(self, name)))
        object.__setattr__(self, "k", _integer("k", self.k, 1))
        object.__setattr__(self, "order", _integer("order", self.order))
        if self.kind in SMOOTHERS:
            if self.T <= 0:
                raise ParameterError("T", f"T must be > 0 s, got {self.T!r}")
            if self.sigma > 0:
                raise ParameterError(
                    "sigma", f"sigma must be <= 0 1/s (a decaying mode), got {self.sigma!r}")
            if self.kind in ("harmonic", "damped_harmonic") and self.k % 2 == 0:
                raise ParameterError(
                    "k", f"k must be odd for the {self.kind} family: zeros sit at odd multiples "
                    f"of pi/T, so T = k*3*pi/wn with even k={self.k} puts no zero on wn")
        else:
            if self.wn <= 0:
                raise ParameterError("wn", f"wn must be > 0 rad/s, got {self.wn!r}")
            if not 0.0 <= self.zeta < 1.0:
                raise ParameterError("zeta", f"zeta must be in [0, 1), got {self.zeta!r}")
        if self.kind == "zvn" and not 1 <= self.order <= MAX_ZVN_ORDER:
            raise ParameterError(
                "order", f"order must be in 1..{MAX_ZVN_ORDER} for zvn, got {self.order!r}")
        if self.kind in ("ei", "ei2", "ei3") and not 0.0 < self.tolerance < 1.0:
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
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)


def kind_name(kind, allowed=KINDS, parameter: str = "kind") -> str:
    """The canonical (lower-case) name of a stage kind: names compare case-insensitively,
    and ``"notch"`` means ``"notch_matched"``. Raises ParameterError naming ``parameter``."""
    if isinstance(kind, str) and kind.strip().lower() == "notch" and "notch_matched" in allowed:
        return "notch_matched"
    return _choice(parameter, kind, allowed)


def rectangular(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Moving average of duration ``T`` [s] (docs/filters.md).

    ``k`` selects the zero ``2 pi k / T`` that exact timing keeps on the sample grid when ``T``
    is not a whole number of samples; ``timing`` is ``"exact"`` or ``"paper"``
    (docs/exact-mode.md). Raises ParameterError naming ``T``, ``k`` or ``timing``."""
    return Stage("rectangular", T=T, k=k, timing=timing)


def harmonic(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Sinusoidal smoother of duration ``T`` [s] (Biagiotti & Melchiorri 2011a, sec. 3.2).

    ``k`` (odd) selects the zero ``3 pi k / T`` kept by exact timing. Raises ParameterError."""
    return Stage("harmonic", T=T, k=k, timing=timing)


def damped_harmonic(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Damped sinusoidal smoother of duration ``T`` [s], ``sigma`` <= 0 [1/s]
    (Biagiotti et al. 2020, eq. 10). Raises ParameterError."""
    return Stage("damped_harmonic", T=T, sigma=sigma, k=k, timing=timing)


def exponential(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Exponential (damped rectangular) smoother of duration ``T`` [s], ``sigma`` <= 0 [1/s]
    (docs/filters.md; Béarée 2014). Raises ParameterError."""
    return Stage("exponential", T=T, sigma=sigma, k=k, timing=timing)


def shaper(kind: str, *, wn: float, zeta: float = 0.0, order: int | None = None,
           tolerance: float = 0.05, duration: float = 0.75, timing: str = "exact") -> Stage:
    """Input shaper for the mode (``wn`` [rad/s], ``zeta``).

    ``kind`` is one of zv, zvd, zvdd, zvn, ei, ei2, ei3, mzv, gmzv (any case); ``order`` is the
    n of ZV^n (zvn, 1..8) or the number of impulses of gmzv (3..9); ``tolerance`` the vibration
    tolerance V of the EI family (0 < V < 1); ``duration`` the span of gmzv in damped periods.
    Impulse amplitudes and times: docs/filters.md. Raises ParameterError naming the parameter.
    """
    kind = kind_name(kind, SHAPERS)
    return Stage(kind, wn=wn, zeta=zeta, order=order, tolerance=tolerance, duration=duration,
                 timing=timing)
def notch(*, wn: float, zeta: float = 0.0, notch_pole_zeta: float = 0.7,
          discretization: str = "matched", pole_zeta: float | None = None) -> Stage:
    """Notch at ``wn`` [rad/s] with zero damping ``zeta`` and pole damping ``notch_pole_zeta``
    (> zeta), Bascetta's notch filter (docs/filters.md).

    ``discretization`` is ``"matched"`` (pole-zero matching: zeros exactly at the sampled mode)
    or ``"tustin"`` (bilinear, pre-warped at wn). ``pole_zeta`` is the old name of
    ``notch_pole_zeta`` (deprecated). Raises ParameterError naming the parameter."""
    if pole_zeta is not None:
        warnings.warn("notch(pole_zeta=) is deprecated; use notch_pole_zeta=",
                      DeprecationWarning, stacklevel=2)
        notch_pole_zeta = pole_zeta
    discretization = _choice("discretization", discretization, ("matched", "tustin"))
    return Stage(f"notch_{discretization}", wn=wn, zeta=zeta, notch_pole_zeta=notch_pole_zeta)


def for_mode(kind: str, *, wn: float, zeta: float = 0.0, k: int = 1) -> Stage:
    """A stage of ``kind`` (any case) that cancels the mode (``wn`` [rad/s], ``zeta``), per
    docs/design.md.

    Mirrors ``sms_design_for_mode``: rectangular T = k 2pi/wd; harmonic T = k 3pi/wd (k odd);
    damped harmonic sigma = -zeta wn, T = k 3pi/wd (k odd); exponential sigma = -zeta wn,
    T = k Td; shapers and notches take the mode itself (k must be 1). Raises ParameterError
    naming ``kind``, ``wn``, ``zeta`` or ``k``.
    """
    kind = kind_name(kind)
    wn = _finite("wn", wn)
    zeta = _finite("zeta", zeta)
    if wn <= 0:
        raise ParameterError("wn", f"wn must be > 0 rad/s, got {wn!r}")
    if not 0.0 <= zeta < 1.0:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    k = _integer("k", k, 1)
    wd = wn * math.sqrt(1.0 - zeta * zeta)
    if kind == "rectangular":
        return Stage(kind, T=k * 2 * math.pi / wd, k=k)
    if kind == "harmonic":
        return Stage(kind, T=k * 3 * math.pi / wd, k=k)
    if kind == "damped_harmonic":
        return Stage(kind, T=k * 3 * math.pi / wd, sigma=-zeta * wn, k=k)
    if kind == "exponential":
        return Stage(kind, T=k * 2 * math.pi / wd, sigma=-zeta * wn, k=k)
    if k != 1:
        raise ParameterError(
            "k", f"k must be 1 for {kind}: shapers and notches are placed on the mode itself")
    return Stage(kind, wn=wn, zeta=zeta)
