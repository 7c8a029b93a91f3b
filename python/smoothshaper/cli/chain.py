# SPDX-License-Identifier: Apache-2.0
"""Stages from the command line (``--stage KIND:key=value,...``, ``--kind`` with ``--wn``) and
the table of a chain's stages that design and analyze print."""
from __future__ import annotations

import argparse
import math

from .. import stages as _stages
from ..errors import ParameterError
from ..stages import Stage
from .common import CliError

__all__ = ["parse_stage", "chain_from_args", "stage_rows", "duration", "add_chain_options"]

_KEY_ALIASES = {"pole_zeta": "notch_pole_zeta"}
_KIND_ALIASES = {"notch": "notch_matched", "smooth_2hump_ei": "smooth_ei2"}
_INT_KEYS = ("k", "order")
_FLOAT_KEYS = ("T", "sigma", "wn", "f", "zeta", "tolerance", "notch_pole_zeta", "duration",
               "insensitivity")
_LIST_KEYS = ("amplitudes", "times")


def _items(spec: str, rest: str) -> list[str]:
    """``rest`` split at the commas outside brackets (``amplitudes=[a, b, c]`` is one item)."""
    items, depth, start = [], 0, 0
    for i, ch in enumerate(rest):
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
            if depth < 0:
                raise ParameterError("stage", f"stage {spec!r}: ']' without '['")
        elif ch == "," and depth == 0:
            items.append(rest[start:i])
            start = i + 1
    if depth:
        raise ParameterError("stage", f"stage {spec!r}: '[' without ']'")
    items.append(rest[start:])
    return [p.strip() for p in items if p.strip()]


def _number_list(spec: str, key: str, value: str) -> list[float]:
    text = value.strip()
    if not (text.startswith("[") and text.endswith("]")):
        raise ParameterError(
            "stage", f"stage {spec!r}: {key} must be a list in brackets, e.g. {key}=[0.5,0.5]")
    try:
        return [float(v) for v in text[1:-1].replace(",", " ").split()]
    except ValueError:
        raise ParameterError(
            "stage", f"stage {spec!r}: {key} must hold numbers, got {value!r}") from None


def parse_stage(spec: str) -> Stage:
    """One ``--stage`` spec (see the module docstring) -> Stage. ParameterError (a ValueError)
    naming ``stage`` on bad syntax."""
    kind, _, rest = spec.partition(":")
    kind = kind.strip().lower()
    kind = _KIND_ALIASES.get(kind, kind)
    if kind not in _stages.KINDS:
        raise ParameterError(
            "stage", f"stage {spec!r}: kind must be one of {', '.join(_stages.KINDS)}, "
                     "or notch")
    fields: dict = {}
    for item in _items(spec, rest):
        key, eq, value = item.partition("=")
        key = _KEY_ALIASES.get(key.strip(), key.strip())
        if not eq:
            raise ParameterError("stage", f"stage {spec!r}: expected key=value, got {item!r}")
        if key in fields:
            raise ParameterError("stage", f"stage {spec!r}: {key} given twice")
        if key in _LIST_KEYS:
            fields[key] = _number_list(spec, key, value)
        elif key in _INT_KEYS:
            try:
                fields[key] = int(value)
            except ValueError:
                raise ParameterError(
                    "stage", f"stage {spec!r}: {key} must be an integer, got {value!r}") from None
        elif key in _FLOAT_KEYS:
            try:
                fields[key] = float(value)
            except ValueError:
                raise ParameterError(
                    "stage", f"stage {spec!r}: {key} must be a number, got {value!r}") from None
        elif key == "timing":
            fields[key] = value.strip()
        else:
            raise ParameterError(
                "stage", f"stage {spec!r}: unknown key {key!r} (keys: T, sigma, k, wn, f, zeta, "
                         "order, tolerance, duration, insensitivity, notch_pole_zeta, timing, "
                         "amplitudes, times)")
    if "f" in fields:
        if "wn" in fields:
            raise ParameterError("stage", f"stage {spec!r}: give wn or f, not both")
        fields["wn"] = 2 * math.pi * fields.pop("f")
    if "insensitivity" in fields:
        if kind != "si" or "order" in fields or "duration" in fields:
            raise ParameterError(
                "stage", f"stage {spec!r}: insensitivity is for si, and designs its order and "
                         "duration (give either)")
        from ..filters import si_shaper
        return si_shaper(wn=fields.get("wn", 0.0), zeta=fields.get("zeta", 0.0),
                         insensitivity=fields["insensitivity"],
                         tolerance=fields.get("tolerance", 0.05),
                         timing=fields.get("timing", "exact"))
    if kind in _stages.SMOOTHERS and "T" not in fields and "wn" in fields:
        from ..filters import design_for_mode
        unused = set(fields) - {"wn", "zeta", "k", "timing"}
        if unused:
            raise ParameterError(
                "stage", f"stage {spec!r}: {', '.join(sorted(unused))} cannot be combined "
                         "with wn (the mode sets the smoother)")
        stage = design_for_mode(kind, wn=fields["wn"], zeta=fields.get("zeta", 0.0),
                                k=fields.get("k", 1))
        return stage.with_(timing=fields.get("timing", "exact"))
    if kind in _stages.SMOOTHERS and "T" not in fields:
        raise ParameterError(
            "stage", f"stage {spec!r}: a {kind} stage needs T=<seconds> or wn=<rad/s>")
    return Stage(kind, **fields)


