# SPDX-License-Identifier: Apache-2.0
"""Builds the cffi extensions smoothshaper._core (double) and smoothshaper._core_float (float)
from the C sources under c/src, and the CPython extension smoothshaper._kinematic_fastpath
(design.kinematic's fast path); the C library sources are compiled once per precision
(_build_library.py); all other metadata lives in pyproject.toml."""
import os
import sys

from setuptools import setup

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python",
                                "smoothshaper"))
from _build_core import SRC_DIR, kinematic_fastpath_extension  # noqa: E402
from _build_library import with_library_dir  # noqa: E402

setup(
    # Each C source compiled once per precision, in parallel, shared by the extensions.
    cmdclass={"build_ext": with_library_dir(SRC_DIR)},
    ext_modules=[kinematic_fastpath_extension()],
    cffi_modules=[
        "python/smoothshaper/_build_core.py:ffibuilder",
        "python/smoothshaper/_build_core.py:ffibuilder_float",
    ],
)
