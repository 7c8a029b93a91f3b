# SPDX-License-Identifier: Apache-2.0
"""NumPy reference of the time-optimal jerk-limited motion between arbitrary states.

Written from docs/design.md ("Any state to any state") and independently of
``c/src/trajectory/third_order.c``: the same profile families (Berscheid and Kroeger,
"Jerk-limited real-time trajectory generation with arbitrary target states", RSS 2021), but
each case's position is sampled at Chebyshev nodes of the case's parameter and fitted by the
polynomial of its degree (NumPy's companion-matrix roots instead of the C code's derivative
isolation), each root refined on the motion itself, and a member accepted by checking the
motion's velocity and acceleration at its extremes (not the C code's structural tests).

Motion of one axis from (p0, v0, a0) to (pf, vf, af) within vmin <= v <= vmax,
amin <= a <= amax, |j| <= jmax. A *member* of family s (s = +1, or -1 with every quantity
mirrored) is: jerk +J until a reaches x, a hold at x (x at the bound), jerk -J down to y (a
cruise at a = 0 on the velocity bound inserted where the ramp crosses zero), a hold at y (at
the bound), jerk +J up to af. Its velocity where the middle ramp passes a = 0 (the crest m)
ties the halves: m = c0 + x^2/J (+ x t2) = cf + y^2/J (+ |y| t6), c0 = v0 - a0^2/(2J),
cf = vf - af^2/(2J).

* :func:`time_optimal`: the shortest member reaching the target (step 1), and the durations
  of every member reaching it (the blocked durations lie between them);
* :func:`farthest`: the member of duration T ending farthest in direction s (step 2: every
  end position between the two directions' is reached in T by the convex combination of
  their jerks);
* :func:`velocity_change`: the velocity interface (position free).

Pieces are ``(jerk, duration, a_start)``; a cruise piece (jerk 0, a = 0) carries its velocity
as a fourth entry. Used by the reference generator (:mod:`smoothshaper.time_optimal`) and
the tests; not on any run path.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["Limits", "time_optimal", "farthest", "velocity_change", "integrate",
           "state_at", "target_ok"]

EPS = float(np.finfo(float).eps)
#: How far a root may stray past the edge of its case and be taken on the edge.
SNAP = 1e-9


class Limits(tuple):
    """(vmax, vmin, amax, amin, jmax) with vmin < 0 < vmax, amin < 0 < amax, jmax > 0."""

    def __new__(cls, vmax, amax, jmax, vmin=None, amin=None):
        return super().__new__(cls, (float(vmax), -float(vmax) if vmin is None else float(vmin),
                                     float(amax), -float(amax) if amin is None else float(amin),
                                     float(jmax)))

    vmax = property(lambda self: self[0])
    vmin = property(lambda self: self[1])
    amax = property(lambda self: self[2])
    amin = property(lambda self: self[3])
    jmax = property(lambda self: self[4])


def target_ok(v, a, lim: Limits) -> str | None:
    """None when (v, a) can be a target (or a start): within the bounds, and the velocity
    where a was last zero on the fastest approach, v - a|a|/(2J), and where it returns to
    zero, v + a|a|/(2J), within the velocity bounds; else "velocity" or "acceleration"."""
    if not math.isfinite(v) or not lim.vmin <= v <= lim.vmax:
        return "velocity"
    r = a * abs(a) / (2 * lim.jmax)
    if not (math.isfinite(a) and lim.amin <= a <= lim.amax and lim.vmin <= v - r <= lim.vmax
            and lim.vmin <= v + r <= lim.vmax):
        return "acceleration"
    return None


def _advance(p, v, a, j, t):
    return p + t * (v + t * (a / 2 + t * j / 6)), v + t * (a + t * j / 2), a + t * j


def integrate(pieces, p, v, a):
    """End (p, v, a) after the pieces (each starting at its own acceleration, a cruise at its
    velocity) and the sum of |displacement| over them."""
    path = 0.0
    for piece in pieces:
        j, t, a = piece[0], piece[1], piece[2]
        if len(piece) > 3:
            v = piece[3]
        q, v, a = _advance(p, v, a, j, t)
        path += abs(q - p)
        p = q
    return p, v, a, path


def state_at(pieces, v0, a0, t):
    """(displacement, v, a, j) at time t of the pieces from (0, v0, a0)."""
    p, v, a, begin = 0.0, v0, a0, 0.0
    for i, piece in enumerate(pieces):
        j, d, a = piece[0], piece[1], piece[2]
        if len(piece) > 3:
            v = piece[3]
        if t < begin + d or i == len(pieces) - 1:
            s = min(max(t - begin, 0.0), d)
            p, v, a = _advance(p, v, a, j, s)
            return p, v, a, j
        p, v, a = _advance(p, v, a, j, d)
        begin += d
    return p, v, a, 0.0


class _Frame:
    """The problem mirrored by s (+1 or -1) and scaled: time A/J, velocity A^2/J, position
    A^3/J^2 with A the smallest acceleration bound (capped at sqrt(J (vmax - vmin)), beyond
    which no motion within the velocity bounds can accelerate)."""

    def __init__(self, s, pd, v0, a0, vf, af, lim: Limits):
        J = lim.jmax
        # the accelerations this motion needs: a unit no larger keeps a short move's roots
        # at the scale of 1 (the fits below then resolve them)
        need = max(abs(a0), abs(af), math.sqrt(J * abs(v0)), math.sqrt(J * abs(vf)),
                   (J * J * abs(pd)) ** (1.0 / 3.0))
        A = min(lim.amax, -lim.amin, math.sqrt(J * (lim.vmax - lim.vmin)))
        if 0 < need < A:
            A = need
        self.s, self.J, self.A = s, J, A
        self.tau, self.vu = A / J, A * A / J
        cap = 2 * math.sqrt(J * (lim.vmax - lim.vmin))
        amax, amin = min(lim.amax, cap) / A, max(lim.amin, -cap) / A
        vmax, vmin = lim.vmax / self.vu, lim.vmin / self.vu
        self.pd = s * pd / self.vu / self.tau
        self.v0, self.vf = s * v0 / self.vu, s * vf / self.vu
        self.a0, self.af = s * a0 / A, s * af / A
        self.Vu, self.Vl = (vmax, vmin) if s > 0 else (-vmin, -vmax)
        self.Au, self.Al = (amax, amin) if s > 0 else (-amin, -amax)
        self.c0 = self.v0 - self.a0 ** 2 / 2
        self.cf = self.vf - self.af ** 2 / 2

    # the member (x, y, t2, t4, t6) as pieces in the frame's units
    def pieces(self, x, y, t2=0.0, t4=0.0, t6=0.0):
        out = [(1.0, x - self.a0, self.a0), (0.0, t2, x)]
        if t4 > 0:
            out += [(-1.0, x, x), (0.0, t4, 0.0, self.Vu), (-1.0, -y, 0.0)]
        else:
            out.append((-1.0, x - y, x))
        out += [(0.0, t6, y), (1.0, self.af - y, y)]
        return out

    def position(self, *member):
        return integrate(self.pieces(*member), 0.0, self.v0, self.a0)[0]

    def duration(self, x, y, t2=0.0, t4=0.0, t6=0.0):
        return 2 * (x - y) + self.af - self.a0 + t2 + t4 + t6

    def top(self, crest):
        """x, t2 of the first half for a crest velocity (None below the first ramp's own).
        A crest within 16 u of the velocity scale below the lowest the first ramp reaches
        (x = max(a0, 0)) is on it: a start on the ramp into a cruise (or on it) reaches the
        bound exactly, but the rounded c0 may lie an ulp above, which the square root makes
        a gap of about vs u / x in x, beyond the member's tolerance."""
        d, b = crest - self.c0, max(self.a0, 0.0)
        if d < b * b <= d + 16 * EPS * self._vs():
            return b, 0.0
        if not d >= 0:
            return None
        return (math.sqrt(d), 0.0) if d <= self.Au ** 2 else (self.Au, (d - self.Au ** 2) / self.Au)

    def bottom(self, crest):
        """y, t6 of the last half for a crest velocity (None below the last ramp's own; on
        it within 16 u of the velocity scale, as for :meth:`top`)."""
        d, b = crest - self.cf, max(-self.af, 0.0)
        if d < b * b <= d + 16 * EPS * self._vs():
            return -b, 0.0
        if not d >= 0:
            return None
        return ((-math.sqrt(d), 0.0) if d <= self.Al ** 2
                else (self.Al, (d - self.Al ** 2) / -self.Al))

    def within(self, member, tol):
        """The member onto its case within tol (None when farther off): the pieces'
        durations >= 0, a hold only on a bound, every velocity at a = 0 and every
        acceleration within the bounds (checked on the motion)."""
        x, y, t2, t4, t6 = member
        if not all(math.isfinite(z) for z in member):
            return None
        ta, tt = tol * max(self.Au, -self.Al), tol * max(1.0, self._vs() / self.Au)
        if min(x - self.a0, self.af - y, x - y) < -ta or min(t2, t4, t6) < -tt:
            return None
        if (t2 > tt and abs(x - self.Au) > ta) or (t6 > tt and abs(y - self.Al) > ta) \
                or (t4 > tt and not (x > -ta and y < ta)):
            return None
        x, y = min(max(x, self.a0), self.Au), max(min(y, self.af), self.Al)
        if x < y:
            x = y = (x + y) / 2
        t2, t4, t6 = max(t2, 0.0), max(t4, 0.0), max(t6, 0.0)
        # the velocity where a passes zero on the middle ramp, from the motion itself
        p, v, a = 0.0, self.v0, self.a0
        for piece in self.pieces(x, y, t2, t4, t6)[:2]:
            p, v, a = _advance(p, v, piece[2], piece[0], piece[1])
        if x > 0 > y:
            crest = v + x * x / 2
            if crest > self.Vu + tol * self._vs():
                return None
            if crest > self.Vu:     # on the edge of the cruise: the member on the bound
                (x, t2), (y, t6) = self.top(self.Vu), self.bottom(self.Vu)
                x, y = max(x, self.a0), min(y, self.af)
        return x, y, t2, t4, t6

    def _vs(self):
        return max(self.Vu, -self.Vl, abs(self.v0), abs(self.vf))

    def reaches(self, member, pd):
        p, v, a, path = integrate(self.pieces(*member), 0.0, self.v0, self.a0)
        scale = path + self._vs() * self.duration(*member) + abs(pd)
        return (abs(p - pd) <= 16 * EPS * scale
                and abs(v - self.vf) <= 16 * EPS * (self._vs() + (self.Au - self.Al) ** 2)
                and abs(a - self.af) <= 16 * EPS * (self.Au - self.Al))

    # -------------------------------------------------------------- the cases' members
    def none(self, u):
        K = self.cf - self.c0
        return ((u + K / u) / 2, (K / u - u) / 2, 0.0, 0.0, 0.0)

    def acc0(self, y):
        return (self.Au, y, (self.cf - self.c0 + y * y - self.Au ** 2) / self.Au, 0.0, 0.0)

    def acc1(self, x):
        return (x, self.Al, 0.0, 0.0, (self.c0 + x * x - self.cf - self.Al ** 2) / -self.Al)

    def acc01(self, t2):
        t6 = (self.c0 + self.Au ** 2 - self.cf - self.Al ** 2 + self.Au * t2) / -self.Al
        return (self.Au, self.Al, t2, 0.0, t6)


def _safe(f):
    """f, with a value not formed (a division by zero at an end) as NaN."""
    def g(t):
        try:
            return f(t)
        except (ZeroDivisionError, OverflowError):
            return math.nan
    return g


def _fitted_roots(f, lo, hi, degree):
    """Real roots in [lo, hi] of f, a polynomial of the given degree: fitted through
    Chebyshev nodes, the companion matrix's real eigenvalues, each refined on f itself; over
    the whole interval and over its part within [-16, 16] (the scale of the motion itself,
    where a fit over a long interval would lose a root of a short motion)."""
    out = _fitted_roots_on(f, lo, hi, degree)
    a, b = max(lo, -16.0), min(hi, 16.0)
    if a < b and (a > lo or b < hi):
        for r in _fitted_roots_on(f, a, b, degree):
            if all(abs(r - q) > 1e-9 * max(1.0, abs(r)) for q in out):
                out.append(r)
    return out


def _fitted_roots_on(f, lo, hi, degree):
    f = _safe(f)
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
        return []
    if hi == lo:
        return [lo] if f(lo) == 0 else []
    k = np.arange(degree + 1)
    nodes = (lo + hi) / 2 + (hi - lo) / 2 * np.cos(np.pi * (k + 0.5) / (degree + 1))
    values = np.array([f(float(t)) for t in nodes])
    if not np.all(np.isfinite(values)):
        return []
    poly = np.polynomial.Polynomial.fit(nodes, values, degree, domain=[lo, hi])
    out = []
    width = hi - lo
    for r in poly.roots():
        if abs(r.imag) > 1e-6 * max(1.0, abs(r)) or not math.isfinite(r.real):
            continue
        t = float(r.real)
        if not lo - 1e-9 * width <= t <= hi + 1e-9 * width:
            continue
        out.append(_refine(f, min(max(t, lo), hi), width))
    return out


def _refine(f, t, width):
    """Newton steps on f with a centred difference, each kept only when it lowers |f|."""
    f = _safe(f)
    ft = f(t)
    if not math.isfinite(ft):
        return t
    for _ in range(8):
        h = 1e-7 * max(abs(t), width, 1e-300)
        d = (f(t + h) - f(t - h)) / (2 * h)
        if d == 0 or not math.isfinite(d) or ft == 0:
            break
        n = t - ft / d
        fn = f(n) if math.isfinite(n) else math.inf
        if not abs(fn) < abs(ft):
            break
        t, ft = n, fn
    return t


def _members_reaching(fr: _Frame):
    """Every member of the frame that reaches its target, as (duration, member)."""
    pd, out = fr.pd, []

    def keep(member):
        m = fr.within(member, SNAP)
        if m is not None and fr.reaches(m, pd):
            out.append((fr.duration(*m), m))

    # the cruise: the crest on the bound, the rest covered at Vu
    top, bottom = fr.top(fr.Vu), fr.bottom(fr.Vu)
    if top is not None and bottom is not None:
        (x, t2), (y, t6) = top, bottom
        t4 = (pd - fr.position(x, y, t2, 0.0, t6)) / fr.Vu
        if t4 >= 0:
            keep((x, y, t2, t4, t6))
    # no hold: u (P(u) - pd) is a quartic in u = x - y
    for u in _fitted_roots(lambda u: u * (fr.position(*fr.none(u)) - pd), 0.0, fr.Au - fr.Al, 4):
        if u > 0:
            keep(fr.none(u))
    # a hold at Au: a quartic in y; at Al: a quartic in x
    for y in _fitted_roots(lambda y: fr.position(*fr.acc0(y)) - pd, fr.Al, min(fr.af, fr.Au), 4):
        keep(fr.acc0(y))
    for x in _fitted_roots(lambda x: fr.position(*fr.acc1(x)) - pd, max(fr.a0, fr.Al), fr.Au, 4):
        keep(fr.acc1(x))
    # both holds: a quadratic in t2, fitted over the scale of its roots
    base = (fr.c0 + fr.Au ** 2 - fr.cf - fr.Al ** 2) / fr.Au
    h = max(abs(base), 1.0, math.sqrt(abs(pd) / fr.Au))
    f = lambda t2: fr.position(*fr.acc01(t2)) - pd     # noqa: E731
    e = [f(0.0), f(h), f(2 * h)]
    if all(math.isfinite(z) for z in e):
        for r in np.roots([(e[2] - 2 * e[1] + e[0]) / (2 * h * h), (4 * e[1] - 3 * e[0] - e[2]) / (2 * h),
                           e[0]]):
            if abs(r.imag) <= 1e-9 * max(1.0, abs(r)):
                keep(fr.acc01(_refine(f, float(r.real), h)))
    # a single ramp from a0 to af
    if fr.af >= fr.a0:
        keep((fr.af, fr.af, 0.0, 0.0, 0.0))
    return out


def _physical(fr: _Frame, member):
    """The member's pieces in seconds and the problem's units (jerk, duration, a_start[, v])."""
    out = []
    for piece in fr.pieces(*member):
        if not piece[1] > 0:
            continue
        q = (fr.s * piece[0] * fr.J, piece[1] * fr.tau, fr.s * piece[2] * fr.A)
        out.append(q + ((fr.s * piece[3] * fr.vu,) if len(piece) > 3 else ()))
    return out


def time_optimal(p0, v0, a0, pf, vf, af, lim: Limits):
    """(duration, pieces, durations) of the time-optimal motion, or None when no member is
    found. ``durations``: every member reaching the target, ascending (seconds)."""
    if pf - p0 == 0 and v0 == vf and a0 == af:
        return 0.0, [], [0.0]
    found = []
    for s in (1, -1):
        fr = _Frame(s, pf - p0, v0, a0, vf, af, lim)
        found += [(T * fr.tau, fr, m) for T, m in _members_reaching(fr)]
    found.sort(key=lambda c: c[0])
    vr, ar = lim.vmax - lim.vmin, lim.amax - lim.amin
    for T, fr, m in found:
        pieces = _physical(fr, m)
        p, v, a, path = integrate(pieces, p0, v0, a0)
        scale = path + abs(p0) + abs(pf) + vr * T
        if (abs(p - pf) <= 64 * EPS * scale and abs(v - vf) <= 64 * EPS * (vr + abs(v0) + abs(vf))
                and abs(a - af) <= 64 * EPS * ar):
            return T, pieces, [c[0] for c in found]
    return None


def farthest(v0, a0, vf, af, lim: Limits, T, s):
    """(displacement, pieces) of the member of duration T that ends farthest in direction s,
    or None when the family has no member that long."""
    if T == 0:
        return (0.0, []) if (v0 == vf and a0 == af) else None
    fr = _Frame(s, 0.0, v0, a0, vf, af, lim)
    Tn = T / fr.tau
    Au, Al, a0n, afn = fr.Au, fr.Al, fr.a0, fr.af
    candidates = []
    u = (Tn - (afn - a0n)) / 2
    if u > 0:
        candidates.append(fr.none(u))
    d = Au * Au + 0.5 * (-2 * Au * Au + 2 * Au * Tn + 2 * Au * (a0n - afn) + 2 * (fr.v0 - fr.vf)
                         - a0n ** 2 + afn ** 2)
    if d >= 0:
        candidates.append(fr.acc0(Au - math.sqrt(d)))
    d = Al * Al - 0.5 * (2 * Al * Al + 2 * Al * Tn + 2 * Al * (a0n - afn) + 2 * (fr.v0 - fr.vf)
                         - a0n ** 2 + afn ** 2)
    if d >= 0:
        candidates.append(fr.acc1(Al + math.sqrt(d)))
    S = Tn - (2 * Au - 2 * Al + afn - a0n)
    if S >= 0:
        R = fr.cf - fr.c0 + Al * Al - Au * Au
        t2 = (R - Al * S) / (Au - Al)
        candidates.append((Au, Al, t2, 0.0, S - t2))
    top, bottom = fr.top(fr.Vu), fr.bottom(fr.Vu)
    if top is not None and bottom is not None:
        (x, t2), (y, t6) = top, bottom
        t4 = Tn - fr.duration(x, y, t2, 0.0, t6)
        if t4 >= 0:
            candidates.append((x, y, t2, t4, t6))
    best = None
    for member in candidates:
        m = fr.within(member, 16 * EPS)
        if m is None or abs(fr.duration(*m) - Tn) > 16 * EPS * max(Tn, 1.0):
            continue
        p, v, a, _ = integrate(fr.pieces(*m), 0.0, fr.v0, fr.a0)
        if (abs(v - fr.vf) > 16 * EPS * (fr._vs() + (Au - Al) ** 2)
                or abs(a - fr.af) > 16 * EPS * (Au - Al)):
            continue
        if best is None or p > best[0]:
            best = (p, m)
    if best is None:
        return None
    pieces = _physical(fr, best[1])
    _, v, a, _ = integrate(pieces, 0.0, v0, a0)
    vr = lim.vmax - lim.vmin
    if abs(v - vf) > 64 * EPS * (vr + abs(v0) + abs(vf)) or abs(a - af) > 64 * EPS * (lim.amax - lim.amin):
        return None
    return s * best[0] * fr.vu * fr.tau, pieces


def velocity_change(v0, a0, vf, af, lim: Limits):
    """Pieces of the time-optimal change (v0, a0) -> (vf, af) within the acceleration bounds
    and jmax (position free): jerk +-J to a peak, a hold on the bound if reached, -+J."""
    J, best = lim.jmax, None
    for s in (1, -1):
        A = lim.amax if s > 0 else -lim.amin
        b0, bf, dv = s * a0, s * af, s * (vf - v0)
        x2 = J * dv + (b0 * b0 + bf * bf) / 2
        if x2 < 0:
            continue
        x, t2 = math.sqrt(x2), 0.0
        if x > A:
            x, t2 = A, (dv - (A * A - (b0 * b0 + bf * bf) / 2) / J) / A
        if x < max(b0, bf) - SNAP * A or t2 < -SNAP * max(1.0, abs(dv) / A) * A / J:
            continue
        x, t2 = max(x, b0, bf), max(t2, 0.0)
        T = (2 * x - b0 - bf) / J + t2
        if best is None or T < best[0]:
            pieces = [(s * J, (x - b0) / J, s * b0), (0.0, t2, s * x), (-s * J, (x - bf) / J, s * x)]
            best = (T, [p for p in pieces if p[1] > 0])
    return None if best is None else best[1]
