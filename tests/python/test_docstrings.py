# SPDX-License-Identifier: Apache-2.0
"""The public API documents itself: every function and class that a module of the API
reference (docs/api/*.rst) exports in ``__all__`` has a numpydoc docstring with a Parameters
section naming every parameter, a Returns section when it returns something and a Raises
section when it takes arguments (every public function validates them); the filter families
cite their source (a year in the docstring). The modules are read from docs/api, so a module
added to the reference is audited too."""
from __future__ import annotations

import ast
import dataclasses
import importlib
import inspect
import re
import textwrap
from pathlib import Path

import pytest

API_DIR = Path(__file__).resolve().parents[2] / "docs" / "api"

#: Functions that implement a filter family or a design rule from a paper: each docstring
#: must cite it (authors and year at least).
CITING = {"smoothshaper.reference.smoothers.smoother_taps",
          "smoothshaper.reference.shapers.shaper_impulses",
          "smoothshaper.reference.shapers.shaper_taps",
          "smoothshaper.reference.shapers.gmzv_undamped",
          "smoothshaper.reference.notch.notch_coefficients",
          "smoothshaper.stages.rectangular", "smoothshaper.stages.harmonic",
          "smoothshaper.stages.damped_harmonic", "smoothshaper.stages.exponential",
          "smoothshaper.stages.shaper", "smoothshaper.stages.notch",
          "smoothshaper.design.kinematic", "smoothshaper.filters.design_for_mode"}

def api_modules() -> list[str]:
    names = []
    for rst in sorted(API_DIR.glob("*.rst")):
        for line in rst.read_text().splitlines():
            m = re.match(r"\.\. automodule:: (\S+)", line.strip())
            if m and m.group(1) not in names:
                names.append(m.group(1))
    return names


def _section(doc: str, title: str) -> str | None:
    """Text of the numpydoc section ``title`` (up to the next section), or None."""
    m = re.search(rf"^{title}\n-{{3,}}\n(.*?)(?=^\S[^\n]*\n-{{3,}}\n|\Z)", doc, re.M | re.S)
    return m.group(1) if m else None


def _returns_value(func) -> bool:
    """True if the source returns something other than None (or yields)."""
    try:
        src = textwrap.dedent(inspect.getsource(func))
    except (OSError, TypeError):
        return False
    tree = ast.parse(src)
    body = tree.body[0]
    for node in ast.walk(body):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)) \
                and node is not body:
            continue
        if isinstance(node, (ast.Yield, ast.YieldFrom)):
            return True
        if isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            return True
    return False


def _parameters(func, skip_first: bool) -> list[str]:
    params = list(inspect.signature(func).parameters.values())
    if skip_first and params:
        params = params[1:]
    return [p.name for p in params]


def _documents(section: str, name: str) -> bool:
    """``name`` appears as a parameter entry: at the start of a line, alone or in a list
    ``a, b : type``, or as ``*args`` / ``**kwargs``."""
    bare = name.lstrip("*")
    return re.search(rf"^\s*(\*{{0,2}}\w+\s*,\s*)*\*{{0,2}}{re.escape(bare)}\b\s*(,|:|$)",
                     section, re.M) is not None


def audit_callable(qualname: str, func, *, doc_source=None, skip_first=False,
                   cite=False) -> list[str]:
    """Problems of one callable's docstring (empty when it meets the standard)."""
    doc = inspect.getdoc(doc_source if doc_source is not None else func) or ""
    if not doc.strip():
        return [f"{qualname}: no docstring"]
    problems = []
    names = _parameters(func, skip_first)
    if names:
        section = _section(doc, "Parameters") or _section(doc, "Other Parameters")
        if section is None:
            problems.append(f"{qualname}: no Parameters section")
        else:
            missing = [n for n in names if not _documents(section, n)]
            if missing:
                problems.append(f"{qualname}: Parameters does not list {', '.join(missing)}")
        if _section(doc, "Raises") is None:
            problems.append(f"{qualname}: no Raises section")
    if _returns_value(func) and _section(doc, "Returns") is None \
            and _section(doc, "Yields") is None:
        problems.append(f"{qualname}: returns a value but has no Returns section")
    if cite and not re.search(r"\b(19|20)\d\d\b", doc):
        problems.append(f"{qualname}: cites no source (authors, title, year, equation)")
    return problems


