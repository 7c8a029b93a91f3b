# SPDX-License-Identifier: Apache-2.0
"""Precomputed coefficients for firmware: a chain designed here, built on the target without
double arithmetic or libm (the C API of ``c/include/smoothshaper/coeffs.h``, docs/firmware.md).

:func:`c_source` writes the C definition of an ``sms_stage_coeffs`` array for a chain, in both
precisions (the target's ``SMS_USE_FLOAT`` picks one); on the target,
``sms_chain_init_coeffs`` builds the chain from it with copies and checks only, and it is the
chain ``sms_chain_init`` would design from the same stages there, bit for bit. The numbers are
computed by the C core of each precision (the ``float`` values by the float build), so nothing
is rounded twice. :func:`coefficients` returns the same numbers as Python values.
"""
from __future__ import annotations

import re

import numpy as np

from . import __version__
from . import stages as _stages
from .errors import ParameterError
from .filters import PRECISIONS, Chain, _backend, _fill_config

__all__ = ["coefficients", "c_source"]

_C_KIND = {kind: "SMS_" + ("SHAPER_" if kind in _stages.SHAPERS else "") + kind.upper()
           for kind in _stages.KINDS}
#: The kinds whose coefficients are a tap table (shapers and input smoothers).
_FIR = _stages.SHAPERS + _stages.INPUT_SMOOTHERS
_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,55}$")   # NAME_stages stays within 63


def _made(stages, Ts: float, precision: str):
    """The C coefficients of each stage: [(ffi, coeffs, taps)] from the ``precision`` build."""
    chain = Chain(stages, Ts=Ts, precision=precision)    # every check, with its message
    ffi, lib = _backend(precision)
    made = []
    for i, stage in enumerate(chain.stages):
        config = ffi.new("sms_stage_config *")
        _fill_config(config, stage)
        coeffs = ffi.new("sms_stage_coeffs *")
        n_taps = ffi.new("size_t *", lib.SMS_SHAPER_MAX_TAPS)
        if stage.kind in _FIR:      # an input smoother has a tap per sample of its window
            lib.sms_shaper_tap_count(config, chain.Ts, n_taps)
        taps = ffi.new("sms_shaper_tap[]", n_taps[0])
        status = lib.sms_stage_coeffs_make(config, chain.Ts, coeffs, taps, n_taps[0])
        if status != 0:        # the Chain above accepted the same config
            raise RuntimeError(f"sms_stage_coeffs_make failed ({status}) on stages[{i}]")
        made.append((coeffs, taps))
    return chain, made


def coefficients(stages, *, Ts: float, precision: str = "float") -> list[dict]:
    """The precomputed coefficients of a chain, one dict per stage, as the C core of
    ``precision`` makes them (``sms_stage_coeffs_make``).

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain (``smoothshaper.stages``), 1 to 16 stages.
    Ts : float, keyword-only
        Sample period of the target [s], finite and > 0.
    precision : {'float', 'double'}, keyword-only
        The target's ``sms_real`` (default float, the common microcontroller build).

    Returns
    -------
    list of dict
        Per stage: ``kind``, ``identity`` (15 floats, config.h) and the family's fields:
        smoothers ``length``, ``window``, ``pole_m1_re``, ``pole_im``, ``pole_lo_re``,
        ``pole_lo_im``, ``gain``, ``tail_re``, ``tail_im``, ``correction_delay``,
        ``correction_gain`` (empty without direct taps), ``input_limit``; shapers and input
        smoothers ``length`` and ``taps`` (``(delay, gain)`` pairs); notches ``d0``, ``d2``, ``a1``, ``a2``. The
        reals are Python floats holding the ``precision`` values exactly.

    Raises
    ------
    ParameterError
        As :class:`~smoothshaper.Chain` for the stages and ``Ts``; naming ``precision``.
    """
    if precision not in PRECISIONS:
        raise ParameterError("precision", f"precision must be one of {PRECISIONS}, got "
                             f"{precision!r}")
    _, made = _made(stages, Ts, precision)
    out = []
    for coeffs, _taps in made:
        kind = _stages.KINDS[coeffs.kind]
        entry = {"kind": kind, "identity": [float(v) for v in coeffs.identity]}
        if kind in _stages.SMOOTHERS:
            s = coeffs.u.smoother
            n = int(s.n_corrections)
            entry.update(length=int(s.length), window=int(s.window),
                         **{f: float(getattr(s, f)) for f in (
                             "pole_m1_re", "pole_im", "pole_lo_re", "pole_lo_im", "gain",
                             "tail_re", "tail_im")},
                         correction_delay=[int(s.correction_delay[j]) for j in range(n)],
                         correction_gain=[float(s.correction_gain[j]) for j in range(n)],
                         input_limit=float(s.input_limit))
        elif kind in _FIR:
            s = coeffs.u.shaper
            entry.update(length=int(s.length),
                         taps=[(int(s.taps[j].delay), float(s.taps[j].gain))
                               for j in range(int(s.n_taps))])
        else:
            s = coeffs.u.notch
            entry.update(d0=float(s.d0), d2=float(s.d2), a1=float(s.a1), a2=float(s.a2))
        out.append(entry)
    return out


