# SPDX-License-Identifier: Apache-2.0
"""Every Python example in docs/ runs as written.

The blocks of a page run in order in one namespace, from a scratch folder laid out like a
repository after ``scripts/main.sh``: ``examples/`` and the FMUs under ``build/fmu/fmus/``
(built by the session fixture the FMU tests share). An example that prints a number says what
it should be; the FMU example's comment promises agreement with the reference to rounding,
which is asserted here from its namespace.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from test_fmu_smoothshaper import fmus  # noqa: E402,F401

ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted((ROOT / "docs").glob("*.md"))


def python_blocks(page: Path) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", page.read_text(), re.S | re.M)


@pytest.fixture(scope="module")
def scratch(tmp_path_factory, fmus):  # noqa: F811
    path = tmp_path_factory.mktemp("docs")
    os.symlink(ROOT / "examples", path / "examples")
    (path / "build" / "fmu" / "fmus").mkdir(parents=True)
    for name, fmu in fmus.items():
        os.symlink(fmu, path / "build" / "fmu" / "fmus" / f"{name}.fmu")
    return path


@pytest.mark.parametrize("page", [p for p in PAGES if python_blocks(p)], ids=lambda p: p.name)
def test_python_examples_run(page, scratch, monkeypatch):
    monkeypatch.chdir(scratch)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace: dict = {"__name__": "__docs__"}
    for block in python_blocks(page):
        exec(compile(block, str(page.relative_to(ROOT)), "exec"), namespace)  # noqa: S102
    if page.name == "cosimulation.md":
        r, y_ref = namespace["r"], namespace["y_ref"]
        assert np.max(np.abs(r["y"] - y_ref)) <= 1e-12
        assert r["y"][-1] == pytest.approx(1.0, abs=1e-12)     # the step has passed the chain
    if page.name == "servo.md":   # ServoDrive.fmu within its tolerance of the testbed
        assert namespace["c"].passed


def test_docs_have_python_examples():
    assert any(python_blocks(p) for p in PAGES)
