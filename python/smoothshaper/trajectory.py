"""Online multi-point generator and B-spline interpolation: C-backed classes and NumPy references.

* :class:`Generator` wraps ``sms_generator`` (docs/design.md): a staircase of targets in, position,
  velocity, acceleration and jerk out, never beyond ``vmax``, ``amax``, ``jmax`` (the argument
  is in ``c/include/smoothshaper/trajectory.h``); :func:`generator_reference` recomputes the
  same trajectory independently (it sums the tail response of *every* change of the first
  stage's velocity, instead of relying on only the last one being active, and evaluates the
  tail in closed form instead of tables).
* :class:`BSpline` wraps ``sms_bspline`` (Biagiotti & Melchiorri 2011b); :func:`bspline_reference` is
  the NumPy version (dense solve, ``np.convolve``). :func:`bspline_period` picks the knot
  spacing from the modes, ``T >= 2*pi/min(wn)``.
"""
from __future__ import annotations

import math

import numpy as np

from . import design as _design
from .filters import ParameterError, _backend, _raise_status, _real_dtype, check_memory
from ._checks import (finite as _finite, finite_signal as _targets, integer as _integer,
                      real_array as _real_array)

__all__ = ["Generator", "generator_reference", "BSpline", "bspline_reference", "bspline_period",
           "GEN_MAX_SEGMENT", "BSPLINE_MAX_DEGREE", "BSPLINE_MAX_AXES", "MultiAxisGenerator",
           "MultiAxisMove", "multi_axis_move", "phase_duration", "multi_axis_reference"]

GEN_MAX_SEGMENT = 4194304.0  # 2**22 samples, as the C core
BSPLINE_MAX_DEGREE = 7
BSPLINE_MAX_AXES = 3


def _generator_error(st, lib, ffi, cfg, Ts, profile):
    """ParameterError naming the cause of a refused generator config, with the values."""
    if st == -4:
        # the tail realisation: its stages T2 (about vmax/amax) and T3 (about amax/jmax, or
        # the mode period) must each last a sample
        T = ffi.new("double[2]")
        cnt = ffi.new("size_t *")
        lim = ffi.new("double[]", [cfg.vmax, cfg.amax, cfg.jmax])
        lib.sms_kinematic_design(cfg.vmax, lim + 1, 2, cfg.profile, cfg.wn, cfg.zeta, 0.0, T, 2,
                                 cnt)
        short = "amax" if T[0] < Ts else "jmax"
        raise ParameterError(
            short, f"{short}: the {profile} profile's tail stages last T2 = {T[0]:.6g} s and "
                   f"T3 = {T[1]:.6g} s (from vmax={cfg.vmax!r}, amax={cfg.amax!r}, "
                   f"jmax={cfg.jmax!r}{f', wn={cfg.wn!r}' if cfg.wn else ''}), shorter than "
                   f"Ts={Ts!r}; lower {short}, use a shorter Ts, or the polynomial profile "
                   "without a mode (time-optimal, any Ts)", st)
    if st == -16:
        raise ParameterError("wn", f"wn={cfg.wn!r} rad/s is at or above the Nyquist frequency "
                                   f"pi/Ts = {math.pi / Ts:.6g} rad/s", st)
    if st == -17:
        raise ParameterError("jmax", f"vmax={cfg.vmax!r}, amax={cfg.amax!r}, jmax={cfg.jmax!r}: "
                                     "their ratios are out of the range this precision can "
                                     "plan with (a^2/j or v j overflows)", st)
    _raise_status(st, lib, ffi, "online generator")


def _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta):
    cfg = ffi.new("sms_generator_config *")
    cfg.vmax = _design._positive("vmax", vmax)
    cfg.amax = _design._positive("amax", amax)
    cfg.jmax = _design._positive("jmax", jmax)
    profile = _design.profile_name(profile)
    wn_, zeta_ = _design._mode(profile, wn, zeta)
    cfg.profile = _design.PROFILES.index(profile)
    cfg.wn = wn_
    cfg.zeta = zeta_
    return cfg