def _real(v: float, precision: str) -> str:
    """A C literal that reads back as exactly v (9 significant digits round-trip a float, 17 a
    double)."""
    if precision == "float":
        text = f"{v:.9g}"
        assert np.float32(text) == np.float32(v)
    else:
        text = f"{v:.17g}"
        assert float(text) == v
    if not re.search(r"[.eEn]", text):
        text += ".0"
    return text + ("f" if precision == "float" else "")


def _double(v: float) -> str:
    text = f"{v:.17g}"
    return text if re.search(r"[.eEn]", text) else text + ".0"


def _wrap(items: list[str], first: str, indent: str, last: str, width: int = 96) -> list[str]:
    """``first`` + items joined by ", " + ``last``, wrapped at ``width`` columns under
    ``indent``."""
    lines, line = [], first
    for k, item in enumerate(items):
        piece = item + (", " if k + 1 < len(items) else last)
        if len(line) + len(piece.rstrip()) > width and line.strip():
            lines.append(line.rstrip())
            line = indent
        line += piece
    lines.append(line.rstrip())
    return lines


def _definitions(name: str, stages_out: list[dict], precision: str) -> list[str]:
    lines = []
    for i, c in enumerate(stages_out):
        if "taps" in c:
            taps = [f"{{{d}u, {_real(g, precision)}}}" for d, g in c["taps"]]
            lines += _wrap(taps, f"static const sms_shaper_tap {name}_taps_{i}[{len(taps)}] = {{",
                           "    ", "};")
    lines.append(f"const sms_stage_coeffs {name}[{len(stages_out)}] = {{")
    for i, c in enumerate(stages_out):
        end = "}}," if i + 1 < len(stages_out) else "}}"
        lines.append(f"    {{{_C_KIND[c['kind']]},")
        lines += _wrap([_double(v) for v in c["identity"]], "     {", "      ", "},")
        if c["kind"] in _stages.SMOOTHERS:
            n = len(c["correction_delay"])
            delays = ", ".join(f"{d}u" for d in c["correction_delay"] + [0] * (2 - n))
            gains = ", ".join(_real(g, precision) for g in c["correction_gain"] + [0.0] * (2 - n))
            items = [f"{c['length']}u", f"{c['window']}u"]
            items += [_real(c[f], precision) for f in (
                "pole_m1_re", "pole_im", "pole_lo_re", "pole_lo_im", "gain", "tail_re",
                "tail_im")]
            items += [f"{n}u", f"{{{delays}}}", f"{{{gains}}}", _double(c["input_limit"])]
            lines += _wrap(items, "     {.smoother = {", "                   ", "}" + end)
        elif "taps" in c:
            lines.append(f"     {{.shaper = {{{c['length']}u, {len(c['taps'])}u, "
                         f"{name}_taps_{i}}}{end}")
        else:
            reals = [_real(c[f], precision) for f in ("d0", "d2", "a1", "a2")]
            lines += _wrap(reals, "     {.notch = {", "                ", "}" + end)
    lines.append("};")
    return lines


