# SPDX-License-Identifier: Apache-2.0
"""The one-line error of the command line: the option a library error comes from, paths by
the option that named them, numbers printed readably."""
from __future__ import annotations

import os
import re

__all__ = ["os_error", "option_for", "readable"]


def os_error(exc: OSError, argv: list[str]) -> str:
    """A failed file operation named by the option the user gave for the path (``--out=x:
    File exists (not a folder)``) instead of Python's ``[Errno 17] File exists: 'x'``."""
    if exc.filename is None or not exc.strerror:
        return str(exc)
    path = os.fsdecode(exc.filename)
    given = [f"{name}={value}" for name, value in _given(argv) if value == path]
    why = exc.strerror + (" (not a folder)" if isinstance(exc, FileExistsError) else "")
    return f"{given[0] if given else path}: {why}"


def _given(argv: list[str]) -> list[tuple[str, str]]:
    """(option, value) pairs as the user wrote them (--x=v or --x v)."""
    pairs = []
    for i, a in enumerate(argv):
        if a.startswith("--"):
            name, eq, value = a.partition("=")
            if not eq and i + 1 < len(argv) and not argv[i + 1].startswith("--"):
                value = argv[i + 1]
            pairs.append((name, value))
    return pairs


def option_for(parameter: str, message: str, argv: list[str]) -> str | None:
    """The options the user gave that a library ParameterError comes from: those whose values
    the message shows (``vmax[1]=...`` -> ``--vmax=1,2 (axis 1)``), else the option of
    ``parameter`` itself (or of the same name with a prefix, ``--shaper-tolerance``); a
    stage's field (``stages[0]``, ``T``) -> its ``--stage``/``--kind``; None if none."""
    given = _given(argv)
    options = {name: value for name, value in given}

    def shown(name, index=""):
        return f"{name}={options[name]}" + (f" (axis {index})" if index else "")
    found = []
    for m in re.finditer(r"(?<![\w\[-])([A-Za-z_]+)(?:\[(\d+)\])? ?=", message):
        name = "--" + m.group(1).replace("_", "-")
        if name in options and not any(f.startswith(name + "=") for f in found):
            found.append(shown(name, m.group(2) or ""))
    base, _, index = parameter.partition("[")
    base, index = base.replace("_", "-"), index.rstrip("]")
    if not found:
        same = [n for n in options if n == f"--{base}" or n.endswith(f"-{base}")]
        # of two options for one parameter (--tolerance, --shaper-tolerance): the one whose
        # value the message quotes
        quoted = [n for n in same if any(_quotes(message, v) for v in options[n].split(","))]
        if quoted or same:
            found.append(shown((quoted or same)[-1], index if index.isdigit() else ""))
    if not found:
        spec = next((v for n, v in given if n == "--stage" and f"{base}=" in v), None)
        if spec is not None:
            found.append(f"--stage {spec}")
    stage = re.search(r"stages\[(\d+)\]", message + " " + parameter)
    if stage and "--h" in options and not any(n in options for n in ("--stage", "--kind")):
        # the stages of a kinematic design come from its bounds
        found = [shown(n) for n in ("--h", "--vmax", "--amax", "--jmax") if n in options] + [
            f for f in found if f.startswith("--Ts=")]
    specs = [f"{n} {v}" for n, v in given if n in ("--stage", "--kind")]
    if stage and specs and not any(f.startswith(("--stage", "--kind")) for f in found):
        i = int(stage.group(1))
        found.insert(0, specs[i] if i < len(specs) else specs[-1])
    if not found and base in ("targets", "via") and "--via" in options:
        found.append("--via")
    if found and "--Ts" in options and not any(f.startswith("--Ts=") for f in found) and (
            " Ts=" in message or "T/Ts" in message):
        found.append(shown("--Ts"))      # a duration in samples: set by the two together
    return ", ".join(found) or None


def _quotes(message: str, text: str) -> bool:
    """Does the message quote the number the user wrote as ``text`` (in any usual form)?"""
    try:
        x = float(text)
    except ValueError:
        return False
    return any(form in message for form in (repr(x), f"{x:g}", f"{x:.6g}", text))


def readable(message: str) -> str:
    """Numbers with more than 6 significant digits as %.6g (integers of 10 or more digits as
    %.3g): an error line stays readable whatever the value."""
    def short(m):
        text = m.group(0)
        digits = len(re.sub(r"[^0-9]", "", text.split("e")[0].split("E")[0]).lstrip("0"))
        if "." not in text and "e" not in text.lower():
            return f"{float(text):.3g}" if digits >= 10 else text
        return f"{float(text):.6g}" if digits > 7 else text
    return re.sub(r"(?<![\w.])\d+(?:\.\d*)?(?:[eE][-+]?\d+)?", short, message)