class Generator:
    """Online multi-point trajectory generator (C core).

    Parameters (keyword-only): ``vmax``, ``amax``, ``jmax`` (> 0), ``Ts`` sample period [s],
    ``profile`` ("polynomial", "trigonometric", "damped"), optional mode ``wn`` [rad/s] and
    ``zeta``, ``q0`` the initial position (the generator starts at rest there, default 0),
    ``precision`` ("double" or "float").

    :meth:`process` takes the target (staircase) per sample and returns an ``(n, 4)`` array of
    position, velocity, acceleration and jerk: the exact values and derivatives of the
    continuous output at the sample instants, so the backward differences of the samples keep
    the bounds too (docs/sampled-limits.md). The polynomial profile without a mode is
    time-optimal: every new target is reached in ruckig's time-optimal jerk-limited duration
    from the current state, rounded up to the sample grid, for any ``Ts``. The other profiles
    (a harmonic or mode-tuned last stage) use a fixed tail of stages T2, T3 and need both to
    last at least ``Ts``. Errors: :class:`~smoothshaper.filters.ParameterError` naming the
    parameter.
    """

    def __init__(self, *, vmax: float, amax: float, jmax: float, Ts: float,
                 profile: str = "polynomial", wn: float | None = None, zeta: float = 0.0,
                 q0: float = 0.0, precision: str = "double"):
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        self.Ts = _design._positive("Ts", Ts)
        q0 = _finite("q0", q0)
        self.precision = precision
        cfg = _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta)
        need = ffi.new("size_t *")
        st = lib.sms_generator_buffer_size(cfg, self.Ts, need)
        if st != 0:
            _generator_error(st, lib, ffi, cfg, self.Ts, profile)
        check_memory("Ts", need[0], f"the generator's delay line at Ts={self.Ts!r}")
        self._buffer = np.zeros(max(need[0], 1), dtype=_real_dtype(precision))
        self._gen = ffi.new("sms_generator *")
        st = lib.sms_generator_init(self._gen, cfg, self.Ts,
                                    ffi.from_buffer("sms_real[]", self._buffer), need[0])
        if st != 0:  # pragma: no cover - the size query validated the same arguments
            _raise_status(st, lib, ffi, "online generator")
        self.vmax, self.amax, self.jmax = cfg.vmax, cfg.amax, cfg.jmax
        self.profile, self.wn, self.zeta = _design.PROFILES[cfg.profile], cfg.wn, cfg.zeta
        self.q0 = q0
        self.reset(q0)

    @property
    def time_optimal(self) -> bool:
        """True for the time-optimal realisation (polynomial profile, no mode)."""
        return bool(self._gen.time_optimal)

    @property
    def T2(self) -> float:
        return self._gen.T2

    @property
    def T3(self) -> float:
        return self._gen.T3

    @property
    def tail_samples(self) -> int:
        """Nc: samples between changes of the first stage's velocity (>= (T2 + T3)/Ts)."""
        return int(self._gen.n_tail)

    def reset(self, position: float | None = None) -> None:
        """Rest at ``position`` (default: ``q0``)."""
        position = self.q0 if position is None else _finite("position", position)
        self._lib.sms_generator_reset(self._gen, position)

    def process(self, targets) -> np.ndarray:
        """Targets ``(n,)`` -> ``(n, 4)`` q, v, a, j; one C call for the whole block."""
        x = _targets("targets", targets)
        dtype = _real_dtype(self.precision)
        xin = np.ascontiguousarray(x, dtype=dtype)
        out = np.empty((x.size, 4), dtype=dtype)
        if x.size:
            self._lib.sms_generator_process(self._gen, self._ffi.from_buffer("sms_real[]", xin),
                                            x.size, self._ffi.from_buffer("sms_real[]", out))
        return out if dtype == np.float64 else out.astype(np.float64)

    def get_state(self) -> np.ndarray:
        """The dynamic state as a float64 array (a copy); :meth:`set_state` on this or an
        identically configured generator continues bit-exactly."""
        out = np.empty(self._lib.sms_generator_state_count(self._gen), dtype=np.float64)
        self._lib.sms_generator_get_state(self._gen, self._ffi.from_buffer("double[]", out))
        return out

    def set_state(self, state) -> None:
        """Restore a state from :meth:`get_state`. Raises ParameterError naming ``state`` if it
        does not fit this generator; then nothing is changed."""
        s = np.ascontiguousarray(_real_array("state", state, ndim=1), dtype=np.float64)
        st = self._lib.sms_generator_set_state(self._gen, self._ffi.from_buffer("double[]", s),
                                               s.size)
        if st != 0:
            raise ParameterError("state", "state does not match this generator (wrong length, "
                                 "non-finite, or counts out of range)", st)

    # Old names (deprecated): one name per concept, as Chain.get_state / set_state.
    save_state = get_state
    load_state = set_state


