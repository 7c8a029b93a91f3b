# SPDX-License-Identifier: Apache-2.0
"""The tuning's validated fast paths give the same Stages, errors and floats as the checked
and written-out forms they replace."""
import math

import numpy as np
import pytest

from smoothshaper import ParameterError
from smoothshaper.stages import Stage, _with_mode, for_mode, shaper
from smoothshaper.calibrate import candidates as cand
from smoothshaper.calibrate.objectives import SpectralObjective, _from_end, stages_R2
from smoothshaper.calibrate.design_memo import impulses, smoother_R

_FIELDS = [f for f in Stage.__slots__]


def _same(a, b):
    assert a == b and hash(a) == hash(b) and repr(a) == repr(b)
    for name in _FIELDS:
        assert type(getattr(a, name)) is type(getattr(b, name)), name


@pytest.mark.parametrize("kind,kw", [("zv", {}), ("mzv", {}), ("ei3", {}), ("zvn", {"order": 4}),
                                     ("gmzv", {"order": 5, "duration": 1.3}),
                                     ("si", {"order": 5, "duration": 1.5})])
def test_with_mode_equals_checked_shaper(kind, kw):
    first = shaper(kind, wn=200.0, zeta=0.05, **kw)
    for wn, zeta in ((237.1, np.float64(0.1034)), (np.float64(1e3), 0.0), (1.0, 0.99)):
        d = kw.get("duration")
        got = _with_mode(first, wn, zeta, None if d is None else np.float64(d * 1.1))
        want = shaper(kind, wn=wn, zeta=zeta, **({**kw, "duration": np.float64(d * 1.1)}
                                                 if d is not None else kw))
        _same(got, want)


@pytest.mark.parametrize("kind", ["smooth_zv", "smooth_si"])
def test_with_mode_equals_checked_input_smoother(kind):
    first = for_mode(kind, wn=200.0, zeta=0.05)
    _same(_with_mode(first, 251.3, np.float64(0.2)), for_mode(kind, wn=251.3, zeta=0.2))


@pytest.mark.parametrize("kind,kw,wn,zeta,dur,field", [
    ("zv", {}, -1.0, 0.1, None, "wn"), ("zv", {}, math.nan, 0.1, None, "wn"),
    ("zv", {}, 100.0, 1.0, None, "zeta"), ("zv", {}, 100.0, -1e-12, None, "zeta"),
    ("smooth_zv", None, 100.0, 0.26, None, "zeta"),
    ("gmzv", {"order": 4, "duration": 1.0}, 100.0, 0.1, 1.5, "duration"),
    ("gmzv", {"order": 4, "duration": 1.0}, 100.0, 0.1, 0.0, "duration"),
    ("si", {"order": 3, "duration": 0.75}, 100.0, 0.1, 0.49, "duration"),
    ("si", {"order": 3, "duration": 0.75}, 100.0, 0.1, math.inf, "duration")])
def test_with_mode_refuses_as_the_constructor(kind, kw, wn, zeta, dur, field):
    if kw is None:
        first = for_mode(kind, wn=200.0, zeta=0.05)

        def checked():
            return for_mode(kind, wn=wn, zeta=zeta)
    else:
        first = shaper(kind, wn=200.0, zeta=0.05, **kw)

        def checked():
            return shaper(kind, wn=wn, zeta=zeta, **({**kw, "duration": dur} if dur is not None
                                                     else kw))
    with pytest.raises(ParameterError) as want:
        checked()
    with pytest.raises(ParameterError) as got:
        _with_mode(first, wn, zeta, dur)
    assert got.value.parameter == want.value.parameter == field
    assert str(got.value) == str(want.value)
    assert first == (for_mode(kind, wn=200.0, zeta=0.05) if kw is None
                     else shaper(kind, wn=200.0, zeta=0.05, **kw))   # untouched


def test_with_mode_refuses_other_kinds():
    with pytest.raises(ParameterError) as e:
        _with_mode(for_mode("harmonic", wn=100.0), 100.0, 0.0)
    assert e.value.parameter == "kind"


