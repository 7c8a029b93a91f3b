# SPDX-License-Identifier: Apache-2.0
"""One rule for every error of the public API: a ParameterError's message starts with the
parameter it names (``.parameter``), as a whole name, and that parameter is one the call took
(``vmax[1]`` for an element of ``vmax``, ``stages[0]`` for a stage), or ``state`` / ``stages``
for what a method's object holds.

The sweep calls each public function and class with valid arguments in which one argument at a
time is replaced by a bad value (NaN, infinities, 0, negatives, 1e300, 1e-300, a string, a
boolean), and checks every ParameterError it raises."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import ParameterError, analysis, design, multi_axis, plants, reference
from smoothshaper.errors import starts_with_name
from smoothshaper.trajectory import BSpline, Generator, bspline_period, tuned_stage

BAD = (math.nan, math.inf, -math.inf, 0.0, -1.0, 1e300, 1e-300, -1e-300, "x", True)
Ts = 1e-3
LIMITS = dict(vmax=250.0, amax=5000.0, jmax=2e5)
STAGE_FIELDS = {"kind", "timing", "T", "sigma", "k", "wn", "zeta", "order", "tolerance",
                "notch_pole_zeta", "duration"}
STAGES = [sms.harmonic(T=0.05), sms.shaper("zv", wn=100.0, zeta=0.05)]

# (callable, keyword arguments that are valid together)
CALLS = [
    (sms.rectangular, dict(T=0.05)),
    (sms.harmonic, dict(T=0.05, k=1)),
    (sms.damped_harmonic, dict(T=0.05, sigma=-2.0)),
    (sms.exponential, dict(T=0.05, sigma=-20.0)),
    (sms.shaper, dict(kind="zv", wn=100.0, zeta=0.05)),
    (sms.shaper, dict(kind="ei", wn=100.0, zeta=0.05, tolerance=0.05)),
    (sms.shaper, dict(kind="zvn", wn=100.0, zeta=0.05, order=3)),
    (sms.notch, dict(wn=100.0, zeta=0.05, notch_pole_zeta=0.7)),
    (sms.for_mode, dict(kind="harmonic", wn=100.0, zeta=0.05)),
    (sms.design_for_mode, dict(kind="harmonic", wn=100.0, zeta=0.05, k=1)),
    (sms.identify_from_peaks, dict(t1=0.1, p1=1.0, t2=0.2, p2=0.5)),
    (sms.identify_from_record, dict(x=np.exp(-np.arange(400) * 1e-2) *
                                    np.cos(np.arange(400) * 0.3), Ts=Ts)),
    (sms.notch_pole_zeta_from_bandwidth, dict(wn=100.0, zeta=0.05, bandwidth=20.0)),
    (sms.Chain, dict(stages=STAGES, Ts=Ts)),
    (design.kinematic, dict(h=40.0, **LIMITS)),
    (design.kinematic, dict(h=40.0, **LIMITS, Ts=Ts, wn=100.0, zeta=0.05)),
    (Generator, dict(**LIMITS, Ts=Ts)),
    (Generator, dict(**LIMITS, Ts=Ts, wn=100.0, zeta=0.05, q0=1.0)),
    (multi_axis.MultiAxisGenerator, dict(vmax=[0.5, 0.4], amax=[5.0, 4.0], jmax=[200.0, 150.0],
                                         Ts=Ts)),
    (multi_axis.phase_duration, dict(delta=[0.3, 0.1], vmax=[0.5, 0.4], amax=[5.0, 4.0],
                                     jmax=[200.0, 150.0])),
    (multi_axis.multi_axis_move, dict(start=[0.0, 0.0], target=[0.3, 0.1], vmax=[0.5, 0.4],
                                      amax=[5.0, 4.0], jmax=[200.0, 150.0], Ts=Ts)),
    (BSpline, dict(degree=3, T=0.05, Ts=Ts)),
    (bspline_period, dict(wn=100.0, Ts=Ts)),
    (tuned_stage, dict(profile="polynomial", wn=100.0, zeta=0.05)),
    (analysis.prv, dict(stages=STAGES, wn=100.0, zeta=0.05, Ts=Ts)),
    (plants.mode, dict(wn=100.0, zeta=0.05)),
    (reference.filter, dict(stages=STAGES, x=np.ones(20), Ts=Ts)),
]


def _bad_values(value):
    """The bad values for an argument: scalars, and each bad scalar in place of an element of
    a sequence (``vmax=[0.5, nan]``)."""
    if isinstance(value, (list, np.ndarray)) and np.asarray(value).dtype.kind == "f":
        for bad in BAD:
            if isinstance(bad, float):
                v = np.array(value, dtype=float)
                v.flat[-1] = bad
                yield v
        yield "x"
        return
    if isinstance(value, list):         # a stage list
        yield from ([], "x", [1.0])
        return
    yield from BAD


def check(exc: ParameterError, allowed: set[str]) -> None:
    message = str(exc)
    assert starts_with_name(message, exc.parameter), (exc.parameter, message)
    base = re.split(r"[\[.]", exc.parameter, maxsplit=1)[0]
    assert base in allowed, (exc.parameter, message, allowed)


def _sweep():
    for func, kwargs in CALLS:
        for name, value in kwargs.items():
            for bad in _bad_values(value):
                yield func, kwargs, name, bad


@pytest.mark.parametrize("func, kwargs", CALLS,
                         ids=[f"{f.__name__}-{i}" for i, (f, _) in enumerate(CALLS)])
def test_every_refusal_starts_with_the_parameter_it_names(func, kwargs):
    func(**kwargs)                          # the valid call works
    refused = 0
    for name, value in kwargs.items():
        for bad in _bad_values(value):
            try:
                func(**{**kwargs, name: bad})
            except ParameterError as exc:
                refused += 1
                # a stage's field names the parameter of the stage it belongs to (README)
                check(exc, set(kwargs) | {"stages"} | (STAGE_FIELDS if "stages" in kwargs
                                                       else set()))
    assert refused, "no bad value was refused"


def test_methods_follow_the_rule():
    """The methods that take data: process, step, reset, set_state, start_from."""
    chain = sms.Chain(STAGES, Ts=Ts)
    gen = Generator(**LIMITS, Ts=Ts)
    xyz = multi_axis.MultiAxisGenerator(vmax=[0.5, 0.4], amax=[5, 4], jmax=[200, 150], Ts=Ts)
    NOT_SAMPLES = (math.nan, math.inf, -math.inf, 1e306, "x", True)
    calls = [(chain.process, "u", [[0.0, math.nan], "x", np.ones((2, 2))]),
             (chain.step, "x", NOT_SAMPLES), (chain.reset, "rest", NOT_SAMPLES),
             (chain.set_state, "state", [np.ones(3), [math.nan] * chain.state_size, "x"]),
             (gen.process, "targets", [[0.0, math.inf], "x"]),
             (gen.reset, "position", [math.nan, "x"]),
             (gen.set_state, "state", [np.ones(3), "x"]),
             (gen.start_from, "v", [1e300, math.nan]),
             (xyz.process, "targets", [[[0.0, math.nan]], "x"]),
             (xyz.set_state, "state", [np.ones(3), "x"])]
    for method, name, values in calls:
        for bad in values:
            with pytest.raises(ParameterError) as info:
                method(**{name: bad}) if name != "v" else method(0.0, v=bad)
            check(info.value, {name, "state", "q", "a", "target"})


@pytest.mark.parametrize("parameter, message, expected", [
    ("amax", "vmax=1e+300, amax=1.0: vmax/amax too long", "amax: vmax=1e+300"),
    ("T", "Ts=0.1 is too coarse", "T: Ts=0.1"),
    ("T", "T must be > 0", "T must be > 0"),
    ("vmax[1]", "vmax[1]=nan must be finite", "vmax[1]=nan"),
])
def test_the_constructor_keeps_the_rule(parameter, message, expected):
    assert str(ParameterError(parameter, message)).startswith(expected)


def test_the_examples_that_broke_it():
    """Generator(vmax=1e300) names amax and starts with it; kinematic's ratio messages start
    with the bound they name, not with "h/vmax"."""
    with pytest.raises(ParameterError) as info:
        Generator(vmax=1e300, amax=1.0, jmax=1.0, Ts=Ts)
    assert info.value.parameter == "amax" and str(info.value).startswith("amax=1.0, vmax=1e+300")
    with pytest.raises(ParameterError) as info:
        design.kinematic(h=1e-300, vmax=1e300)
    assert info.value.parameter == "vmax" and str(info.value).startswith("vmax=1e+300 with h=")