# ----------------------------------------------------------------------------------------------
# NumPy reference of the generator
# ----------------------------------------------------------------------------------------------

class _Tail:
    """The fixed tail M(T2) * L(T3) in closed form (moments of L, no tables)."""

    def __init__(self, T2, last):
        self.T2, self.T3, self.kind, self.sigma = T2, last.T, last.kind, last.sigma
        self.mu = 0.5 * T2 + self._M(1, np.array(self.T3))
        self.Tc = T2 + self.T3

    def _M(self, j, u):
        """int_0^u tau^j l(tau) dtau for u in [0, T3]."""
        T, u = self.T3, np.asarray(u, dtype=float)
        if self.kind == "rectangular":
            return u ** (j + 1) / ((j + 1) * T)
        if self.kind == "harmonic":
            A, w = math.pi / (2 * T), math.pi / T
            c, s = np.cos(w * u), np.sin(w * u)
            if j == 0:
                return A * (1 - c) / w
            if j == 1:
                return A * (s / w ** 2 - u * c / w)
            return A * (2 * u * s / w ** 2 + (2 / w ** 3 - u ** 2 / w) * c - 2 / w ** 3)
        sg = self.sigma
        A = sg / math.expm1(sg * T)
        e = np.exp(sg * u)
        if j == 0:
            return A * np.expm1(sg * u) / sg
        if j == 1:
            return A * (e * (u / sg - 1 / sg ** 2) + 1 / sg ** 2)
        return A * (e * (u ** 2 / sg - 2 * u / sg ** 2 + 2 / sg ** 3) - 2 / sg ** 3)

    def _density(self, s, inside):
        """l(s) where ``inside`` (the caller decides the support), else 0."""
        T = self.T3
        s = np.clip(s, 0.0, T)
        if self.kind == "rectangular":
            val = np.full_like(s, 1 / T)
        elif self.kind == "harmonic":
            val = math.pi / (2 * T) * np.sin(math.pi * s / T)
        else:
            val = self.sigma / math.expm1(self.sigma * T) * np.exp(self.sigma * s)
        return np.where(inside, val, 0.0)

    def _P(self, k, s):
        u = np.clip(s, 0.0, self.T3)
        M0, M1 = self._M(0, u), self._M(1, u)
        if k == 1:
            out = M0
        elif k == 2:
            out = s * M0 - M1
        else:
            out = 0.5 * (s * s * M0 - 2 * s * M1 + self._M(2, u))
        return np.where(s > 0, out, 0.0)

    def responses(self, m, Ts):
        """Ramp G, step F, impulse x2 and its derivative x2' of the tail at s = m Ts.

        x2' = (l(s) - l(s - T2)) / T2 jumps where a copy of l starts or ends; at a jump on a
        sample instant it takes the right limit. Which side a sample is on is decided on the
        integer sample index m against the breakpoint in samples (:func:`_breakpoint_samples`),
        not on m Ts - T2, which rounds either way when the breakpoint is on the grid.
        """
        T2 = self.T2
        s = m * Ts
        off1 = _breakpoint_samples(self.T3, Ts)
        on2 = _breakpoint_samples(T2, Ts)
        off2 = _breakpoint_samples(self.Tc, Ts)
        settled = m >= off2          # the change has passed through the whole tail
        G = (self._P(3, s) - self._P(3, s - T2)) / T2
        G = np.where(settled, s - self.mu, G)
        F = np.where(settled, 1.0, (self._P(2, s) - self._P(2, s - T2)) / T2)
        x2 = np.where(settled, 0.0, (self._P(1, s) - self._P(1, s - T2)) / T2)
        x2d = (self._density(s, m < off1) - self._density(s - T2, (m >= on2) & (m < off2))) / T2
        return G, F, x2, x2d