def test_family_builds_equal_checked_stages():
    fams = {f.name: f for f in cand.families(2)}
    p = [237.1, np.float64(0.1), 530.0, np.float64(0.16)]
    _same(fams["mzv"].build(p)[0], shaper("mzv", wn=p[0], zeta=p[1]))
    _same(fams["mzv"].build(p)[0], shaper("mzv", wn=p[0], zeta=p[1]))   # the copy path
    _same(fams["zv+zv"].build(p)[1], shaper("zv", wn=p[2], zeta=p[3]))
    _same(fams["zv+zv"].build(p)[1], shaper("zv", wn=p[2], zeta=p[3]))
    q = [237.1, np.float64(0.1), np.float64(0.9)]
    for _ in range(2):
        _same(fams["si (n=3)"].build(q)[0], shaper("si", wn=q[0], zeta=q[1], order=3,
                                                    duration=q[2]))
    fams["gmzv (n=4)"].build([237.1, 0.1, 1.0])
    with pytest.raises(ParameterError):
        fams["gmzv (n=4)"].build([237.1, 0.1, 1.6])


def _spectral():
    rng = np.random.default_rng(7)
    f = np.linspace(5.0, 120.0, 300)
    P = np.exp(-0.5 * ((f - 38.0) / 2.0) ** 2) + 0.3 * np.exp(-0.5 * ((f - 64.0) / 3.0) ** 2) \
        + 0.01 * rng.random(f.size)
    return SpectralObjective(f, P, zetas=(0.05, 0.1, 0.15), group_hz=0.8)


def _written_out(obj, R2, L):
    # the score as written before its terms were held: the same floats are required
    R2e = _from_end(R2, obj.poles, L).reshape(obj.n, obj.nz)
    R = np.sqrt(np.maximum(R2e, 0.0))
    left = np.maximum(R * obj.P[:, None] - obj.tau, 0.0).sum(axis=0)
    v = 100.0 * float(left.max()) / obj.den if obj.den > 0 else 0.0
    return v + 0.1 * math.sqrt(max(float(obj.tune_S @ R2e.mean(axis=1)), 0.0))


def test_tuning_value_same_floats():
    obj = _spectral()
    for kind, L in (("mzv", 0.0192), ("zv", 0.0), ("ei", 0.031)):
        for wn in (220.0, 246.74, 300.0):
            R2 = stages_R2([shaper(kind, wn=wn, zeta=0.1)], obj.poles)
            assert obj.tuning_value(R2, L) == _written_out(obj, R2, L)
    R2 = np.ones(obj.poles.size)
    R2[3] = np.nan
    assert math.isnan(obj.tuning_value(R2, 0.01)) and math.isnan(_written_out(obj, R2, 0.01))


def test_tuning_values_same_floats_as_tuning_value():
    obj = _spectral()
    designs = [shaper("mzv", wn=wn, zeta=0.1) for wn in (200.0, 246.74, 290.0)]
    R2 = np.stack([stages_R2([s], obj.poles) for s in designs], axis=1)
    L = np.array([0.02, 0.0192, 0.015])
    got = obj.tuning_values(R2, L)
    R2e = R2 * np.exp(2.0 * np.real(obj.poles)[:, None] * L[None, :])
    R = np.sqrt(np.maximum(R2e, 0.0)).reshape(obj.n, obj.nz, -1)
    left = np.maximum(R * obj.P[:, None, None] - obj.tau, 0.0).sum(axis=0)
    want = 100.0 * left.max(axis=0) / obj.den + 0.1 * np.sqrt(np.maximum(
        obj.tune_S @ (R2e.reshape(obj.n, obj.nz, -1).sum(axis=1) / obj.nz), 0.0))
    assert np.array_equal(got, want)


def test_tuning_terms_follow_replaced_poles():
    obj = _spectral()
    R2 = np.full(obj.poles.size, 0.5)
    obj.tuning_value(R2, 0.02)
    obj.poles = obj.poles * 1.1
    assert obj.tuning_value(R2, 0.02) == _written_out(obj, R2, 0.02)


def test_stages_R2_same_floats():
    poles = _spectral().poles
    chains = [[shaper("zv", wn=240.0, zeta=0.1)],
              [shaper("zv", wn=240.0, zeta=0.1), shaper("mzv", wn=530.0, zeta=0.16)],
              [for_mode("smooth_zv", wn=240.0, zeta=0.1)],
              [for_mode("rectangular", wn=240.0, zeta=0.1), shaper("zv", wn=240.0, zeta=0.1)]]
    from smoothshaper.reference.continuous import transfer_unchecked
    for stages in chains:
        H = np.ones(poles.size, dtype=complex)
        for s in stages:
            if s.kind in ("zv", "mzv"):
                A, t = impulses(s)
                H *= np.exp(-np.outer(poles, t)) @ A
            elif s.kind == "smooth_zv":
                H *= smoother_R(s, poles)
            else:
                H *= transfer_unchecked(s, poles)
        assert np.array_equal(stages_R2(stages, poles), np.abs(H) ** 2)
    assert np.array_equal(stages_R2([], poles), np.ones(poles.size))
