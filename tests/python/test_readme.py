# SPDX-License-Identifier: Apache-2.0
"""Every example in README.md runs as written.

The Python blocks run in order in one namespace; every command of the shell blocks runs with
``python -m smoothshaper`` from a scratch folder that sees the repository's ``examples/``; the C
block must be ``examples/chain_step.c``, which ctest compiles, runs and checks
(``example_chain_step``). Two commands are not rerun here because whole suites cover them:
``validate`` (tests/python/test_validation.py builds and checks the FMUs) and ``report``
(tests/python/test_report.py); the quick-start block is what CI itself runs.
"""
from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()
COVERED_ELSEWHERE = ("validate", "report")


def blocks(language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```", README, re.S | re.M)


def shell_commands() -> list[str]:
    out = []
    for block in blocks("sh"):
        if "scripts/main.sh" in block:          # the quick start: CI runs it
            continue
        for line in block.replace("\\\n", " ").splitlines():
            command = line.split("  #")[0].strip()
            if command:
                out.append(command)
    return out


def test_readme_has_examples_of_every_kind():
    assert blocks("python") and blocks("c") and shell_commands()


def test_c_example_is_the_shipped_program():
    (block,) = blocks("c")
    program = (ROOT / "examples" / "chain_step.c").read_text()
    assert block.strip() in program


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A working folder with the repository's examples/ (commands write their outputs here)."""
    path = tmp_path_factory.mktemp("readme")
    os.symlink(ROOT / "examples", path / "examples")
    (path / "docs").mkdir()
    return path


def test_python_examples_run(scratch, monkeypatch):
    monkeypatch.chdir(scratch)
    namespace: dict = {"__name__": "__readme__"}
    for block in blocks("python"):
        exec(compile(block, "README.md", "exec"), namespace)  # noqa: S102


@pytest.mark.parametrize("command", [c for c in shell_commands()
                                     if c.split()[1] not in COVERED_ELSEWHERE])
def test_shell_example_runs(scratch, command):
    argv = shlex.split(command)
    assert argv[0] == "smoothshaper", command
    env = dict(os.environ, MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, "-m", "smoothshaper", *argv[1:]], cwd=scratch,
                            capture_output=True, text=True, env=env, timeout=600)
    assert result.returncode == 0, f"{command}\n{result.stdout}\n{result.stderr}"


def test_commands_covered_elsewhere_are_the_ones_named():
    skipped = {c.split()[1] for c in shell_commands()} & set(COVERED_ELSEWHERE)
    assert skipped == set(COVERED_ELSEWHERE)
    for name in COVERED_ELSEWHERE:
        assert (ROOT / "tests" / "python" / f"test_{'validation' if name == 'validate' else name}"
                ".py").exists()