def _breakpoint_samples(b, Ts):
    """A breakpoint b [s] in samples: round(b/Ts) if it passes the integer test of
    docs/exact-mode.md (within 1e-9 * max(1, b/Ts)), else b/Ts."""
    nu = b / Ts
    n = math.floor(nu + 0.5)
    return float(n) if abs(nu - n) <= 1e-9 * max(nu, 1.0) else nu


def _tail_samples(Tc, Ts):
    nu = _breakpoint_samples(Tc, Ts)
    return int(nu) if nu == int(nu) else int(math.ceil(nu))


def generator_reference(targets, *, vmax, amax, jmax, Ts, profile="polynomial", wn=None,
                        zeta=0.0, position=0.0) -> np.ndarray:
    """NumPy reference of :class:`Generator`: ``(n, 4)`` array of q, q', q'', q'''.

    The polynomial profile without a mode is the time-optimal realisation: its reference is
    :func:`smoothshaper.time_optimal.time_optimal_reference` (``position`` is the initial
    rest). The other profiles: the schedule of the first stage (scheme of trajectory.h: velocity changes on
    samples, >= Nc samples apart, of at most vmax, segments of >= Nc samples ending exactly on
    the target) is replayed; the output is then the sum over all changes dV_i of
    dV_i * (ramp, step, impulse, impulse') responses of the tail at t - t_i.

    Jumps of the jerk on a sample instant (the jerk response jumps at s = 0, T3, T2, T2 + T3
    after each change): the output is the right limit, the value over [t_n, t_n + Ts) that a
    zero-order hold applies next, as documented for ``sms_generator`` in trajectory.h. A
    breakpoint b is on the grid when b/Ts passes the integer test of docs/exact-mode.md
    (within 1e-9 * max(1, b/Ts) of an integer); the side is then decided on the integer sample
    index, so stage lengths that are whole multiples of Ts give the right limit whatever the
    rounding of T2, T3 and Ts (a change's last jump at T2 + T3 gives 0 there).
    """
    x = _targets("targets", targets)
    vmax = _design._positive("vmax", vmax)
    Ts = _design._positive("Ts", Ts)
    if profile == "polynomial" and wn is None:
        from .time_optimal import time_optimal_reference
        return time_optimal_reference(x, vmax=vmax, amax=_design._positive("amax", amax),
                                      jmax=_design._positive("jmax", jmax), Ts=Ts,
                                      q0=_finite("position", position))
    tail_stages = _design.kinematic_reference(h=vmax, vmax=amax, amax=jmax, profile=profile,
                                              wn=wn, zeta=zeta)
    tail = _Tail(tail_stages[0].T, tail_stages[1])
    Nc = _tail_samples(tail.Tc, Ts)
    # replay the schedule
    r = start = goal = float(position)
    target = float(position)
    V = 0.0
    seg_len = seg_pos = 0
    age = Nc
    changes = []  # (sample index, dV)

    def plan(k):
        nonlocal V, start, goal, seg_len, seg_pos, age
        d = target - r
        if V != 0 and (d == 0 or (d > 0) != (V > 0)):
            changes.append((k, -V))
            V, seg_len, seg_pos, start, goal, age = 0.0, 0, 0, r, r, 0
            return
        samples = abs(d) / (vmax * Ts)
        if samples > GEN_MAX_SEGMENT:
            samples = GEN_MAX_SEGMENT
            d = math.copysign(GEN_MAX_SEGMENT * vmax * Ts, d)
        m = float(math.floor(samples))
        if m < samples:
            m += 1.0
        m = max(m, float(Nc))
        Vn = d / (m * Ts)
        start, goal, seg_len, seg_pos = r, r + d, int(m), 0
        if Vn != V:
            changes.append((k, Vn - V))
            V, age = Vn, 0

    for k, tk in enumerate(x):
        target = tk
        if age < Nc:
            age += 1
        if seg_len > 0:
            seg_pos += 1
            if seg_pos >= seg_len:
                r, seg_len, seg_pos, start = goal, 0, 0, goal
                if age >= Nc and target != r:
                    plan(k)
                else:
                    changes.append((k, -V))
                    V, age = 0.0, 0
            else:
                r = start + V * (seg_pos * Ts)
        if age >= Nc and target != (goal if seg_len > 0 else r):
            plan(k)
    # the output: every change through the tail
    n = x.size
    out = np.zeros((n, 4))
    out[:, 0] = position
    for k0, dv in changes:
        G, F, x2, x2d = tail.responses(np.arange(n - k0), Ts)
        out[k0:, 0] += dv * G
        out[k0:, 1] += dv * F
        out[k0:, 2] += dv * x2
        out[k0:, 3] += dv * x2d
    return out


