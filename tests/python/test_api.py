# SPDX-License-Identifier: Apache-2.0
"""One consistent Python API: ParameterError everywhere, plain numbers in messages, no silent
casts of complex/boolean/text input, case-insensitive names, lazy submodules, ``__all__`` in
every public module, one name per concept (import cycles and layers: test_layers_python.py)."""
from __future__ import annotations

import importlib
import pathlib
import subprocess
import sys
import warnings

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import ParameterError

PACKAGE = pathlib.Path(sms.__file__).parent
Ts = 1e-3


def raises(parameter: str, func, *args, **kwargs) -> ParameterError:
    """``func`` raises ParameterError (a ValueError) naming ``parameter``, with a message that
    starts with it and shows no NumPy scalar reprs."""
    with pytest.raises(ParameterError) as info:
        func(*args, **kwargs)
    exc = info.value
    assert isinstance(exc, ValueError)
    assert exc.parameter == parameter, (exc.parameter, str(exc))
    assert str(exc).startswith(parameter), str(exc)
    assert "np." not in str(exc) and "float64(" not in str(exc), str(exc)
    return exc


# -- the examples that used to fail ----------------------------------------------------------

def test_stage_constructors_raise_parameter_error():
    raises("zeta", sms.shaper, "zv", wn=100, zeta=1.2)
    raises("wn", sms.shaper, "zv", wn=-1.0)
    raises("T", sms.harmonic, T=-1.0)
    raises("sigma", sms.exponential, T=0.1, sigma=0.5)
    raises("k", sms.harmonic, T=0.1, k=2)
    raises("order", sms.shaper, "zvn", wn=100, order=9)
    raises("tolerance", sms.shaper, "ei", wn=100, tolerance=1.5)
    raises("notch_pole_zeta", sms.notch, wn=100, zeta=0.5, notch_pole_zeta=0.1)
    raises("kind", sms.Stage, "wobble")
    raises("timing", sms.rectangular, T=0.1, timing="sloppy")
    raises("discretization", sms.notch, wn=100, discretization="euler")


def test_messages_show_plain_numbers():
    exc = raises("T", sms.harmonic, T=np.float64("nan"))
    assert str(exc) == "T must be finite, got nan"
    exc = raises("zeta", sms.shaper, "zv", wn=100, zeta=np.float64(1.5))
    assert str(exc).endswith("got 1.5")
    exc = raises("u", sms.Chain(sms.harmonic(T=0.01), Ts=Ts).process, [0.0, np.nan])
    assert "u[1] = nan" in str(exc)


@pytest.mark.parametrize("value", [True, False, np.bool_(True), 1 + 2j, np.complex128(1),
                                   "0.1", None, [0.1]])
def test_scalars_refuse_bool_complex_and_text(value):
    exc = raises("T", sms.harmonic, T=value)
    assert "must be a real number" in str(exc)


@pytest.mark.parametrize("call, parameter", [
    (lambda h: sms.harmonic(T=h), "T"),
    (lambda h: sms.design.kinematic(h=h, vmax=1.0), "h"),
    (lambda h: sms.design.kinematic(h=1.0, vmax=1.0, amax=2, jmax=3, Ts=h), "Ts"),
    (lambda h: sms.Chain(sms.harmonic(T=0.1), Ts=h), "Ts")])
def test_an_int_beyond_the_largest_float_is_named(call, parameter):
    """float(10**400) raises OverflowError; every scalar check turns it into the parameter's
    error (the int's size in bits, never its 400 digits)."""
    exc = raises(parameter, call, 10 ** 400)
    assert "1329 bits" in str(exc) and len(str(exc)) < 200


@pytest.mark.parametrize("call, parameter", [
    (lambda n: sms.harmonic(T=0.1, k=n), "k"),
    (lambda n: sms.harmonic(T=0.1, k=-n), "k"),
    (lambda n: sms.Chain(sms.rectangular(T=0.1, k=n), Ts=Ts), "k"),
    (lambda n: sms.design_for_mode("harmonic", wn=100.0, k=n), "k"),
    (lambda n: sms.for_mode("rectangular", wn=100.0, k=n), "k"),
    (lambda n: sms.Chain(sms.harmonic(T=0.1), Ts=Ts).impulse_response(n), "n")])
