"""Builds the cffi extensions smoothshaper._core (double) and smoothshaper._core_float (float)
from c/src/*.c; all other metadata lives in pyproject.toml."""
from setuptools import setup

setup(
    cffi_modules=[
        "python/smoothshaper/_build_core.py:ffibuilder",
        "python/smoothshaper/_build_core.py:ffibuilder_float",
    ],
)
