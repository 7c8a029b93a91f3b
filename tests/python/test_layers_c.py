# SPDX-License-Identifier: Apache-2.0
"""The C core and the FMU glue keep the layers that docs/architecture.md declares.

The layer table in docs/architecture.md (section "Layers") is the declaration: each row names a
layer, the files it holds (glob patterns, ``*`` crossing folders) and the layers it may use.
This test reads every C file of ``c/src``, ``c/include``, ``fmu`` and the Python package's C
extension, and finds two kinds of dependency between files:

- an ``#include`` that resolves to a file of the tree (on the build's include path: the file's
  own folder, ``c/include``, ``c/src``, ``fmu``); headers the build generates or takes from
  elsewhere (``<Model>_variables.h``, the FMI headers) are not files of the tree;
- a use, in a ``.c`` file, of a function another ``.c`` file defines with external linkage
  (a call or its address): this is the link the include graph hides when a header of one file
  declares functions that another file defines.

It fails when a file belongs to no layer or to two, when a dependency runs to a layer its
layer may not use, and on every circle of files (a strongly connected set). Pure Python and
text only: comments and string literals are removed before reading, nothing is compiled.
"""
from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ARCHITECTURE = ROOT / "docs" / "architecture.md"
SCANNED = ("c/src", "c/include", "fmu", "python/smoothshaper")
INCLUDE_DIRS = ("c/include", "c/src", "fmu")


@dataclass
class Layer:
    name: str
    patterns: list[str]
    may_use: set[str]


@dataclass
class Report:
    files: int = 0
    dependencies: set[tuple[str, str]] = field(default_factory=set)
    unassigned: list[str] = field(default_factory=list)
    ambiguous: list[tuple[str, list[str]]] = field(default_factory=list)
    unknown_layers: list[str] = field(default_factory=list)
    upward: list[tuple[str, str, str, str]] = field(default_factory=list)  # src, dst, layers
    cycles: list[list[str]] = field(default_factory=list)

    def problems(self) -> list[str]:
        out = [f"{p}: in no layer of docs/architecture.md" for p in self.unassigned]
        out += [f"{p}: in several layers ({', '.join(ls)})" for p, ls in self.ambiguous]
        out += [f"layer table: {u}" for u in self.unknown_layers]
        out += [f"{s} ({ls}) -> {d} ({ld}): {ls} may not use {ld}"
                for s, d, ls, ld in self.upward]
        out += [f"circle of {len(c)}: " + ", ".join(c) for c in self.cycles]
        return out


# ---- the declaration --------------------------------------------------------------------------

def read_layers(markdown: str, section: str = "Layers") -> dict[str, Layer]:
    """The rows of the first table under the heading ``## <section>``: columns layer, paths
    (backquoted globs), may use (layer names separated by commas; a dash for none). The
    Python package's table (section "Python package") has the same columns."""
    found = re.search(rf"^## {re.escape(section)}\s*$(.*?)(?=^## |\Z)", markdown, re.M | re.S)
    if found is None:
        raise ValueError(f"docs/architecture.md has no '## {section}' section")
    rows = [line for line in found.group(1).splitlines() if line.startswith("|")]
    if len(rows) < 3:
        raise ValueError(f"the {section} section has no table")
    header = [c.strip().lower() for c in rows[0].strip("|").split("|")]
    col = {name: header.index(name) for name in ("layer", "paths", "may use")}
    layers: dict[str, Layer] = {}
    for line in rows[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        name = cells[col["layer"]]
        patterns = re.findall(r"`([^`]+)`", cells[col["paths"]])
        uses = {u.strip() for u in cells[col["may use"]].split(",")} - {"", "-", "—"}
        layers[name] = Layer(name, patterns, uses)
    return layers


def layer_of(path: str, layers: dict[str, Layer]) -> list[str]:
    return [ly.name for ly in layers.values()
            if any(fnmatch.fnmatchcase(path, p) for p in ly.patterns)]


# ---- reading C as text ------------------------------------------------------------------------

_TOKEN = re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|/\*.*?\*/|//[^\n]*', re.S)
_INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"]+)[>"]', re.M)
_DIRECTIVE = re.compile(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", re.M)
_IDENT = re.compile(r"[A-Za-z_]\w*")


def strip(text: str, keep_strings: bool) -> str:
    """Comments become blanks (newlines kept); string and character literals too, unless
    keep_strings (the include lines need theirs)."""
    def blank(m: re.Match) -> str:
        s = m.group(0)
        if keep_strings and s[0] in "\"'":
            return s
        return re.sub(r"[^\n]", " ", s)
    return _TOKEN.sub(blank, text)


def includes(text: str) -> list[str]:
    return [m.group(2) for m in _INCLUDE.finditer(strip(text, keep_strings=True))]


def definitions(text: str, *, static: bool = False) -> set[str]:
    """Names of the functions the file defines with external linkage (and its static ones too
    when static): at brace depth 0, a name followed by a parenthesised list and then '{'."""
    code = _DIRECTIVE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)),
                          strip(text, keep_strings=False))
    names, depth, i, start = set(), 0, 0, 0   # start: where the current declaration began
    while i < len(code):
        ch = code[i]
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                start = i + 1
        elif ch == ";" and depth == 0:
            start = i + 1
        elif depth == 0 and ch == "(":
            m = re.search(r"([A-Za-z_]\w*)\s*$", code[start:i])
            level, j = 1, i + 1
            while j < len(code) and level:
                level += {"(": 1, ")": -1}.get(code[j], 0)
                j += 1
            rest = code[j:].lstrip()
            if m and rest.startswith("{") and (static or not re.search(r"\bstatic\b", code[start:i])):
                names.add(m.group(1))
            i = j
            continue
        i += 1
    return names