def test_a_huge_int_is_shown_by_its_size(call, parameter):
    """An integer parameter of 10**400 is refused with its size in bits, not its 401 digits
    (for_mode and impulse_response raised OverflowError from float())."""
    exc = raises(parameter, call, 10 ** 400)
    assert ("1329 bits" in str(exc) or "2^1328" in str(exc)) and len(str(exc)) < 200, str(exc)


def test_for_mode_names_wn_when_the_period_is_beyond_a_float():
    """The length for_mode derives from wn is not a parameter the caller gave: a mode too slow
    for a float period names wn, not T."""
    exc = raises("wn", sms.for_mode, "harmonic", wn=1e-308)
    assert "1e-308" in str(exc)
    raises("wn", sms.for_mode, "rectangular", wn=5e-324, zeta=0.9)     # wd underflows to 0
    raises("k", sms.for_mode, "rectangular", wn=1e-300, k=10 ** 10)
    assert sms.for_mode("harmonic", wn=100.0, k=3).T == 3 * 3 * np.pi / 100.0


@pytest.mark.parametrize("bad", [np.array([0.0, np.longdouble("1e4000")], dtype=np.longdouble),
                                 np.array([0.0, np.inf], dtype=np.float16)])
def test_extended_and_half_precision_overflow_is_named(bad):
    """A longdouble beyond the largest double is the parameter's error, with no RuntimeWarning
    from the cast on the way."""
    chain = sms.Chain(sms.harmonic(T=0.01), Ts=Ts)
    chain.process(np.linspace(0.0, 1.0, 20))
    before = chain.get_state()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        exc = raises("u", chain.process, bad)
        raises("x", sms.identify_from_record, bad, Ts=Ts)
    assert "u[1] = inf" in str(exc)
    assert np.array_equal(chain.get_state(), before)


def test_duration_names_what_is_not_a_stage():
    """design.duration summed ``.T`` of anything: a float16 array (whose .T is itself) gave
    inf, other values an AttributeError or TypeError."""
    stages = [sms.harmonic(T=0.1), sms.rectangular(T=0.2)]
    assert sms.design.duration(stages) == pytest.approx(0.3)
    assert sms.design.duration(stages[0]) == 0.1
    raises("stages[1]", sms.design.duration, [stages[0], 0.2])
    raises("stages[0]", sms.design.duration, np.array([1.0, np.inf], dtype=np.float16))
    raises("stages", sms.design.duration, None)
    exc = raises("stages[0]", sms.Chain, [np.float16(1.0)], Ts=Ts)
    assert "got 1.0" in str(exc)


def test_integers_refuse_bool_and_fractions():
    raises("k", sms.harmonic, T=0.1, k=True)
    raises("k", sms.harmonic, T=0.1, k=1.5)
    assert sms.harmonic(T=0.1, k=np.int64(3)).k == 3
    assert sms.harmonic(T=0.1, k=3.0).k == 3


@pytest.mark.parametrize("bad", [np.ones(4) + 1j, np.ones(4, dtype=bool), ["a", "b"]])
def test_signals_refuse_complex_boolean_and_text(bad):
    chain = sms.Chain(sms.harmonic(T=0.01), Ts=Ts)
    before = chain.get_state()
    raises("u", chain.process, bad)
    assert np.array_equal(chain.get_state(), before)          # state untouched
    raises("x", sms.reference.filter, sms.harmonic(T=0.01), bad, Ts=Ts)


