# SPDX-License-Identifier: Apache-2.0
"""The Python package keeps the layers docs/architecture.md declares (section "Python
package"): no import circle, no import the table does not allow, no module in no layer or in
two. The table is read, and the rules applied, by test_layers_c.py's code (one parser for both
tables); this file finds the Python imports. The import reader is unit-tested on small
synthetic packages (a circle, one through a package's ``__init__``, an upward import, a stray
module), so a pass means something."""
from __future__ import annotations

import ast
import pathlib

from test_layers_c import check_dependencies, read_layers

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "python" / "smoothshaper"
ARCHITECTURE = ROOT / "docs" / "architecture.md"
SECTION = "Python package"


def _module_name(path: pathlib.Path, package: pathlib.Path) -> str:
    parts = list(path.relative_to(package.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _top_level_names(tree: ast.Module) -> set[str]:
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names.update((a.asname or a.name).split(".")[0] for a in node.names)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
                names.update(n.id for n in ast.walk(target) if isinstance(n, ast.Name))
    return names


def import_graph(package: pathlib.Path) -> tuple[dict[str, set[str]], dict[str, pathlib.Path]]:
    """``({module: modules of the package it imports}, {module: its file})``.

    Every import counts, also inside functions. ``from P import x`` is an import of the
    module ``P.x`` when that is a module of the package, of ``P`` when ``P``'s ``__init__``
    defines ``x``, and of nothing here otherwise (a compiled extension such as ``_core``).
    That Python runs a package's ``__init__`` before its submodules is not counted."""
    paths = {_module_name(p, package): p for p in sorted(package.rglob("*.py"))}
    trees = {m: ast.parse(p.read_text(encoding="utf-8")) for m, p in paths.items()}
    defined = {m: _top_level_names(t) for m, t in trees.items() if paths[m].name == "__init__.py"}
    graph = {}
    for module, tree in trees.items():
        base = module.split(".") if paths[module].name == "__init__.py" else module.split(".")[:-1]
        found = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                found.update(a.name for a in node.names if a.name in paths)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    anchor = base[:len(base) - node.level + 1]
                    target = ".".join(anchor + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                for alias in node.names:
                    if f"{target}.{alias.name}" in paths:
                        found.add(f"{target}.{alias.name}")
                    elif target in paths and (alias.name == "*" or alias.name in
                                              defined.get(target, {alias.name})):
                        found.add(target)
        graph[module] = found - {module}
    return graph, paths


def check(package: pathlib.Path, markdown: str, root: pathlib.Path = ROOT):
    """test_layers_c's report for the package's modules (paths relative to ``root``) and the
    imports between them, against the table of ``markdown``'s section "Python package"."""
    graph, paths = import_graph(package)
    rel = {m: p.relative_to(root).as_posix() for m, p in paths.items()}
    edges = {(rel[a], rel[b]) for a in graph for b in graph[a]}
    return check_dependencies(sorted(rel.values()), edges, read_layers(markdown, SECTION))


# -- the package ---------------------------------------------------------------------------

def test_the_package_keeps_its_declared_layers():
    report = check(PACKAGE, ARCHITECTURE.read_text(encoding="utf-8"))
    assert report.problems() == [], "\n".join(report.problems())
    assert report.files > 60 and len(report.dependencies) > 200     # the whole package read


def test_the_graph_sees_the_imports_that_matter():
    """Guards the reader on the real package: lazy imports inside functions, relative imports
    two levels up, names from a package's __init__, compiled extensions skipped."""
    graph, paths = import_graph(PACKAGE)
    assert graph["smoothshaper.calibrate.outputs"] & {"smoothshaper.fmi",        # lazy
                                                      "smoothshaper.validation"}
    assert "smoothshaper.filters" in graph["smoothshaper.cli.chain"]              # from ..
    assert "smoothshaper" in graph["smoothshaper.cli"]                     # __version__
    assert "smoothshaper.cli.trajectory" in graph["smoothshaper.cli.design"]
    assert not any(m.endswith("_core") for m in graph["smoothshaper.filters"])
    assert paths["smoothshaper.cli"].name == "__init__.py"


# -- the reader and the rules on synthetic packages ----------------------------------------

TABLE = """# Title

## Layers

| layer | paths | may use | what it holds |
|---|---|---|---|
| other | `x/*` | — | |

## Python package

| layer | paths | may use | what it holds |
|---|---|---|---|
| top | `pkg/app/*`, `pkg/__main__.py` | low | |
| low | `pkg/__init__.py`, `pkg/util.py`, `pkg/sub/*` | — | |
"""


def _check(tmp_path: pathlib.Path, files: dict[str, str]):
    package = tmp_path / "pkg"
    for rel, text in {"__init__.py": "", **files}.items():
        (package / rel).parent.mkdir(parents=True, exist_ok=True)
        (package / rel).write_text(text)
    return check(package, TABLE, root=tmp_path)


def test_a_clean_synthetic_package_passes(tmp_path):
    report = _check(tmp_path, {
        "util.py": "import math\n",
        "sub/__init__.py": "from .leaf import f\n",
        "sub/leaf.py": "from .. import util\n\ndef f():\n    from ..util import math\n",
        "app/__init__.py": "from ..sub import f\nfrom . import cmd\n",
        "app/cmd.py": "from .. import _core\n",          # a compiled extension: no module
        "__main__.py": "from .app import cmd\n"})
    assert report.problems() == []
    assert ("pkg/__main__.py", "pkg/app/cmd.py") in report.dependencies
    assert ("pkg/sub/leaf.py", "pkg/util.py") in report.dependencies      # also lazily
    assert not any(b.endswith("_core") for _, b in report.dependencies)


def test_a_lazy_import_circle_fails(tmp_path):
    report = _check(tmp_path, {
        "util.py": "def g():\n    from .sub import leaf\n",     # lazy: still a dependency
        "sub/__init__.py": "",
        "sub/leaf.py": "from ..util import g\n"})
    assert report.cycles == [["pkg/sub/leaf.py", "pkg/util.py"]]


def test_a_circle_through_a_package_init_fails(tmp_path):
    report = _check(tmp_path, {
        "__init__.py": "from .util import VERSION\n",
        "util.py": "VERSION = 1\n\ndef g():\n    from . import VERSION\n"})
    assert report.cycles == [["pkg/__init__.py", "pkg/util.py"]]


def test_an_upward_import_fails(tmp_path):
    report = _check(tmp_path, {
        "util.py": "import pkg.app.cmd\n",
        "app/__init__.py": "",
        "app/cmd.py": "from ..util import x\n",
        "sub/__init__.py": "",
        "sub/leaf.py": "def f():\n    from ..app import cmd\n"})
    assert report.upward == [("pkg/sub/leaf.py", "pkg/app/cmd.py", "low", "top"),
                             ("pkg/util.py", "pkg/app/cmd.py", "low", "top")]
    assert report.cycles == [["pkg/app/cmd.py", "pkg/util.py"]]


def test_a_module_in_no_layer_fails(tmp_path):
    report = _check(tmp_path, {"util.py": "", "stray.py": "", "extra/mod.py": ""})
    assert report.unassigned == ["pkg/extra/mod.py", "pkg/stray.py"]