def identifiers(text: str) -> set[str]:
    return set(_IDENT.findall(strip(text, keep_strings=False)))


# ---- the graph ----------------------------------------------------------------------------------

def resolve(name: str, path: str, files: dict[str, str],
            include_dirs: tuple[str, ...] = INCLUDE_DIRS) -> str | None:
    for folder in (str(Path(path).parent),) + include_dirs:
        candidate = str(Path(folder, name).as_posix())
        parts: list[str] = []
        for part in candidate.split("/"):      # fold "..", as the preprocessor does
            if part == "..":
                parts.pop() if parts else None
            elif part not in ("", "."):
                parts.append(part)
        candidate = "/".join(parts)
        if candidate in files:
            return candidate
    return None


def dependencies(files: dict[str, str],
                 include_dirs: tuple[str, ...] = INCLUDE_DIRS) -> set[tuple[str, str]]:
    """(from, to) for every include of a file of the tree and every use of a function that
    another .c file defines."""
    edges = set()
    for path, text in files.items():
        for name in includes(text):
            target = resolve(name, path, files, include_dirs)
            if target is not None and target != path:
                edges.add((path, target))
    defined = {p: definitions(t) for p, t in files.items() if p.endswith(".c")}
    definer: dict[str, list[str]] = {}
    for path, names in defined.items():
        for name in names:
            definer.setdefault(name, []).append(path)
    for path in defined:
        own = definitions(files[path], static=True)     # a name it defines itself is its own
        for name in identifiers(files[path]) - own:
            for target in definer.get(name, []):
                edges.add((path, target))
    return edges


def circles(edges: set[tuple[str, str]]) -> list[list[str]]:
    """Strongly connected sets of more than one file (Tarjan), each sorted, sorted."""
    graph: dict[str, list[str]] = {}
    for a, b in sorted(edges):
        graph.setdefault(a, []).append(b)
        graph.setdefault(b, [])
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:            # depth <= number of files: a few dozen
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
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
                out.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return sorted(out)


def check(files: dict[str, str], layers: dict[str, Layer],
          include_dirs: tuple[str, ...] = INCLUDE_DIRS) -> Report:
    return check_dependencies(files, dependencies(files, include_dirs), layers)


def check_dependencies(files, edges: set[tuple[str, str]], layers: dict[str, Layer]) -> Report:
    """The report for ``files`` (paths) and the dependencies ``edges`` between them, whatever
    found them (C includes and calls here, Python imports in test_layers_python.py)."""
    report = Report(files=len(files))
    for ly in layers.values():
        for u in sorted(ly.may_use - set(layers)):
            report.unknown_layers.append(f"{ly.name} may use '{u}', which is no layer")
    home: dict[str, str] = {}
    for path in sorted(files):
        found = layer_of(path, layers)
        if not found:
            report.unassigned.append(path)
        elif len(found) > 1:
            report.ambiguous.append((path, found))
        else:
            home[path] = found[0]
    report.dependencies = set(edges)
    for a, b in sorted(report.dependencies):
        la, lb = home.get(a), home.get(b)
        if la and lb and la != lb and lb not in layers[la].may_use:
            report.upward.append((a, b, la, lb))
    report.cycles = circles(report.dependencies)
    # The declaration itself must be one way: no circle among the layers' "may use".
    declared = {(ly.name, u) for ly in layers.values() for u in ly.may_use if u in layers}
    report.cycles += [["layer " + n for n in c] for c in circles(declared)]
    return report


