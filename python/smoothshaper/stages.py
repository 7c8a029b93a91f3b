"""Plain stage descriptions shared by the C-backed filters and the NumPy reference.

A :class:`Stage` is data only, like the C ``sms_stage_config``: it holds the physical
parameters of one stage and validates everything that does not depend on the sample period.
Checks that need ``Ts`` (``T >= Ts``, a mode below Nyquist) happen where ``Ts`` is known.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from ._checks import finite as _finite

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
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {', '.join(KINDS)}; got {self.kind!r}")
        if self.timing not in TIMINGS:
            raise ValueError(f"timing must be 'exact' or 'paper', got {self.timing!r}")
        if self.order is None:
            object.__setattr__(self, "order", 3 if self.kind == "gmzv" else 1)
        for name in ("T", "sigma", "wn", "zeta", "tolerance", "notch_pole_zeta", "duration"):
            object.__setattr__(self, name, _finite(name, getattr(self, name)))
        if isinstance(self.k, bool) or int(self.k) != self.k:
            raise ValueError(f"k must be an integer >= 1, got {self.k!r}")
        if isinstance(self.order, bool) or int(self.order) != self.order:
            raise ValueError(f"order must be an integer, got {self.order!r}")
        object.__setattr__(self, "k", int(self.k))
        object.__setattr__(self, "order", int(self.order))
        if self.kind in SMOOTHERS:
            if self.T <= 0:
                raise ValueError(f"T must be > 0 s, got {self.T!r}")
            if self.sigma > 0:
                raise ValueError(f"sigma must be <= 0 1/s (a decaying mode), got {self.sigma!r}")
            if self.k < 1:
                raise ValueError(f"k must be >= 1, got {self.k!r}")
            if self.kind in ("harmonic", "damped_harmonic") and self.k % 2 == 0:
                raise ValueError(
                    f"k must be odd for the {self.kind} family: zeros sit at odd multiples of "
                    f"pi/T, so T = k*3*pi/wn with even k={self.k} puts no zero on wn")
        else:
            if self.wn <= 0:
                raise ValueError(f"wn must be > 0 rad/s, got {self.wn!r}")
            if not 0.0 <= self.zeta < 1.0:
                raise ValueError(f"zeta must be in [0, 1), got {self.zeta!r}")
        if self.kind == "zvn" and not 1 <= self.order <= MAX_ZVN_ORDER:
            raise ValueError(f"order must be in 1..{MAX_ZVN_ORDER} for zvn, got {self.order!r}")
        if self.kind in ("ei", "ei2", "ei3") and not 0.0 < self.tolerance < 1.0:
            raise ValueError(f"tolerance must be in (0, 1), got {self.tolerance!r}")
        if self.kind == "gmzv":
            if not 3 <= self.order <= MAX_IMPULSES:
                raise ValueError(f"order (number of impulses) must be in 3..{MAX_IMPULSES} for "
                                 f"gmzv, got {self.order!r}")
            if not 0.0 < self.duration < 0.5 * (self.order - 1):
                raise ValueError(f"duration must be in (0, {0.5 * (self.order - 1)!r}) damped "
                                 f"periods for gmzv with order {self.order}, got {self.duration!r}")
        if self.kind in NOTCHES and not self.notch_pole_zeta > self.zeta:
            raise ValueError(
                f"notch_pole_zeta must be > zeta ({self.zeta!r}), got {self.notch_pole_zeta!r}")

    @property
    def kind_index(self) -> int:
        """The C ``sms_kind`` value."""
        return KINDS.index(self.kind)

    def with_(self, **changes) -> "Stage":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)


def rectangular(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Moving average of duration ``T`` [s] (docs/filters.md)."""
    return Stage("rectangular", T=T, k=k, timing=timing)


def harmonic(*, T: float, k: int = 1, timing: str = "exact") -> Stage:
    """Sinusoidal smoother of duration ``T`` [s] (docs/filters.md)."""
    return Stage("harmonic", T=T, k=k, timing=timing)


def damped_harmonic(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Damped sinusoidal smoother, ``sigma`` <= 0 [1/s] (docs/filters.md)."""
    return Stage("damped_harmonic", T=T, sigma=sigma, k=k, timing=timing)


def exponential(*, T: float, sigma: float, k: int = 1, timing: str = "exact") -> Stage:
    """Exponential (damped rectangular) smoother (docs/filters.md)."""
    return Stage("exponential", T=T, sigma=sigma, k=k, timing=timing)


def shaper(kind: str, *, wn: float, zeta: float = 0.0, order: int | None = None,
           tolerance: float = 0.05, duration: float = 0.75, timing: str = "exact") -> Stage:
    """Input shaper ``kind`` in zv, zvd, zvdd, zvn, ei, ei2, ei3, mzv, gmzv for the mode
    (wn [rad/s], zeta). ``order``: n of zvn, impulses of gmzv; ``tolerance``: V of the EI
    family; ``duration``: span of gmzv in damped periods."""
    if kind not in SHAPERS:
        raise ValueError(f"kind must be one of {', '.join(SHAPERS)} for a shaper, got {kind!r}")
    return Stage(kind, wn=wn, zeta=zeta, order=order, tolerance=tolerance, duration=duration,
                 timing=timing)


def notch(*, wn: float, zeta: float = 0.0, pole_zeta: float = 0.7,
          discretization: str = "matched") -> Stage:
    """Notch at ``wn`` [rad/s]: zero damping ``zeta``, pole damping ``pole_zeta`` (docs/filters.md).
    ``discretization`` is 'matched' (pole-zero matching) or 'tustin' (pre-warped at wn)."""
    if discretization not in ("matched", "tustin"):
        raise ValueError(f"discretization must be 'matched' or 'tustin', got {discretization!r}")
    return Stage(f"notch_{discretization}", wn=wn, zeta=zeta, notch_pole_zeta=pole_zeta)


def for_mode(kind: str, *, wn: float, zeta: float = 0.0, k: int = 1) -> Stage:
    """A stage of ``kind`` that cancels the mode (wn [rad/s], zeta), per docs/design.md.

    Mirrors ``sms_design_for_mode``: rectangular T = k 2pi/wd; harmonic T = k 3pi/wd (k odd);
    damped harmonic sigma = -zeta wn, T = k 3pi/wd (k odd); exponential sigma = -zeta wn,
    T = k Td; shapers and notches take the mode itself (k must be 1).
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}; got {kind!r}")
    wn = _finite("wn", wn)
    zeta = _finite("zeta", zeta)
    if wn <= 0:
        raise ValueError(f"wn must be > 0 rad/s, got {wn!r}")
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"zeta must be in [0, 1), got {zeta!r}")
    if isinstance(k, bool) or int(k) != k or k < 1:
        raise ValueError(f"k must be an integer >= 1, got {k!r}")
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
        raise ValueError(f"k must be 1 for {kind}: shapers and notches are placed on the mode itself")
    return Stage(kind, wn=wn, zeta=zeta)