def c_source(stages, *, Ts: float, name: str = "smoothshaper_chain") -> str:
    """C source defining ``const sms_stage_coeffs NAME[n]``: the chain's precomputed
    coefficients for a firmware target, in both precisions.

    On the target (nothing designed, no double arithmetic, no libm)::

        extern const sms_stage_coeffs NAME[];     /* this file, compiled with the library */
        extern const size_t NAME_stages;          /* its number of stages */
        sms_chain_coeffs_memory_size(NAME, NAME_stages, &need);
        sms_chain_init_coeffs(&chain, stages, NAME, NAME_stages, memory, n_cells);

    The values are the C core's own (the float build's for ``SMS_USE_FLOAT``, else the double
    build's), written so that they read back exactly; the chain built from them equals, bit
    for bit, ``sms_chain_init`` of the same stages at the same ``Ts`` in that precision.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain, 1 to 16 stages (e.g. from ``design.for_mode`` or ``calibrate``).
    Ts : float, keyword-only
        Sample period of the target [s], finite and > 0.
    name : str, keyword-only
        C identifier of the array (up to 56 characters); ``NAME_stages`` (a ``const size_t``)
        is its length.

    Returns
    -------
    str
        The C source (includes ``smoothshaper/coeffs.h``).

    Raises
    ------
    ParameterError
        As :class:`~smoothshaper.Chain` for the stages and ``Ts``; naming ``name`` if it is
        not a C identifier.
    """
    if not isinstance(name, str) or not _IDENTIFIER.match(name):
        raise ParameterError("name", f"name must be a C identifier of at most 56 characters, "
                             f"got {name!r}")
    per_precision = {p: coefficients(stages, Ts=Ts, precision=p) for p in ("float", "double")}
    chain = Chain(stages, Ts=Ts)
    described = "\n".join(f" *   {i}: {_describe(s)}" for i, s in enumerate(chain.stages))
    lines = [f"/* Precomputed coefficients (smoothshaper {__version__}, coeffs.h) of the chain",
             described,
             f" * at Ts = {chain.Ts!r} s; FIR length {chain.length} samples. Both precisions: "
             "SMS_USE_FLOAT picks",
             " * the float values. On the target, with no design:",
             f" *   extern const sms_stage_coeffs {name}[];",
             f" *   extern const size_t {name}_stages;",
             f" *   sms_chain_coeffs_memory_size({name}, {name}_stages, &need);",
             f" *   sms_chain_init_coeffs(&chain, stages, {name}, {name}_stages, memory, "
             "n_cells); */",
             '#include "smoothshaper/coeffs.h"', "",
             f"extern const sms_stage_coeffs {name}[{len(chain.stages)}];",
             f"extern const size_t {name}_stages;",
             f"const size_t {name}_stages = {len(chain.stages)}u;", "",
             "#ifdef SMS_USE_FLOAT"]
    lines += _definitions(name, per_precision["float"], "float")
    lines.append("#else")
    lines += _definitions(name, per_precision["double"], "double")
    lines.append("#endif")
    return "\n".join(lines) + "\n"


def _describe(s) -> str:
    if s.kind in _stages.SMOOTHERS:
        extra = f", sigma = {s.sigma!r} 1/s" if s.kind in ("damped_harmonic", "exponential") else ""
        return f"{s.kind}, T = {s.T!r} s{extra}, {s.timing} timing"
    if s.kind in _stages.SHAPERS:
        return f"{s.kind} shaper, wn = {s.wn!r} rad/s, zeta = {s.zeta!r}, {s.timing} timing"
    return f"{s.kind}, wn = {s.wn!r} rad/s, zeta = {s.zeta!r}, pole zeta = {s.notch_pole_zeta!r}"
