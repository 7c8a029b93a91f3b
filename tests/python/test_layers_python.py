# SPDX-License-Identifier: Apache-2.0
"""The Python package keeps the layers docs/architecture.md declares: no import cycle, no
import the table does not allow, no module outside the table. The checker is unit-tested on
small synthetic packages (a cycle, an upward import, a stray module), so a pass means
something."""
from __future__ import annotations

import ast
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "python" / "smoothshaper"
ARCHITECTURE = ROOT / "docs" / "architecture.md"
SECTION = "Python package"
NOTHING = {"", "-", "—", "nothing", "none"}


# -- the checker ---------------------------------------------------------------------------

def layer_table(markdown: str, section: str) -> list[tuple[str, list[str], set[str]]]:
    """The first table under the heading ``section``, columns ``layer | folders/modules | may
    import``: ``(layer, paths, allowed layers)`` per row, top layer first. Paths and layer
    names are the backticked words of a cell (or its comma-separated words)."""
    lines = markdown.splitlines()
    start = next((i for i, line in enumerate(lines)
                  if re.fullmatch(r"#+\s*" + re.escape(section) + r"\s*", line.strip())), None)
    assert start is not None, f"no heading {section!r}"
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        if not line.strip().startswith("|"):
            if rows:
                break
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if set("".join(cells)) <= set("-: "):
            continue                                   # the header rule
        rows.append(cells)
    assert rows, f"no table under {section!r}"
    header, body = rows[0], rows[1:]
    assert [h.lower() for h in header] == ["layer", "folders/modules", "may import"], header

    def words(cell):
        found = re.findall(r"`([^`]+)`", cell) or [w.strip() for w in cell.split(",")]
        return [w for w in found if w.lower() not in NOTHING]
    return [(name.strip("`* "), words(paths), set(words(allowed))) for name, paths, allowed in body]


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


def import_graph(package: pathlib.Path) -> tuple[dict[str, set[str]], dict[str, str]]:
    """``({module: modules of the package it imports}, {module: path relative to package})``.

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
    return graph, {m: p.relative_to(package).as_posix() for m, p in paths.items()}


def assign_layers(files: dict[str, str], table) -> tuple[dict[str, str], list[str]]:
    """``({module: layer}, [modules no row names])``: a file row wins over its folder, a
    deeper folder over a shallower one."""
    rules = [(path, layer) for layer, paths, _ in table for path in paths]
    layer_of, unassigned = {}, []
    for module, rel in files.items():
        matches = [(path.endswith("/"), -len(path), layer) for path, layer in rules
                   if rel == path or (path.endswith("/") and rel.startswith(path))]
        if matches:
            layer_of[module] = min(matches)[2]
        else:
            unassigned.append(rel)
    return layer_of, sorted(unassigned)


def import_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), sorted."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(found)


def forbidden_imports(graph, layer_of, table) -> list[str]:
    """Imports from one layer into another that its row does not allow, as
    ``"a (layer) -> b (layer)"``."""
    allowed = {layer: may for layer, _, may in table}
    return sorted(f"{a} ({layer_of[a]}) -> {b} ({layer_of[b]})"
                  for a in graph for b in graph[a]
                  if a in layer_of and b in layer_of and layer_of[a] != layer_of[b]
                  and layer_of[b] not in allowed[layer_of[a]])


def table_problems(table) -> list[str]:
    """A row that may import its own layer's name, an unknown layer or a layer above it (the
    table is ordered top to bottom: imports point down)."""
    names = [layer for layer, _, _ in table]
    problems = [f"layer {name!r} twice" for name in set(names) if names.count(name) > 1]
    for i, (layer, _, may) in enumerate(table):
        problems += [f"{layer} may import {m!r}, which is not a layer below it"
                     for m in sorted(may) if m not in names[i + 1:]]
    return problems


def check(package: pathlib.Path, markdown: str, section: str = SECTION) -> dict[str, list]:
    table = layer_table(markdown, section)
    graph, files = import_graph(package)
    layer_of, unassigned = assign_layers(files, table)
    return {"table": table_problems(table), "unassigned": unassigned,
            "cycles": import_cycles(graph), "forbidden": forbidden_imports(graph, layer_of, table)}


# -- the package ---------------------------------------------------------------------------

def test_the_package_keeps_its_declared_layers():
    problems = check(PACKAGE, ARCHITECTURE.read_text(encoding="utf-8"))
    assert problems == {"table": [], "unassigned": [], "cycles": [], "forbidden": []}, problems


def test_the_graph_sees_the_imports_that_matter():
    """Guards the parser itself on the real package: lazy imports inside functions, relative
    imports two levels up, names from a package's __init__, compiled extensions skipped."""
    graph, files = import_graph(PACKAGE)
    assert "smoothshaper.fmi" in graph["smoothshaper.calibrate.outputs"] \
        or "smoothshaper.validation" in graph["smoothshaper.calibrate.outputs"]   # lazy
    assert "smoothshaper.filters" in graph["smoothshaper.cli.chain"]                 # from ..
    assert "smoothshaper" in graph["smoothshaper.cli"]                    # __version__
    assert "smoothshaper.cli.trajectory" in graph["smoothshaper.cli.design"]
    assert not any(m.endswith("_core") for m in graph["smoothshaper.filters"])
    assert files["smoothshaper.cli"] == "cli/__init__.py"