def test_other_entry_points_raise_parameter_error():
    raises("Ts", sms.Chain, sms.harmonic(T=0.01), Ts=0.0)
    raises("Ts", sms.Chain, sms.harmonic(T=0.01), Ts=True)
    raises("stages[1]", sms.Chain, [sms.harmonic(T=0.01), "zv"], Ts=Ts)
    raises("precision", sms.Chain, sms.harmonic(T=0.01), Ts=Ts, precision="half")
    raises("state", sms.Chain(sms.harmonic(T=0.01), Ts=Ts).set_state, np.zeros(3) + 1j)
    raises("n", sms.Chain(sms.harmonic(T=0.01), Ts=Ts).impulse_response, 0)
    raises("kind", sms.design_for_mode, "wobble", wn=100.0)
    raises("k", sms.design_for_mode, "harmonic", wn=100.0, k=True)
    raises("wn", sms.for_mode, "harmonic", wn=0.0)
    raises("t2", sms.identify_from_peaks, t1=1.0, p1=2.0, t2=0.5, p2=1.0)
    raises("Ts", sms.identify_from_record, np.ones(50), Ts=-1.0)
    raises("h", sms.design.kinematic, h=0.0, vmax=1.0)
    raises("profile", sms.design.kinematic, h=1.0, vmax=1.0, profile="cubic")
    raises("vmax", sms.trajectory.Generator, vmax=-1.0, amax=1.0, jmax=1.0, Ts=Ts)
    raises("degree", sms.trajectory.BSpline, degree=True, T=0.1, Ts=Ts)
    raises("via", sms.trajectory.bspline_reference, [[1 + 1j], [2]], degree=3, T=0.1, Ts=Ts)
    raises("wn", sms.analysis.mode_poles, -1.0, 0.0)
    raises("w", sms.analysis.frequency_response, sms.harmonic(T=0.1), [1 + 1j])
    raises("tolerance", sms.analysis.insensitivity, sms.harmonic(T=0.1), wn_hat=30.0,
           tolerance=2.0)
    raises("u", sms.plants.simulate_zoh, sms.plants.mode(wn=10.0), np.ones(4) + 1j, Ts=Ts)
    raises("oversample", sms.plants.simulate_zoh, sms.plants.mode(wn=10.0), np.ones(4), Ts=Ts,
           oversample=True)
    raises("t", sms.reference.harmonic_trajectory, [1j], T=1.0)


# -- case-insensitive names ------------------------------------------------------------------

def test_kind_names_are_case_insensitive():
    assert sms.shaper("ZV", wn=100.0) == sms.shaper("zv", wn=100.0)
    assert sms.for_mode("Damped_Harmonic", wn=100.0, zeta=0.1).kind == "damped_harmonic"
    assert sms.Stage("ZVD", wn=100.0).kind == "zvd"
    assert sms.Stage("notch", wn=100.0).kind == "notch_matched"
    assert sms.design_for_mode("EI", wn=100.0).kind == "ei"
    assert sms.notch(wn=100.0, discretization="Tustin").kind == "notch_tustin"
    assert sms.rectangular(T=0.1, timing="PAPER").timing == "paper"
    assert sms.Chain(sms.harmonic(T=0.01), Ts=Ts, precision="Float").precision == "float"
    assert sms.design.kinematic(h=1.0, vmax=1.0, amax=10.0, profile="Trigonometric")[-1].kind \
        == "harmonic"


# -- one name per concept ----------------------------------------------------------------------

def test_state_is_get_state_set_state_everywhere():
    chain = sms.Chain(sms.harmonic(T=0.01), Ts=Ts)
    gen = sms.trajectory.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=Ts)
    gen.process(np.full(20, 1.0))
    saved = gen.get_state()
    twin = sms.trajectory.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=Ts)
    twin.set_state(saved)
    assert np.array_equal(twin.process(np.full(50, 1.0)), gen.process(np.full(50, 1.0)))
    assert callable(chain.get_state) and callable(chain.set_state)
    raises("state", twin.set_state, saved[:-1])


def test_notch_pole_damping_has_one_name():
    stage = sms.notch(wn=100.0, zeta=0.02, notch_pole_zeta=0.5)
    assert stage.notch_pole_zeta == 0.5
    with pytest.warns(DeprecationWarning):
        assert sms.notch(wn=100.0, zeta=0.02, pole_zeta=0.5) == stage


def test_cli_tolerance_has_one_flag(capsys):
    from smoothshaper.cli import build_parser
    for argv in (["design", "--kind", "ei", "--wn", "100", "--tolerance", "0.1"],
                 ["analyze", "--kind", "ei", "--wn", "100", "--tolerance", "0.1"]):
        assert build_parser().parse_args(argv).tolerance == 0.1
    with pytest.raises(SystemExit):
        build_parser().parse_args(["design", "--help"])
    text = capsys.readouterr().out
    assert "--tolerance" in text and "--shaper-tolerance" not in text


# -- module structure ------------------------------------------------------------------------

def _modules() -> list[str]:
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out.append(".".join(parts))
    return out


def _public(name: str) -> bool:
    return not any(p.startswith("_") for p in name.split(".")[1:]) and name.split(".")[-1] \
        not in ("__main__",)


