# SPDX-License-Identifier: Apache-2.0
"""FMU tooling: build the FMUs, run them in fmpy and libcosim, and compare them with the NumPy
reference (docs/cosimulation.md).

* :mod:`~smoothshaper.fmi.parameters`: the SmoothShaper FMU's start values for a chain;
* :mod:`~smoothshaper.fmi.timing`: what an FMU reports at the communication points;
* :mod:`~smoothshaper.fmi.build`: CMake build (FMI 2.0 and 3.0) and model-description checks;
* :mod:`~smoothshaper.fmi.simulate`: runs in fmpy and libcosim (MultiAxisGenerator with every
  axis's input, for either FMI version);
* :mod:`~smoothshaper.fmi.cases`, :mod:`~smoothshaper.fmi.compare`: the validation cases and
  one run against the reference;
* :mod:`~smoothshaper.fmi.validate`: ``smoothshaper validate``, the whole campaign and its
  report;
* :mod:`~smoothshaper.fmi.cosim`: the system co-simulation (``python -m smoothshaper.cosim``).

The functions of all but the last are importable from here (and from
``smoothshaper.validation``, their former home).
"""
from .build import (FMI_VERSIONS, FMU_MODELS, build_fmus, fmpy_problems, fmutool_problems,
                    repo_root)
from .cases import (TRAJECTORY_LIMITS, TRAJECTORY_PROFILES, multi_axis_case, target_staircase,
                    test_input, validation_cases)
from .compare import (REL_TOL, compare, compare_importers, compare_importers_trajectory,
                      compare_trajectory)
from .parameters import KIND_VALUES, STAGE_FIELDS, ModeStage, reference_stages, start_values
from .simulate import (multi_axis_input, simulate, simulate_libcosim, simulate_multi_axis,
                       simulate_trajectory, start_values_for)
from .timing import (TICK_SLACK, at_communication_points, communication_points,
                     expected_output, expected_trajectory, tick_inputs)
from .validate import REQUIRES, RUN_STEPS, fmi3_against_fmi2, run

__all__ = ["REL_TOL", "REQUIRES", "RUN_STEPS", "ModeStage", "start_values", "reference_stages",
           "communication_points", "tick_inputs", "at_communication_points", "expected_output",
           "expected_trajectory", "simulate", "validation_cases", "build_fmus", "fmpy_problems",
           "fmutool_problems", "simulate_libcosim", "compare_importers",
           "compare_importers_trajectory", "compare", "target_staircase", "simulate_trajectory",
           "compare_trajectory", "run", "STAGE_FIELDS", "KIND_VALUES", "TICK_SLACK", "FMU_MODELS",
           "TRAJECTORY_LIMITS", "TRAJECTORY_PROFILES", "repo_root", "test_input", "FMI_VERSIONS",
           "multi_axis_case", "multi_axis_input", "simulate_multi_axis", "start_values_for",
           "fmi3_against_fmi2"]