def chain_from_args(args) -> list[Stage]:
    stages = [parse_stage(s) for s in (args.stage or [])]
    for kind in getattr(args, "kind", None) or []:
        if args.wn is None:
            raise CliError("--wn is required with --kind (the mode to design for)")
        from ..filters import design_for_mode
        stage = design_for_mode(kind, wn=args.wn, zeta=args.zeta, k=args.k)
        if kind == "zvn":
            stage = stage.with_(order=args.order)
        if kind in ("ei", "ei2", "ei3"):
            stage = stage.with_(tolerance=args.tolerance)
        stages.append(stage)
    return stages


def _shaper_duration(stage: Stage) -> float | None:
    """Time of a shaper's last impulse [s] (C sms_shaper_impulses), None for other kinds."""
    if stage.kind not in _stages.SHAPERS:
        return None
    from ..filters import _backend, _fill_config
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    _fill_config(config, stage)
    amps, times = ffi.new("double[64]"), ffi.new("double[64]")
    count = ffi.new("size_t *")
    if lib.sms_shaper_impulses(config, amps, times, 64, count) != 0:
        return None
    return max(times[i] for i in range(count[0]))


def duration(stage: Stage) -> float | None:
    if stage.kind in _stages.SMOOTHERS:
        return stage.T
    if stage.kind in _stages.INPUT_SMOOTHERS:
        from ..reference.input_smoothers import smoother_kernel
        return smoother_kernel(stage)[1]
    return _shaper_duration(stage)


def stage_rows(stages: list[Stage], Ts: float | None) -> tuple[list[str], list[list]]:
    header = ["#", "kind", "T [s]", "sigma [1/s]", "wn [rad/s]", "zeta", "k", "order", "timing"]
    if Ts is not None:
        header.append("L [samples]")
    rows = []
    for i, s in enumerate(stages):
        smoother = s.kind in _stages.SMOOTHERS
        mode = not smoother and s.kind != "impulses"
        row = [i, s.kind, duration(s), s.sigma if smoother else None,
               s.wn if mode else None, s.zeta if mode else None,
               s.k if smoother else None,
               s.order if s.kind in ("zvn", "gmzv", "si", "impulses") else None,
               None if s.kind in _stages.NOTCHES else s.timing]
        if Ts is not None:
            from ..filters import Chain, ParameterError
            try:
                row.append(Chain([s], Ts=Ts).length or "IIR")
            except ParameterError as exc:    # name the stage by its place in the whole chain
                raise ParameterError(exc.parameter, str(exc).replace(
                    "stages[0]", f"stages[{len(rows)}]"), exc.status) from None
        rows.append(row)
    return header, rows


def _kind_arg(text: str) -> str:
    """--kind value: kind names compare case-insensitively; 'notch' means notch_matched."""
    try:
        return _stages.kind_name(text)
    except ValueError:
        return text          # argparse then reports it against the choices


def add_chain_options(p, *, with_kind: bool = True) -> None:
    p.add_argument("--stage", action="append", metavar="STAGE",
                   help="a stage KIND:key=value,... (repeatable; see 'smoothshaper --help')")
    if with_kind:
        p.add_argument("--kind", action="append", choices=_stages.KINDS, type=_kind_arg,
                       help="design a stage of this kind for the mode --wn/--zeta (repeatable)")
    p.add_argument("--wn", type=float, help="natural frequency of the mode [rad/s]")
    p.add_argument("--zeta", type=float, default=0.0, help="damping ratio of the mode (default 0)")
    p.add_argument("--k", type=int, default=1, help="multiple of the zero placed on the mode "
                   "(odd for the harmonic families; default 1)")
    if with_kind:
        p.add_argument("--order", type=int, default=1, help="n of --kind zvn (default 1)")
    p.add_argument("--tolerance", type=float, default=0.05,
                   help="vibration tolerance V: the residual --kind ei/ei2 accept at the mode, "
                   "and the PRV level of analyze's insensitivity band (default 0.05 = 5 %%)")
    # The old name of --tolerance for design (deprecated, hidden).
    p.add_argument("--shaper-tolerance", dest="tolerance", type=float, help=argparse.SUPPRESS)