def test_submodules_are_attributes_loaded_lazily():
    code = ("import sys, smoothshaper as sms; assert 'smoothshaper.design' not in sys.modules; "
            "assert sms.design.kinematic; assert 'smoothshaper.design' in sys.modules; "
            "assert sms.analysis.prv and sms.plants.mode and sms.trajectory.Generator; "
            "assert 'design' in dir(sms)")
    subprocess.run([sys.executable, "-c", code], check=True)
    with pytest.raises(AttributeError):
        sms.no_such_thing  # noqa: B018


@pytest.mark.parametrize("name", [m for m in _modules() if _public(m)])
def test_every_public_module_declares_all(name):
    module = importlib.import_module(name) if "validation" not in name else \
        pytest.importorskip(name)
    assert hasattr(module, "__all__"), name
    for item in module.__all__:
        assert hasattr(module, item), (name, item)
    leaked = {"np", "math", "dataclass", "os", "sys", "annotations"} & set(module.__all__)
    assert not leaked, (name, leaked)


def _check_calls(func) -> dict[str, int]:
    """How often ``func()`` runs each argument check of the package (by code object, so
    every module's imported name counts): a stage, a stage list, Ts, a Stage's own
    validation, a mode's wn and zeta, a limit array."""
    from smoothshaper import _checks, stages
    from smoothshaper.reference import _checks as ref_checks, shapers
    watched = {ref_checks.check_stage.__code__: "stage", ref_checks.as_stage_list.__code__:
               "stage", ref_checks.check_Ts.__code__: "Ts",
               stages.Stage.__post_init__.__code__: "Stage.__post_init__",
               shapers.mode_pole.__code__: "mode_pole", _checks.real_array.__code__: "real_array"}
    counts = dict.fromkeys(watched.values(), 0)

    def profile(frame, event, arg):
        if event == "call" and frame.f_code in watched:
            counts[watched[frame.f_code]] += 1
    sys.setprofile(profile)
    try:
        func()
    finally:
        sys.setprofile(None)
    return counts


def test_public_calls_check_their_arguments_once():
    """The checks are done where a call enters the package; the inner layers trust them.
    analysis.prv used to check its stage 8 times, Ts twice and the stage's mode 3 times on
    the way down; reference.filter a chain of three 22, 7 and 6 times."""
    zv, chain = sms.shaper("zv", wn=100.0, zeta=0.05), [
        sms.damped_harmonic(T=0.0504, sigma=-3.0), sms.shaper("zvd", wn=100.0), sms.notch(wn=200.0)]
    once = {"stage": 1, "Ts": 1, "Stage.__post_init__": 0, "mode_pole": 0}
    for call in (lambda: sms.analysis.prv(zv, wn=100.0, zeta=0.05, Ts=Ts),
                 lambda: sms.analysis.prv(chain, wn=100.0, Ts=Ts),
                 lambda: sms.reference.impulse_response(zv, Ts=Ts),
                 lambda: sms.reference.filter(chain, np.ones(20), Ts=Ts),
                 lambda: sms.reference.filter_zi(chain, Ts=Ts),
                 lambda: sms.analysis.ChainResponse(chain, Ts=Ts)):
        counts = _check_calls(call)
        assert {k: counts[k] for k in once} == once, counts
    assert _check_calls(lambda: sms.for_mode("damped_harmonic", wn=100.0, zeta=0.1)
                        )["Stage.__post_init__"] == 0
    limits = dict(vmax=np.array([1.0, 2.0]), amax=10.0, jmax=np.array([100.0, 300.0]))
    assert _check_calls(lambda: sms.multi_axis.phase_duration(np.array([0.1, 0.2]), **limits)
                        )["real_array"] == 4         # delta and each limit, once
    plain = dict(vmax=[1.0, 2.0], amax=10.0, jmax=[100.0, 300.0])     # checked in C
    assert _check_calls(lambda: sms.multi_axis.phase_duration([0.1, 0.2], **plain)
                        )["real_array"] == 0
    assert _check_calls(lambda: sms.trajectory.generator_reference(
        np.ones(5), vmax=1.0, amax=10.0, jmax=200.0, Ts=Ts, wn=100.0))["stage"] == 0


def test_package_import_emits_no_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        subprocess.run([sys.executable, "-W", "error", "-c", "import smoothshaper"], check=True)