def audit_module(name: str) -> list[str]:
    module = importlib.import_module(name)
    exported = getattr(module, "__all__", None)
    if exported is None:
        return [f"{name}: no __all__"]
    problems = []
    for attr in exported:
        obj = getattr(module, attr)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        if not (getattr(obj, "__module__", "") or "").startswith(name.split(".")[0]):
            continue
        if getattr(obj, "__module__", "") != name:
            continue        # audited where it is defined
        qual = f"{name}.{attr}"
        cite = qual in CITING
        if inspect.isfunction(obj):
            problems += audit_callable(qual, obj, cite=cite)
            continue
        if issubclass(obj, BaseException):
            if not (inspect.getdoc(obj) or "").strip():
                problems.append(f"{qual}: no docstring")
            continue
        init = obj.__dict__.get("__init__")
        if dataclasses.is_dataclass(obj):
            doc = inspect.getdoc(obj) or ""
            section = _section(doc, "Attributes") or _section(doc, "Parameters")
            fields = [f.name for f in dataclasses.fields(obj)]
            if section is None:
                problems.append(f"{qual}: dataclass without an Attributes section")
            else:
                missing = [f for f in fields if not _documents(section, f)]
                if missing:
                    problems.append(f"{qual}: Attributes does not list {', '.join(missing)}")
        elif init is not None and inspect.isfunction(init):
            problems += audit_callable(qual, init, doc_source=obj, skip_first=True)
        elif not (inspect.getdoc(obj) or "").strip():
            problems.append(f"{qual}: no docstring")
        for mname, member in obj.__dict__.items():
            if mname.startswith("_"):
                continue
            if isinstance(member, property):
                if not (inspect.getdoc(member) or "").strip():
                    problems.append(f"{qual}.{mname}: property without docstring")
            elif isinstance(member, (staticmethod, classmethod)):
                problems += audit_callable(f"{qual}.{mname}", member.__func__,
                                           skip_first=isinstance(member, classmethod))
            elif inspect.isfunction(member):
                problems += audit_callable(f"{qual}.{mname}", member, skip_first=True)
    return problems


@pytest.mark.parametrize("name", api_modules())
def test_public_api_docstrings(name):
    problems = audit_module(name)
    assert not problems, "\n".join(problems)


def test_the_audit_finds_what_is_missing():
    """The checker itself: a function without sections, with an undocumented parameter, and
    one that is complete."""
    def bare(x, *, Ts):
        """Filter x."""
        return x

    def partial(x, *, Ts):
        """Filter x.

        Parameters
        ----------
        x : array_like
            Input.

        Returns
        -------
        ndarray
        """
        return x

    def complete(x, *, Ts):
        """Filter x (Biagiotti and Melchiorri, 2012).

        Parameters
        ----------
        x : array_like
            Input, shape (n,).
        Ts : float
            Sample period [s].

        Returns
        -------
        ndarray
            Output, shape (n,).

        Raises
        ------
        ParameterError
            Ts is not positive.
        """
        return x

    assert len(audit_callable("bare", bare)) == 3
    assert audit_callable("partial", partial) == [
        "partial: Parameters does not list Ts", "partial: no Raises section"]
    assert audit_callable("complete", complete, cite=True) == []
    assert audit_callable("partial", partial, cite=True)[-1].endswith("cites no source "
                                                                      "(authors, title, year, "
                                                                      "equation)")


def test_the_reference_lists_every_public_module():
    listed = set(api_modules())
    for name in ("smoothshaper.stages", "smoothshaper.filters", "smoothshaper.analysis",
                 "smoothshaper.design", "smoothshaper.plants", "smoothshaper.errors"):
        assert name in listed
