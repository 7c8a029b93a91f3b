# SPDX-License-Identifier: Apache-2.0
"""The declared dependencies match the imports, and a missing optional package is named with
the extra that installs it (the fresh-venv check of the built wheel is
tests/install/fresh_venv.sh, run by scripts/test.sh)."""
import ast
import re
import sys
import tomllib
from pathlib import Path

import pytest

import smoothshaper
from smoothshaper import _optional, cli

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = Path(smoothshaper.__file__).resolve().parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
# Importable module of each base dependency (the distribution name can differ).
BASE_MODULES = {"numpy": "numpy", "scipy": "scipy", "cffi": "cffi"}


def _requirement_name(text: str) -> str:
    return re.split(r"[<>=!~\[; ]", text, maxsplit=1)[0].strip().lower()


# Modules setup.py runs to build the extensions; the installed package never imports them.
BUILD_MODULES = ("_build_core.py", "_build_library.py")


def _third_party_imports(build: bool = False):
    """(module file, node, top-level name, enclosing function or None, handled) for every
    import of a module that is neither the standard library nor this package; ``handled``
    is True inside a ``try`` that catches ImportError (the code then goes on without it).
    ``build``: the build-time modules (``_build_core.py`` and ``_build_library.py``, run by
    setup.py) instead of the installed package."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if (path.name in BUILD_MODULES) != build:
            continue
        tree = ast.parse(path.read_text(), str(path))

        def visit(node, func, handled):
            for child in ast.iter_child_nodes(node):
                f, h = func, handled
                if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    f = child
                if isinstance(child, ast.Try) and any(
                        isinstance(hd.type, ast.Name) and hd.type.id in
                        ("ImportError", "ModuleNotFoundError") for hd in child.handlers):
                    for stmt in child.body:
                        visit_one(stmt, f, True)
                    for part in child.handlers + child.orelse + child.finalbody:
                        visit_one(part, f, h)
                    continue
                visit_one(child, f, h)

        def visit_one(child, func, handled):
            names = []
            if isinstance(child, ast.Import):
                names = [a.name for a in child.names]
            elif isinstance(child, ast.ImportFrom) and child.level == 0 and child.module:
                names = [child.module]
            for name in names:
                top = name.split(".")[0]
                if top not in sys.stdlib_module_names and top != "smoothshaper":
                    found.append((path, child, top, func, handled))
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                visit(child, child, handled)
            else:
                visit(child, func, handled)

        visit(tree, None, False)
    return found


def _calls_optional(func) -> bool:
    """The function asks :mod:`smoothshaper._optional` for the package before importing it."""
    for node in ast.walk(func):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in ("require", "pyplot"):
                return True
    return False


def test_base_dependencies_are_what_the_package_imports():
    """Every third-party import is a base dependency or an optional one of _optional.EXTRAS
    (SciPy is a base dependency: design, trajectory and plants need it)."""
    declared = {_requirement_name(r) for r in PYPROJECT["project"]["dependencies"]}
    assert declared == set(BASE_MODULES)
    tops = {top for _, _, top, _, _ in _third_party_imports()}
    assert tops <= set(BASE_MODULES.values()) | set(_optional.EXTRAS), \
        tops - set(BASE_MODULES.values()) - set(_optional.EXTRAS)


def test_build_requirements_are_what_the_build_imports():
    """setup.py's build: cffi (and pycparser, which cffi requires) and setuptools (its
    build_ext)."""
    declared = {_requirement_name(r) for r in PYPROJECT["build-system"]["requires"]}
    tops = {top for _, _, top, _, _ in _third_party_imports(build=True)}
    assert tops - {"pycparser"} <= declared and "cffi" in declared, tops


def test_every_extra_lists_its_packages():
    extras = PYPROJECT["project"]["optional-dependencies"]
    for module, (dist, extra) in _optional.EXTRAS.items():
        assert dist in {_requirement_name(r) for r in extras[extra]}, (module, extra)
    names = {_requirement_name(r) for r in extras["all"]}
    assert names == {"smoothshaper"} and "plot,validate,bench" in extras["all"][0]


def test_optional_packages_are_imported_only_through_optional():
    """An optional package is never imported at module level, and a function that imports it
    asks _optional first (so the error names the extra) or catches ImportError itself."""
    bad = []
    for path, node, top, func, handled in _third_party_imports():
        if top not in _optional.EXTRAS or handled:
            continue
        if func is None or not _calls_optional(func):
            bad.append(f"{path.relative_to(PACKAGE)}:{node.lineno} imports {top}")
    assert not bad, bad


def test_require_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "fmpy", None)
    with pytest.raises(ModuleNotFoundError) as info:
        _optional.require("fmpy", "running an FMU in fmpy")
    assert str(info.value) == ("running an FMU in fmpy needs the Python package 'fmpy', which "
                               "is not installed: pip install 'smoothshaper[validate]'")
    assert info.value.name == "fmpy"
    with pytest.raises(KeyError):
        _optional.require("numpy", "x")          # a base dependency is not optional


def test_fmi_functions_name_the_extra(monkeypatch, tmp_path):
    import numpy as np
    from smoothshaper import stages
    from smoothshaper.fmi import simulate
    monkeypatch.setitem(sys.modules, "fmpy", None)
    with pytest.raises(_optional.MissingDependency, match=r"smoothshaper\[validate\]"):
        simulate(str(tmp_path / "x.fmu"), [stages.shaper("zv", wn=10.0)],
                 np.arange(3) * 1e-3, np.ones(3), Ts=1e-3)


def _run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv, extra", [
    (("analyze", "--stage", "harmonic:wn=100", "--Ts", "1e-3", "--wn", "100", "--points", "20"),
     "plot"),
    (("report", "--only", "seed002"), "plot"),
    (("validate",), "validate"),
])
def test_cli_without_an_extra_exits_3_naming_it(monkeypatch, capsys, tmp_path, argv, extra):
    """Without the optional package, one line naming the extra and exit 3 (the report writes
    no README with a traceback in it)."""
    for name in ("matplotlib", "matplotlib.pyplot", "fmpy"):
        monkeypatch.setitem(sys.modules, name, None)
    out_dir = tmp_path / "out"
    code, _, err = _run(capsys, *argv, "--out", str(out_dir))
    assert code == cli.EXIT_UNAVAILABLE, err
    assert f"pip install 'smoothshaper[{extra}]'" in err and err.count("\n") == 1, err
    assert not (out_dir / "README.md").exists()


@pytest.mark.parametrize("argv, written", [
    (("design", "generator", "--via", "0,20,40", "--vmax", "250", "--amax", "5000", "--jmax",
      "200000", "--Ts", "1e-3", "--plot", "{d}/g.png", "--csv", "{d}/g.csv"), "g.csv"),
    (("design", "generator", "--via", "0,0,0;100,50,20", "--vmax", "250,200,100", "--amax",
      "5000,4000,2000", "--jmax", "2e5,1e5,5e4", "--Ts", "1e-3", "--plot", "{d}/m.png"), "m.png"),
    (("design", "bspline", "--via", "0,0;1,2;3,1", "--wn", "25", "--Ts", "1e-3", "--plot",
      "{d}/b.png"), "b.png"),
    (("calibrate", "{examples}/resonance_xy.csv", "--axis", "y", "--out", "{d}/cal"), "cal"),
])
def test_figures_without_matplotlib_exit_3_before_any_work(monkeypatch, capsys, tmp_path, argv,
                                                           written):
    """An option that asks for figures, matplotlib missing: exit 3 with one line naming the
    extra, nothing printed to stdout and nothing written (no table, no CSV, no folder)."""
    for name in ("matplotlib", "matplotlib.pyplot"):
        monkeypatch.setitem(sys.modules, name, None)
    examples = Path(__file__).resolve().parents[2] / "examples"
    code, out, err = _run(capsys, *[a.format(d=tmp_path, examples=examples) for a in argv])
    assert code == cli.EXIT_UNAVAILABLE, err
    assert "pip install 'smoothshaper[plot]'" in err and err.count("\n") == 1, err
    assert err.startswith(f"smoothshaper {argv[0]} "), err
    assert out == "" and not (tmp_path / written).exists()


def test_cosim_without_its_extra_exits_3_in_one_line(monkeypatch, capsys, tmp_path):
    from smoothshaper.fmi import cosim
    monkeypatch.setitem(sys.modules, "libcosimpy", None)
    code = cosim.main(["--out", str(tmp_path / "c")])
    out, err = capsys.readouterr()
    assert code == 3 and err.count("\n") == 1 and "smoothshaper[validate]" in err, err
    assert not (tmp_path / "c").exists()
