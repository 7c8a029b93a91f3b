# SPDX-License-Identifier: Apache-2.0
"""Where the Python tests build (or find) their FMUs.

``SMOOTHSHAPER_TEST_FMU_DIR`` names a configured CMake tree whose FMUs the tests reuse
(scripts/test.sh passes its release tree, so the FMUs are built once); by default the tests
build their own in build-pytest-fmu.
"""
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def fmu_build_dir() -> Path:
    """The CMake tree the tests' FMUs come from."""
    return Path(os.environ.get("SMOOTHSHAPER_TEST_FMU_DIR") or ROOT / "build-pytest-fmu")
