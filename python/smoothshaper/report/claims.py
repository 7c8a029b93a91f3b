# SPDX-License-Identifier: Apache-2.0
"""Numbers of the report, each next to the value it is checked against.

A :class:`Claim` is the single record that the markdown report prints and the tests assert:
our number, the reference it must match (the paper's printed value, or an exact closed form
when the paper prints none or prints a wrong one), the tolerance and why. When our number
disagrees with the paper, ``paper`` holds the paper's value, ``expected`` what we assert
instead, and ``note`` the explanation; the tests then also assert that the disagreement is
real (so an explanation cannot outlive the discrepancy it explains).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["RELATIONS", "Claim", "Figure", "Section", "fmt", "claims_table"]

RELATIONS = ("==", "<=", ">=")


@dataclass(frozen=True)
class Claim:
    """One checked number.

    ``relation`` '==' means ``|ours - expected| <= tol``; '<=' means ``ours <= expected + tol``;
    '>=' means ``ours >= expected - tol``. ``reference`` says where ``expected`` comes from
    (e.g. "paper, Fig. 5", "closed form 100|cos(pi r/2)|").
    """

    key: str
    what: str
    ours: float
    expected: float
    tol: float
    reference: str
    unit: str = ""
    relation: str = "=="
    paper: float | None = None
    note: str = ""

    def __post_init__(self):
        if self.relation not in RELATIONS:
            raise ValueError(f"relation must be one of {RELATIONS}, got {self.relation!r}")
        if not (self.tol >= 0 and math.isfinite(self.tol)):
            raise ValueError(f"tol must be finite and >= 0, got {self.tol!r}")
        object.__setattr__(self, "ours", float(self.ours))
        object.__setattr__(self, "expected", float(self.expected))

    @property
    def holds(self) -> bool:
        """Whether our number satisfies the claim within its tolerance."""
        if not math.isfinite(self.ours):
            return False
        if self.relation == "==":
            return abs(self.ours - self.expected) <= self.tol
        if self.relation == "<=":
            return self.ours <= self.expected + self.tol
        return self.ours >= self.expected - self.tol

    @property
    def disagrees_with_paper(self) -> bool:
        """True when the paper printed a value and we assert something else instead."""
        return self.paper is not None and self.paper != self.expected


@dataclass(frozen=True)
class Figure:
    path: Path
    caption: str


@dataclass
class Section:
    """One part of the report: a seed (or the shapers beyond the seeds)."""

    key: str
    title: str
    claim: str            # what the source says, in one paragraph
    command: str          # how to reproduce just this section
    claims: list[Claim] = field(default_factory=list)
    figures: list[Figure] = field(default_factory=list)
    body: str = ""        # method and discussion, markdown
    seconds: float = 0.0  # wall time to build

    def add(self, *claims: Claim) -> None:
        keys = {c.key for c in self.claims}
        for c in claims:
            if c.key in keys:
                raise ValueError(f"duplicate claim key {c.key!r} in section {self.key}")
            keys.add(c.key)
            self.claims.append(c)


def fmt(x: float | None, unit: str = "") -> str:
    """A number for a table: 4 significant digits, scientific when tiny or huge."""
    if x is None:
        return "-"
    if x == 0:
        s = "0"
    elif not math.isfinite(x):
        s = str(x)
    elif abs(x) < 1e-3 or abs(x) >= 1e5:
        s = f"{x:.3e}"
    else:
        s = f"{x:.4g}"
    return f"{s} {unit}".strip()


def _cell(text: str) -> str:
    """Table-safe text: a literal '|' (as in |H(p)|) would split the cell."""
    return text.replace("|", "\\|")


def claims_table(claims: list[Claim]) -> str:
    """Markdown table: what, paper, ours, asserted, tolerance, status, note."""
    rows = ["| claim | paper | ours | asserted against | tolerance | ok |",
            "|---|---|---|---|---|---|"]
    notes = []
    for c in claims:
        rel = {"==": "=", "<=": "&le;", ">=": "&ge;"}[c.relation]
        asserted = f"{rel} {fmt(c.expected, c.unit)} ({_cell(c.reference)})"
        mark = "yes" if c.holds else "**NO**"
        what = _cell(c.what)
        if c.note:
            notes.append(c)
            what += f" [note {len(notes)}]"
        rows.append(f"| {what} | {fmt(c.paper, c.unit)} | {fmt(c.ours, c.unit)} | {asserted} "
                    f"| {fmt(c.tol, c.unit)} | {mark} |")
    out = "\n".join(rows)
    if notes:
        out += "\n\n" + "\n".join(f"{i}. **{c.what}**: {c.note}" for i, c in enumerate(notes, 1))
    return out