def tree_files(root: Path = ROOT) -> dict[str, str]:
    out = {}
    for top in SCANNED:
        for path in sorted((root / top).rglob("*")):
            if path.suffix in (".c", ".h") and path.is_file():
                out[path.relative_to(root).as_posix()] = path.read_text(encoding="utf-8")
    return out


# ---- the tests ----------------------------------------------------------------------------------

def test_the_tree_keeps_the_declared_layers():
    report = check(tree_files(), read_layers(ARCHITECTURE.read_text(encoding="utf-8")))
    assert report.files > 40 and len(report.dependencies) > 80   # the scan did read the tree
    assert report.problems() == []


def test_the_scan_sees_what_the_include_lines_hide():
    # step.c's sms_chain_step is declared in chain.h: only the definition says who holds it
    files = tree_files()
    edges = dependencies(files)
    assert ("c/src/trajectory/multi_step.c", "c/src/filter/step.c") in edges
    assert ("fmu/fmu_core.c", "fmu/fmu_serialize.c") in edges
    assert ("fmu/fmi2_glue.c", "fmu/fmu_core.c") in edges
    assert ("fmu/smoothshaper_model.c", "fmu/fmu_refuse.c") in edges
    assert "sms_chain_init" in definitions(files["c/src/filter/chain.c"])
    assert "sms_smoother_init" not in definitions(files["c/src/filter/chain.c"])


SYNTHETIC_TABLE = """
## Layers

| layer | paths | may use | what it holds |
|---|---|---|---|
| top | `top/*` | low | |
| low | `low/*` | — | |
"""


def synthetic(**overrides: str) -> dict[str, str]:
    files = {
        "top/a.c": '#include "low/b.h"\nint a(void)\n{\n    return b();\n}\n',
        "low/b.h": "int b(void);\n",
        "low/b.c": '#include "b.h"\n/* a() would be upward */\nint b(void)\n{\n    return 1;\n}\n',
        "low/c.c": "static int a(void)\n{\n    return 0;\n}\n",   # a static namesake: no link
    }
    files.update(overrides)
    return files


def check_synthetic(files, table=SYNTHETIC_TABLE):
    return check(files, read_layers(table), include_dirs=(".",))


def test_a_clean_synthetic_tree_passes():
    report = check_synthetic(synthetic())
    assert report.problems() == []
    assert ("top/a.c", "low/b.c") in report.dependencies     # the call, besides the include
    assert ("top/a.c", "low/b.h") in report.dependencies


def test_an_upward_include_fails():
    report = check_synthetic(synthetic(**{"low/b.h": '#include "top/a.h"\nint b(void);\n',
                                          "top/a.h": "int a(void);\n"}))
    assert report.upward == [("low/b.h", "top/a.h", "low", "top")]


def test_an_upward_call_and_its_circle_fail():
    # b.c calls a(), which top/a.c defines: no include says so, the definition does
    report = check_synthetic(synthetic(**{
        "low/b.c": "int a(void);\nint b(void)\n{\n    return a();\n}\n"}))
    assert [(s, d) for s, d, _, _ in report.upward] == [("low/b.c", "top/a.c")]
    assert report.cycles == [["low/b.c", "top/a.c"]]


def test_an_include_circle_within_one_layer_fails():
    report = check_synthetic(synthetic(**{"low/b.h": '#include "d.h"\nint b(void);\n',
                                          "low/d.h": '#include "b.h"\n'}))
    assert report.upward == []
    assert report.cycles == [["low/b.h", "low/d.h"]]


def test_a_file_outside_every_layer_and_a_circular_table_fail():
    report = check_synthetic(synthetic(**{"stray/e.c": "int e(void)\n{\n    return 2;\n}\n"}))
    assert report.unassigned == ["stray/e.c"]
    table = SYNTHETIC_TABLE.replace("| low | `low/*` | — |", "| low | `low/*` | top, nowhere |")
    report = check_synthetic(synthetic(), table)
    assert ["layer low", "layer top"] in report.cycles
    assert report.unknown_layers == ["low may use 'nowhere', which is no layer"]


@pytest.mark.parametrize("text,names", [
    ("static int f(void)\n{\n}\nint g(int x)\n{\n    if (x) {\n    }\n}\n", {"g"}),
    ("int f(void);\nint (*p)(void);\n", set()),
    ("static double\nf(void)\n{\n}\n", set()),
    ('/* int f(void) { } */\nconst char *s = "g() {";\n', set()),
    ("#define F(x) \\\n    f(x) {\nsms_status h(void (*cb)(int), double v[4])\n{\n}\n", {"h"}),
])
def test_definitions_reads_only_external_function_definitions(text, names):
    assert definitions(text) == names
