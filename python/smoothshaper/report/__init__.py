# SPDX-License-Identifier: Apache-2.0
"""Seed reproduction report: the papers' figures and numbers regenerated and checked.

``run(out_dir)`` writes ``out_dir/README.md`` and the PNG figures it shows. Each section is one
module with a ``build(fig_dir=None)`` function returning a :class:`~.claims.Section`; the tests
call the same functions (without figures) and assert every :class:`~.claims.Claim`, so the
report cannot drift from what is tested. Reproduce from the command line with
``smoothshaper report --out DIR`` or ``python -m smoothshaper.report --out DIR [--only KEY ...]``.
"""
from __future__ import annotations

import importlib
import os
import time
import traceback
from pathlib import Path

from .. import _optional
from ..errors import ParameterError
from .claims import Claim, Figure, Section, claims_table

#: Section keys in report order (most valuable first), each the name of a module here.
SECTIONS = ("seed000", "seed001", "seed002", "seed003", "seed004", "shapers", "scheduled")

__all__ = ["run", "build_section", "SECTIONS", "REQUIRES", "Claim", "Figure", "Section"]

#: The optional packages a run needs (extra ``plot``), checked before it starts.
REQUIRES = ("matplotlib",)


def build_section(key: str, fig_dir: Path | None = None) -> Section:
    """Build one section; figures go to ``fig_dir`` (none drawn when it is None)."""
    if key not in SECTIONS:
        raise ParameterError(
            "section", f"section must be one of {', '.join(SECTIONS)}, got {key!r}")
    module = importlib.import_module(f".{key}", __name__)
    t0 = time.perf_counter()
    section = module.build(fig_dir)
    section.seconds = time.perf_counter() - t0
    return section


def _render(section: Section, out_dir: Path) -> str:
    parts = [f"## {section.title}", "", f"**Claim.** {section.claim}", "",
             f"**Reproduce:** `{section.command}`", ""]
    if section.body:
        parts += [section.body.strip(), ""]
    if section.claims:
        parts += ["### Numbers", "", claims_table(section.claims), ""]
    for fig in section.figures:
        rel = fig.path.relative_to(out_dir).as_posix()
        parts += [f"![{fig.caption}]({rel})", "", f"*{fig.caption}*", ""]
    parts += [f"<sub>built in {section.seconds:.1f} s</sub>", ""]
    return "\n".join(parts)


def run(out_dir, *, only=None, progress=None) -> Path:
    """Write the report into ``out_dir`` (created if needed) and return the README path.

    ``only``: section keys to build (default: all, in :data:`SECTIONS` order); ``progress``:
    None or a callable called as ``progress(key)`` when each section starts. Raises
    ParameterError naming ``only`` for an unknown section, and RuntimeError after writing the
    report if a section failed to build or a claim does not hold.
    """
    out_dir = Path(out_dir)
    keys = list(SECTIONS if only is None else only)
    for key in keys:
        if key not in SECTIONS:
            raise ParameterError(
                "only", f"only must name sections among {', '.join(SECTIONS)}, got {key!r}")
    _optional.require_all(REQUIRES, "smoothshaper report")
    out_dir.mkdir(parents=True, exist_ok=True)
    rendered, summary, failures = [], [], []
    for key in keys:
        if progress is not None:
            progress(key)
        try:
            section = build_section(key, out_dir / "figures" / key)
        except _optional.MissingDependency:
            raise       # the installation lacks an extra: say which, write no half report
        except Exception:  # a broken section is reported, the others still build
            failures.append(key)
            rendered.append(f"## {key}\n\n**This section failed to build:**\n\n```\n"
                            f"{traceback.format_exc()}```\n")
            summary.append(f"| {key} | failed | - | - |")
            continue
        bad = [c.key for c in section.claims if not c.holds]
        if bad:
            failures.append(f"{key}: {', '.join(bad)}")
        n_ok = len(section.claims) - len(bad)
        n_dis = sum(c.disagrees_with_paper for c in section.claims)
        summary.append(f"| [{section.title}](#{_anchor(section.title)}) "
                       f"| {n_ok}/{len(section.claims)} | {n_dis} | {section.seconds:.1f} s |")
        rendered.append(_render(section, out_dir))
    head = ["# smoothshaper: reproduction of the seed papers", "",
            "The seed papers are the five source papers the library implements (seed 000 to "
            "004; authors, titles and years in the repository's `docs/references.md`). "
            "Every number below is computed by `smoothshaper` (stages, NumPy reference, analysis "
            "and plant models) when this report is built, and the same numbers are asserted by "
            "`tests/python/test_report*.py` and `tests/python/test_seed*.py`. Each row gives the "
            "paper's printed value (when it prints one), ours, what it is asserted against (the "
            "paper, or an exact closed form where the paper prints no number or a wrong one) and "
            "the tolerance. Disagreements with a paper are kept in the table with a note.", "",
            "| section | claims that hold | disagreements with the paper (explained) | time |",
            "|---|---|---|---|", *summary, ""]
    validation = out_dir.parent / "validation" / "README.md"
    if validation.is_file():   # written by `smoothshaper validate` (scripts/main.sh runs it first)
        head += ["The FMUs are checked against the same NumPy reference by `smoothshaper "
                 f"validate`: see [its report]({os.path.relpath(validation, out_dir)}).", ""]
    readme = out_dir / "README.md"
    readme.write_text("\n".join(head) + "\n" + "\n".join(rendered))
    if failures:
        raise RuntimeError("report written to %s, but: %s" % (readme, "; ".join(failures)))
    return readme


def _anchor(title: str) -> str:
    keep = "".join(ch for ch in title.lower() if ch.isalnum() or ch in " -")
    return keep.replace(" ", "-")
