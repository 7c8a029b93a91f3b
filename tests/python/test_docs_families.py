# SPDX-License-Identifier: Apache-2.0
"""docs/families.md cannot rot: everything it names exists.

Each family section links its math, C functions, Python objects, NumPy reference and tests.
A renamed header, function, class or test, a moved page or heading, or a new stage kind without
a section fails here rather than leaving a dead pointer for the reader.
"""
from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGE = DOCS / "families.md"
TEXT = PAGE.read_text()
HEADERS = "\n".join(p.read_text() for p in sorted((ROOT / "c/include/smoothshaper").glob("*.h")))
BULLETS = ("Math", "C", "Python", "NumPy reference", "Tests")


def sections() -> dict[str, str]:
    parts = re.split(r"^## (.+)$", TEXT, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def links(text: str) -> list[str]:
    return re.findall(r"\]\(([^)]+)\)", text)


def code_spans(text: str) -> list[str]:
    return re.findall(r"`([^`\n]+)`", text)


def slug(heading: str) -> str:
    """The anchor a Markdown renderer (GitHub's rule) gives a heading."""
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    return {slug(h) for h in re.findall(r"^#+ (.+)$", page.read_text(), flags=re.M)}


def test_every_section_has_math_c_python_reference_and_tests():
    assert sections(), "docs/families.md has no family sections"
    for title, body in sections().items():
        for bullet in BULLETS:
            assert re.search(rf"^- {re.escape(bullet)}:", body, re.M), \
                f"section {title!r} has no '- {bullet}:' line"


@pytest.mark.parametrize("target", sorted(set(links(TEXT))))
def test_linked_file_and_heading_exist(target):
    assert "://" not in target, f"{target}: the page links only files of the repository"
    path, _, anchor = target.partition("#")
    file = (DOCS / path).resolve()
    assert file.is_file(), f"{target}: no such file"
    assert ROOT in file.parents, f"{target}: outside the repository"
    if anchor:
        assert anchor in anchors(file), f"{target}: no heading with that anchor in {path}"


def declared_functions() -> set[str]:
    return set(re.findall(r"SMS_API[^;{]*?\b(sms_\w+)\s*\(", HEADERS))


@pytest.mark.parametrize("name", sorted({s[:-2] for s in code_spans(TEXT)
                                         if re.fullmatch(r"sms_\w+\(\)", s)}))
def test_named_c_function_is_declared_in_a_header(name):
    assert name in declared_functions(), f"{name}() is not declared in c/include/smoothshaper"


@pytest.mark.parametrize("name", sorted({s for s in code_spans(TEXT)
                                         if re.fullmatch(r"SMS_[A-Z0-9_]+", s)}))
def test_named_c_constant_exists(name):
    assert re.search(rf"\b{name}\b\s*(=|,|\n)|#define {name}\b", HEADERS), \
        f"{name} is not an enumerator or macro of c/include/smoothshaper"


@pytest.mark.parametrize("field", sorted({s for s in code_spans(TEXT) if "::" in s}))
def test_named_struct_field_exists(field):
    struct, member = field.split("::")
    body = re.search(rf"typedef struct {struct} \{{(.*?)\}} {struct};", HEADERS, re.S)
    assert body, f"{struct} is not a struct of c/include/smoothshaper"
    assert re.search(rf"\b{member}\b\s*(\[[^\]]*\])?\s*[;,]", body.group(1)), \
        f"{struct} has no field {member}"


@pytest.mark.parametrize("name", sorted({s for s in code_spans(TEXT)
                                         if re.fullmatch(r"smoothshaper(\.\w+)+", s)}))
def test_named_python_object_exists(name):
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):       # the longest importable module, then attributes
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for attr in parts[cut:]:
            assert hasattr(obj, attr), f"{name}: {'.'.join(parts[:cut])} has no {attr}"
            obj = getattr(obj, attr)
        return
    pytest.fail(f"{name}: no such module")


@pytest.mark.parametrize("title", sorted(sections()))
def test_named_tests_exist_in_the_linked_test_files(title):
    body = sections()[title]
    files = [(DOCS / t).resolve() for t in links(body) if t.startswith("../tests/")]
    source = "\n".join(f.read_text() for f in files if f.is_file())
    for name in {s for s in code_spans(body) if re.fullmatch(r"test_\w+", s)}:
        assert re.search(rf"^def {name}\(|\b{name}\s*\(void\)", source, re.M), \
            f"section {title!r}: {name} is in none of its linked test files"


def test_every_stage_kind_has_a_section():
    enum = re.search(r"typedef enum sms_kind \{(.*?)\} sms_kind;", HEADERS, re.S).group(1)
    kinds = re.findall(r"^\s*(SMS_[A-Z0-9_]+)\s*=", enum, re.M)
    assert len(kinds) == int(re.search(r"#define SMS_KIND_COUNT (\d+)", HEADERS).group(1))
    named = set(code_spans(TEXT))
    assert [k for k in kinds if k not in named] == []


def test_the_docs_index_links_the_page():
    assert "(families.md)" in (DOCS / "index.md").read_text()