# ----------------------------------------------------------------------------------------------
# B-splines
# ----------------------------------------------------------------------------------------------

def _bspline_args(degree, T, Ts, axes):
    if not 1 <= _integer("degree", degree) <= BSPLINE_MAX_DEGREE:
        raise ParameterError(
            "degree", f"degree must be an integer in 1..{BSPLINE_MAX_DEGREE}, got {degree!r}")
    if not 1 <= _integer("axes", axes) <= BSPLINE_MAX_AXES:
        raise ParameterError(
            "axes", f"axes must be an integer in 1..{BSPLINE_MAX_AXES}, got {axes!r}")
    Ts = _design._positive("Ts", Ts)
    T = _design._positive("T", T)
    if T / Ts < 1.0 - 1e-9:   # the one rule for short T (T within 1e-9 of Ts is one sample)
        raise ParameterError(
            "T", f"T must be >= Ts = {Ts!r} (one knot spacing of at least a sample), "
                 f"got {T!r}")
    return int(degree), T, Ts, int(axes)


def _via(name, via, axes=None) -> np.ndarray:
    q = _real_array(name, via)
    if q.ndim == 1:
        q = q[:, None]
    if q.ndim != 2 or q.shape[0] < 2:
        raise ParameterError(
            name, f"{name} must have shape (M,) or (M, axes) with M >= 2, got {q.shape}")
    if axes is not None and q.shape[1] != axes:
        raise ParameterError(
            name, f"{name} must have {axes} columns (one per axis), got {q.shape[1]}")
    if not np.all(np.isfinite(q)):
        raise ParameterError(name, f"{name} must be finite")
    return q