# -- the checker on synthetic packages -----------------------------------------------------

TABLE = """# Title

## Python package

| layer | folders/modules | may import |
|---|---|---|
| top | `app/`, `__main__.py` | `low` |
| low | `__init__.py`, `util.py`, `sub/` | nothing |

## Next section

| layer | folders/modules | may import |
|---|---|---|
| other | `x/` | nothing |
"""


def _package(tmp_path: pathlib.Path, files: dict[str, str]) -> pathlib.Path:
    package = tmp_path / "pkg"
    for rel, text in {"__init__.py": "", **files}.items():
        (package / rel).parent.mkdir(parents=True, exist_ok=True)
        (package / rel).write_text(text)
    return package


def test_checker_reads_only_its_section_and_orders_layers():
    table = layer_table(TABLE, SECTION)
    assert table == [("top", ["app/", "__main__.py"], {"low"}),
                     ("low", ["__init__.py", "util.py", "sub/"], set())]
    assert table_problems(table) == []
    assert table_problems([("a", [], {"b"}), ("b", [], {"a"})]) == \
        ["b may import 'a', which is not a layer below it"]
    with pytest.raises(AssertionError):
        layer_table("## Python package\n\nno table here\n", SECTION)


def test_checker_passes_a_clean_package(tmp_path):
    package = _package(tmp_path, {
        "util.py": "import math\n",
        "sub/__init__.py": "from .leaf import f\n",
        "sub/leaf.py": "from .. import util\n\ndef f():\n    from ..util import math\n",
        "app/__init__.py": "from ..sub import f\nfrom . import cmd\n",
        "app/cmd.py": "from .. import _core\n",          # a compiled extension: no module
        "__main__.py": "from .app import cmd\n"})
    assert check(package, TABLE) == {"table": [], "unassigned": [], "cycles": [],
                                     "forbidden": []}


def test_checker_finds_a_cycle(tmp_path):
    package = _package(tmp_path, {
        "util.py": "def g():\n    from .sub import leaf\n",     # lazy: still a dependency
        "sub/__init__.py": "",
        "sub/leaf.py": "from ..util import g\n"})
    assert check(package, TABLE)["cycles"] == [["pkg.sub.leaf", "pkg.util"]]


def test_checker_finds_a_cycle_through_a_package_init(tmp_path):
    package = _package(tmp_path, {
        "__init__.py": "from .util import VERSION\n",
        "util.py": "VERSION = 1\n\ndef g():\n    from . import VERSION\n"})
    assert check(package, TABLE)["cycles"] == [["pkg", "pkg.util"]]


def test_checker_finds_an_upward_import(tmp_path):
    package = _package(tmp_path, {
        "util.py": "import pkg.app.cmd\n",
        "app/__init__.py": "",
        "app/cmd.py": "from ..util import x\n",
        "sub/__init__.py": "",
        "sub/leaf.py": "def f():\n    from ..app import cmd\n"})
    result = check(package, TABLE)
    assert result["forbidden"] == ["pkg.sub.leaf (low) -> pkg.app.cmd (top)",
                                   "pkg.util (low) -> pkg.app.cmd (top)"]
    assert result["cycles"] == [["pkg.app.cmd", "pkg.util"]]


def test_checker_finds_a_module_no_row_names(tmp_path):
    package = _package(tmp_path, {"util.py": "", "stray.py": "", "extra/mod.py": ""})
    assert check(package, TABLE)["unassigned"] == ["extra/mod.py", "stray.py"]
