# SPDX-License-Identifier: Apache-2.0
"""smoothshaper.fmi: the co-simulation timing model, checked on hand-computed cases, and
the report of a full run (the FMUs built by the FMU tests' fixture)."""
from __future__ import annotations

import shutil

import numpy as np
import pytest

from smoothshaper import fmi
from smoothshaper.stages import rectangular
from fmu_builds import fmu_build_dir


def test_tick_inputs_for_a_step_that_is_not_a_multiple_of_Ts():
    # Ts = 1, h = 2.5: ticks 1, 2 in the first step (u = 0), 3..5 in the second (u = 1), 6, 7 in
    # the third (u = 2); tick 5 sits exactly on t = 5, the end of the second step.
    x, n_at = fmi.tick_inputs(np.array([0.0, 2.5, 5.0, 7.5]), np.array([0.0, 1, 2, 3]), Ts=1.0)
    assert n_at.tolist() == [0, 2, 5, 7]
    assert x.tolist() == [0, 0, 1, 1, 1, 2, 2]


def test_expected_output_is_the_last_ticks_output():
    # Moving average of 2 taps over x = 0 0 1 1 1 2 2: y = 0 0 .5 1 1 1.5 2; read at ticks 2, 5, 7.
    y = fmi.expected_output([rectangular(T=2.0)], np.array([0.0, 2.5, 5.0, 7.5]),
                                   np.array([0.0, 1, 2, 3]), Ts=1.0)
    assert y.tolist() == [0.0, 0.0, 1.0, 2.0]


def test_expected_output_starts_at_the_rest_point_and_keeps_it_without_ticks():
    # h = 0.4 Ts: the first two communication points have no tick yet.
    t = np.arange(6) * 0.4
    y = fmi.expected_output([rectangular(T=1.0)], t, np.array([3.0, 5, 5, 5, 5, 5]), Ts=1.0)
    assert y.tolist() == [3.0, 3.0, 3.0, 5.0, 5.0, 5.0]   # tick 1 (t = 1) uses u(0.8) = 5


def test_start_values_switch_unused_stages_off():
    values = fmi.start_values([rectangular(T=0.01)], Ts=1e-3)
    assert values["stage[0].kind"] == 0 and values["stage[0].T"] == 0.01
    assert all(values[f"stage[{k}].kind"] == -1 for k in range(1, 8))
    with pytest.raises(ValueError, match="stages"):
        fmi.start_values([rectangular(T=0.01)] * 9, Ts=1e-3)


def test_run_writes_a_passing_report(tmp_path):
    pytest.importorskip("fmpy", reason="fmpy is needed to simulate the FMUs")
    pytest.importorskip("matplotlib", reason="the report draws plots")
    if shutil.which("cmake") is None:
        pytest.skip("cmake is needed to build the FMUs")
    fmus = fmi.build_fmus(fmu_build_dir())
    fmus3 = fmi.build_fmus(fmu_build_dir(), fmi_version="3.0")
    assert fmi.run(tmp_path, fmus=fmus, fmus3=fmus3, stop_time=0.2) is True
    report = (tmp_path / "README.md").read_text()
    assert "**Result: PASS**" in report and "| NO |" not in report
    assert "## FMI 3.0 against FMI 2.0" in report and "| MultiAxisGenerator | 8 axes |" in report
    assert (tmp_path / "smoothshaper_00.png").stat().st_size > 1000
    assert "| ServoDrive | controller 3 (lqg) | 0.0e+00 | yes |" in report
    assert (tmp_path / "servo_drive_lqg.png").stat().st_size > 1000


def test_validation_and_cosim_helpers_name_bad_arguments():
    """They took anything: step=0 was a ZeroDivisionError, NaN a ValueError from int(),
    Ts='1' passed as 1 s, Ts=NaN into the FMU's start values, a u shorter than t an
    IndexError, a NaN rest or t went on to NaN expectations."""
    import numpy as np
    import pytest
    import smoothshaper as sms
    from smoothshaper import fmi as v
    from smoothshaper.fmi import cosim
    t = v.communication_points(step=1e-3, stop_time=0.01)
    cases = [
        ("Ts", lambda: v.start_values([sms.harmonic(T=0.05)], Ts=np.nan)),
        ("Ts", lambda: v.start_values([sms.harmonic(T=0.05)], Ts="1")),
        ("step", lambda: v.communication_points(step=0.0, stop_time=1.0)),
        ("step", lambda: v.communication_points(step=np.nan, stop_time=1.0)),
        ("step", lambda: v.communication_points(step=1e-300, stop_time=1.0)),
        ("stop_time", lambda: v.communication_points(step=1e-3, stop_time=None)),
        ("u", lambda: v.tick_inputs(t, np.ones(3), Ts=1e-4)),
        ("t", lambda: v.tick_inputs([], [], Ts=1e-4)),
        ("t", lambda: v.tick_inputs(t[::-1], np.ones(t.size), Ts=1e-4)),
        ("Ts", lambda: v.tick_inputs(t, np.ones(t.size), Ts=True)),
        ("rest", lambda: v.expected_output([sms.harmonic(T=0.05)], t, np.ones(t.size),
                                           Ts=1e-4, rest=np.nan)),
        ("t", lambda: v.target_staircase([0.0, np.nan])),
        ("n_steps", lambda: cosim.reference(10 ** 400, shaper=True)),
        ("shaper", lambda: cosim.reference(10, shaper="yes")),
        ("p", lambda: cosim.residual_vibration(np.ones(50), np.ones(40))),
    ]
    for parameter, call in cases:
        with pytest.raises(sms.ParameterError) as info:
            call()
        assert info.value.parameter == parameter, (parameter, str(info.value))
    x, n_at = v.tick_inputs(t, np.ones(t.size), Ts=1e-4)
    assert n_at[-1] == 100 and x.size == 100


def test_former_module_paths_keep_working():
    """The FMU tooling moved into smoothshaper.fmi; smoothshaper.validation and
    smoothshaper.cosim (imported by users, and run by ``python -m``) export the same objects."""
    import subprocess
    import sys
    from smoothshaper import cosim as old_cosim, fmi, validation as old_validation
    from smoothshaper.fmi import cosim
    for new, old in ((fmi, old_validation), (cosim, old_cosim)):
        assert new.__all__ == old.__all__
        for name in new.__all__:
            assert getattr(old, name) is getattr(new, name), name
    assert old_cosim.KIND_ZV == cosim.KIND_ZV and old_cosim.KIND_NONE == cosim.KIND_NONE
    done = subprocess.run([sys.executable, "-m", "smoothshaper.cosim", "--help"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "--build-dir" in done.stdout, done.stderr