class BSpline:
    """Uniform B-spline filter of degree ``degree``, knot spacing ``T`` (rounded to ``N`` whole
    samples), on ``axes`` axes (C core). See ``sms_bspline`` in trajectory.h for the timing:
    via-point i (1 <= i <= M-2) is passed at sample ``(i-1) N + k0`` after the start."""

    def __init__(self, *, degree: int, T: float, Ts: float, axes: int = 1,
                 precision: str = "double"):
        degree, T, Ts, axes = _bspline_args(degree, T, Ts, axes)
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        need = ffi.new("size_t *")
        st = lib.sms_bspline_buffer_size(degree, axes, T, Ts, need)
        if st != 0:
            _raise_status(st, lib, ffi, "B-spline filter")
        check_memory("T", need[0], f"a degree-{degree} B-spline on {axes} axes with T/Ts = "
                     f"{T / Ts:.6g}")
        self._buffer = np.zeros(need[0], dtype=_real_dtype(precision))
        self._b = ffi.new("sms_bspline *")
        st = lib.sms_bspline_init(self._b, degree, axes, T, Ts,
                                  ffi.from_buffer("sms_real[]", self._buffer), need[0])
        if st != 0:  # pragma: no cover
            _raise_status(st, lib, ffi, "B-spline filter")
        self.degree, self.axes, self.Ts, self.precision = degree, axes, Ts, precision

    @property
    def N(self) -> int:
        return int(self._b.N)

    @property
    def T(self) -> float:
        """The knot spacing realised, N Ts."""
        return self.N * self.Ts

    @property
    def k0(self) -> int:
        return int(self._b.k0)

    def control_points(self, via) -> np.ndarray:
        """Control points ``(M, axes)`` for via-points ``(M, axes)`` (or ``(M,)`` for one axis)."""
        q = _via("via", via, self.axes)
        M = q.shape[0]
        ctrl = np.empty_like(q)
        nwork = self._lib.sms_bspline_work_size(self._b, M)
        work = np.empty(max(nwork, 1))
        st = self._lib.sms_bspline_control_points(
            self._b, self._ffi.from_buffer("double[]", np.ascontiguousarray(q)), M,
            self._ffi.from_buffer("double[]", ctrl), self._ffi.from_buffer("double[]", work), nwork)
        if st != 0:  # pragma: no cover - validated above
            _raise_status(st, self._lib, self._ffi, "B-spline control points")
        return ctrl

    def pass_samples(self, M: int) -> np.ndarray:
        """Samples at which via-points 1 .. M-2 are passed."""
        return np.array([self._lib.sms_bspline_pass_sample(self._b, i) for i in range(1, M - 1)],
                        dtype=np.int64)

    def end_sample(self, M: int) -> int:
        """First sample from which the output rests on the last via-point."""
        return (M - 2) * self.N + self.degree * (self.N - 1)

    def staircase(self, control, n_samples: int) -> np.ndarray:
        """The held control points of the feeding protocol, ``(n_samples, axes)``."""
        c = np.asarray(control, dtype=np.float64)
        j = np.minimum(np.arange(n_samples) // self.N + 1, c.shape[0] - 1)
        return c[j]

    def process(self, x, rest=None, *, progress=None) -> np.ndarray:
        """Filter ``x`` ``(n, axes)`` after resting every axis at ``rest`` (default x[0]).

        ``progress``: None or a callable called as ``progress(samples)`` after every block of
        samples. The samples are stepped through ``sms_bspline_step`` one at a time on
        pointers into one contiguous array (about 1 us per sample)."""
        x = np.ascontiguousarray(_real_array("x", x).reshape(-1, self.axes))
        if not np.all(np.isfinite(x)):
            raise ParameterError("x", "x must be finite")
        rest = x[0] if rest is None else np.asarray(rest, dtype=np.float64).reshape(self.axes)
        ffi, lib, b, axes = self._ffi, self._lib, self._b, self.axes
        lib.sms_bspline_reset(b, ffi.new("sms_real[]", [float(v) for v in rest]))
        work = np.ascontiguousarray(x, dtype=_real_dtype(self.precision))
        out = np.empty_like(work)
        pin = ffi.from_buffer("sms_real[]", work)
        pout = ffi.from_buffer("sms_real[]", out)
        step = lib.sms_bspline_step
        block = 1 << 16
        for start in range(0, work.shape[0], block):
            stop = min(start + block, work.shape[0])
            for k in range(start * axes, stop * axes, axes):
                step(b, pin + k, pout + k)
            if progress is not None:
                progress(stop - start)
        return out.astype(np.float64, copy=False)

    def interpolate(self, via, *, extra: int = 0, progress=None) -> np.ndarray:
        """Output ``(end_sample + 1 + extra, axes)`` passing through the via-points
        (``progress`` as in :meth:`process`)."""
        q = _via("via", via, self.axes)
        ctrl = self.control_points(q)
        n = self.end_sample(q.shape[0]) + 1 + int(extra)
        return self.process(self.staircase(ctrl, n), rest=q[0], progress=progress)


def bspline_reference(via, *, degree: int, T: float, Ts: float):
    """NumPy reference: ``(control, output, pass_samples)`` for via-points ``(M, axes)``.

    Discrete response d of one control point held N samples then p moving averages of N
    samples (np.convolve), k0 = floor(len(d) - 1) / 2, c_m = d[k0 + m N], dense solve.
    """
    q = _via("via", via)
    degree, T, Ts, _ = _bspline_args(degree, T, Ts, min(q.shape[1], BSPLINE_MAX_AXES))
    N = max(1, int(math.floor(T / Ts + 0.5)))
    check_memory("T", (degree + 1) * N * (q.shape[0] + degree), f"the reference B-spline with "
                 f"T/Ts = {T / Ts:.6g}")
    d = np.ones(N)
    for _ in range(degree):
        d = np.convolve(d, np.full(N, 1.0 / N))
    k0 = (d.size - 1) // 2
    M = q.shape[0]
    n = M - 2
    ctrl = q.copy()
    if n > 0:
        A = np.zeros((n, n))
        rhs = q[1:-1].copy()
        for i in range(1, M - 1):
            for j in range(-degree - 2, M + degree + 2):
                k = k0 + (i - j) * N
                if not 0 <= k < d.size:
                    continue
                if 1 <= j <= M - 2:
                    A[i - 1, j - 1] += d[k]
                else:
                    rhs[i - 1] -= d[k] * (q[0] if j <= 0 else q[-1])
        ctrl[1:-1] = np.linalg.solve(A, rhs)
    n_out = (M - 2) * N + degree * (N - 1) + 1
    jj = np.minimum(np.arange(n_out) // N + 1, M - 1)
    x = ctrl[jj]
    kern = np.full(N, 1.0 / N)
    out = np.empty_like(x)
    for a in range(q.shape[1]):
        # rest at q[0] before sample 0: filter the deviation from it
        y = x[:, a] - q[0, a]
        for _ in range(degree):
            y = np.convolve(y, kern)[:n_out]
        out[:, a] = y + q[0, a]
    passes = np.array([(i - 1) * N + k0 for i in range(1, M - 1)], dtype=np.int64)
    return ctrl, out, passes


def bspline_period(*, wn, Ts: float) -> float:
    """Shortest knot spacing ``N Ts >= 2 pi / min(wn)`` (Biagiotti & Melchiorri 2011b, sec. IV)."""
    w = np.atleast_1d(np.asarray(wn, dtype=np.float64))
    if w.size == 0 or not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise ParameterError(
            "wn", f"wn must be one or more finite frequencies > 0 rad/s, got {wn!r}")
    Ts = _design._positive("Ts", Ts)
    return max(1.0, math.ceil(2 * math.pi / (w.min() * Ts) * (1 - 1e-12))) * Ts


# Coordinated multi-axis motion lives in its own module; exposed here with the other generators.
from .multi_axis import (MultiAxisGenerator, MultiAxisMove, multi_axis_move,  # noqa: E402
                         phase_duration)
from .reference.multi_axis import multi_axis_reference  # noqa: E402