def test_every_subcommand_has_a_description_without_markup():
    import argparse
    from smoothshaper.cli import build_parser
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert set(sub.choices) >= {"design", "analyze", "identify", "validate", "report"}
    for name, p in sub.choices.items():
        assert p.description and len(p.description) > 40, name
        for text in (p.description, p.format_help(), parser.format_help()):
            assert ":class:" not in text and "``" not in text and "issue " not in text, name


def test_masked_entries_are_refused_not_read_under_the_mask():
    """np.asarray of a masked array takes the values under the mask: a masked sample was
    filtered as if it were data."""
    chain = sms.Chain(sms.harmonic(T=0.01), Ts=Ts)
    before = chain.get_state()
    raises("u", chain.process, np.ma.array([1.0, 2.0, 3.0], mask=[0, 1, 0]))
    assert np.array_equal(chain.get_state(), before)
    raises("w", sms.analysis.frequency_response, sms.harmonic(T=0.1),
           np.ma.array([1.0, 2.0], mask=[1, 0]))
    y = chain.process(np.ma.array([1.0, 2.0], mask=[0, 0]))      # nothing masked: accepted
    assert y.shape == (2,)


def test_a_notch_band_refused_for_its_size_says_which_way():
    """A band 20 rad/s wide at wn = 1e308 rounds onto zeta (too narrow); the message said the
    bandwidth must be 'narrower than the notch allows'."""
    exc = raises("bandwidth", sms.notch_pole_zeta_from_bandwidth, wn=1e308, bandwidth=20.0)
    assert "too narrow" in str(exc)
    exc = raises("bandwidth", sms.notch_pole_zeta_from_bandwidth, wn=100.0, bandwidth=1e300)
    assert "too wide" in str(exc)
    assert sms.notch_pole_zeta_from_bandwidth(wn=100.0, bandwidth=20.0) == pytest.approx(0.1)


def test_status_helpers_name_a_status_that_is_not_an_integer():
    """status_string(10**40) raised cffi's OverflowError, 'x' a ValueError from int(), 1.5
    was truncated to 1 and True taken as 1."""
    from smoothshaper import filters
    for bad in ("x", None, np.nan, 1.5, True):
        raises("status", filters.status_string, bad)
        raises("status", filters.raise_for_status, bad, context="here")
    assert filters.status_string(10 ** 40) == "unknown status"
    assert filters.status_string(np.int8(-3)) == filters.status_string(-3)
    filters.raise_for_status(0, context="here")


def test_timedelta_and_huge_fractions_are_named():
    """np.timedelta64 is a NumPy integer whose float() raises TypeError (it escaped the shared
    check); a Fraction beyond the largest float was reported as 'an int of 1328 bits'."""
    from fractions import Fraction
    exc = raises("T", sms.harmonic, T=np.timedelta64(5, "ms"))
    assert "real number" in str(exc)
    raises("k", sms.harmonic, T=0.1, k=np.timedelta64(3, "ms"))
    raises("h", sms.design.kinematic, h=np.timedelta64(5, "ms"), vmax=1.0)
    exc = raises("T", sms.harmonic, T=Fraction(10 ** 400, 3))
    assert "Fraction beyond the largest float" in str(exc)
    raises("k", sms.harmonic, T=0.1, k=Fraction(10 ** 400, 3))
    assert sms.harmonic(T=Fraction(1, 10)).T == 0.1


def test_an_endless_iterator_is_refused_not_drained():
    """higher=itertools.repeat(1.0) and stages=itertools.repeat(stage) were read forever."""
    import itertools
    import time
    t = time.process_time()
    exc = raises("higher", sms.design.kinematic, h=1.0, vmax=1.0, amax=1.0, jmax=1.0,
                 higher=itertools.repeat(1.0))
    assert "or more" in str(exc)
    raises("higher", sms.design.kinematic_lengths, h=1.0, vmax=1.0, amax=1.0, jmax=1.0,
           higher=itertools.count(1))
    stage = sms.harmonic(T=0.01)
    raises("stages", sms.Chain, itertools.repeat(stage), Ts=Ts)
    raises("stages", sms.design.duration, itertools.repeat(stage))
    raises("stages", sms.multi_axis.MultiAxisGenerator, vmax=1.0, amax=1.0, jmax=1.0, Ts=Ts,
           stages=itertools.repeat(stage))
    assert time.process_time() - t < 5
    assert sms.Chain(iter([stage, stage]), Ts=Ts).length > 0
