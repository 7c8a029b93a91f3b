# SPDX-License-Identifier: Apache-2.0
"""Ready-to-use outputs of a calibration: table, JSON, C config, FMU start values, firmware
configuration.

* ``recommended.stages``: dicts that ``smoothshaper.Stage(**d)`` accepts, so
  ``Chain([Stage(**d) for d in stages], Ts=...)`` builds the filter.
* ``c_config``: C code filling ``sms_stage_config`` values for ``sms_chain_init``.
* ``c_coeffs``: the chain's precomputed coefficients for ``sms_chain_init_coeffs`` (a firmware
  target builds it without designing it: no double arithmetic, no libm).
* ``fmu_start_values``: ``fmpy.simulate_fmu(start_values=...)`` values for SmoothShaper.fmu.
* ``firmware_config``: with ``--firmware``, the firmware's configuration for every analysed
  axis (:func:`.firmware.config_text`), with the suggested maximum acceleration.
"""
from __future__ import annotations

import json
import os
import math
from dataclasses import asdict

from .candidates import Candidate
from ..stages import INPUT_SMOOTHERS

__all__ = ["C_KIND", "range_statement", "c_config", "c_coeffs", "fmu_start_values", "axis_json", "to_json",
           "write_json", "report_text", "firmware_picks", "firmware_config"]

C_KIND = {"rectangular": "SMS_RECTANGULAR", "harmonic": "SMS_HARMONIC",
          "damped_harmonic": "SMS_DAMPED_HARMONIC", "exponential": "SMS_EXPONENTIAL",
          "zv": "SMS_SHAPER_ZV", "zvd": "SMS_SHAPER_ZVD", "zvdd": "SMS_SHAPER_ZVDD",
          "zvn": "SMS_SHAPER_ZVN", "ei": "SMS_SHAPER_EI", "ei2": "SMS_SHAPER_EI2",
          "mzv": "SMS_SHAPER_MZV", "ei3": "SMS_SHAPER_EI3", "gmzv": "SMS_SHAPER_GMZV",
          "notch_tustin": "SMS_NOTCH_TUSTIN", "notch_matched": "SMS_NOTCH_MATCHED",
          "impulses": "SMS_SHAPER_IMPULSES", "si": "SMS_SHAPER_SI",
          **{k: "SMS_" + k.upper() for k in INPUT_SMOOTHERS}}


def c_config(c: Candidate, Ts: float, axis: str) -> str:
    """C statements that fill ``cfg[]`` for the recommended chain of ``axis``."""
    n = len(c.stages)
    lines = [f"/* smoothshaper calibrate, axis {axis}: {c.name}, remaining vibration "
             f"{c.vibration:.3g} %, delay {c.length:.4g} s (designed for Ts = {Ts:g} s) */",
             f"sms_stage_config cfg_{axis}[{n}];"]
    for i, s in enumerate(c.stages):
        v = f"cfg_{axis}[{i}]"
        lines.append(f"{v} = sms_stage_config_default({C_KIND[s.kind]});")
        if s.kind in ("rectangular", "harmonic", "damped_harmonic", "exponential"):
            lines.append(f"{v}.T = {s.T!r};  /* s */")
            if s.sigma:
                lines.append(f"{v}.sigma = {s.sigma!r};  /* 1/s */")
            if s.k != 1:
                lines.append(f"{v}.k = {s.k}u;")
        elif s.kind == "impulses":
            lines.append(f"{v}.order = {s.order}u;")
            for j, (a, t) in enumerate(zip(s.amplitudes, s.times)):
                lines.append(f"{v}.amplitudes[{j}] = {a!r}; {v}.times[{j}] = {t!r};  /* s */")
        else:
            lines.append(f"{v}.wn = {s.wn!r};  /* rad/s ({s.wn / (2 * math.pi):.6g} Hz) */")
            lines.append(f"{v}.zeta = {s.zeta!r};")
            if s.kind in ("zvn", "gmzv", "si"):
                lines.append(f"{v}.order = {s.order}u;")
            if s.kind in ("ei", "ei2", "ei3", "si"):
                lines.append(f"{v}.tolerance = {s.tolerance!r};")
            if s.kind in ("gmzv", "si"):
                lines.append(f"{v}.duration = {s.duration!r};  /* damped periods */")
    lines.append(f"/* then: sms_chain_memory_size(cfg_{axis}, {n}, Ts, &need); "
                 f"sms_chain_init(&chain, stages, cfg_{axis}, {n}, Ts, memory, need); */")
    return "\n".join(lines) + "\n"


def c_coeffs(c: Candidate, Ts: float, axis: str) -> str:
    """C source of the recommended chain's precomputed coefficients for ``axis``
    (``coeffs_<axis>[]``, :func:`smoothshaper.coeffs.c_source`): a firmware target builds the
    chain from them with ``sms_chain_init_coeffs``, without designing it.

    Parameters
    ----------
    c : Candidate
        The recommended filter.
    Ts : float
        The target's sample period [s].
    axis : str
        The axis, a C identifier (``_ident`` of its name).

    Returns
    -------
    str
        The C source, headed by what the chain is for.
    """
    from ..coeffs import c_source
    return (f"/* smoothshaper calibrate, axis {axis}: {c.name}, remaining vibration "
            f"{c.vibration:.3g} %, delay {c.length:.4g} s */\n"
            + c_source(list(c.stages), Ts=Ts, name=f"coeffs_{axis}"))


def firmware_picks(cal) -> dict:
    """{axis: firmware.Pick} of every analysed axis (None shaper where nothing the firmware runs
    meets the limits), keyed by the firmware's axis (``x``, ``y``, ``xy``) or, where two
    analyses share one, by the analysis's name."""
    from . import firmware as fw
    picks, seen = {}, {}
    for res in cal.axes:
        seen[res.firmware_axis] = seen.get(res.firmware_axis, 0) + 1
    for res in cal.axes:
        key = res.firmware_axis if seen[res.firmware_axis] == 1 else res.name
        c = res.recommended
        if c is None or c.firmware is None:
            picks[key] = fw.Pick(None, 1.0, 0.0, 0.0)
            continue
        shaper, freq, damping = c.firmware
        A, t = shaper.impulses(freq, damping)
        picks[key] = fw.Pick(shaper, freq, damping, fw.max_accel(A, t))
    return picks


def firmware_config(cal) -> str | None:
    """The firmware's configuration text for every analysed axis, or None with
    ``firmware="none"``."""
    if cal.firmware == "none" or not cal.axes:
        return None
    from . import firmware as fw
    return fw.config_text(cal.firmware, firmware_picks(cal))


def fmu_start_values(c: Candidate, Ts: float) -> dict:
    from ..validation import start_values
    return start_values(c.stages, Ts=Ts)


def axis_json(res, Ts: float) -> dict:
    out = {"axis": res.name, "file": res.record.path, "kind": res.record.kind,
           "signal": res.signal, "band_hz": list(res.band), "resolution_hz": res.resolution,
           "modal_fit_misfit": res.misfit, "modal_fit_explains": res.explains,
           "ranked_by": res.ranked_by, "ranked_by_figure": (
               "vibration_modal" if res.ranked_by == "modal fit" else "vibration_spectrum"),
           "figures": dict(FIGURES), "notes": list(res.notes),
           "default_limit": (None if getattr(res, "default_limit", None) is None
                             else res.default_limit.as_dict()),
           "modes": [m.as_dict() for m in res.modes],
           "candidates": [c.as_dict() for c in res.candidates], "recommended": None}
    if res.record.kind == "raw":
        out["sample_period"] = res.record.Ts
        out["timestamp_jitter"] = res.record.jitter
        out["excluded_fraction"] = res.record.excluded
    if res.fit_r2 is not None:
        out["decay_fit_r2"] = res.fit_r2
    c = res.recommended
    if c is not None:
        out["recommended"] = dict(c.as_dict(), **{
            "c_config": c_config(c, Ts, _ident(res.name)) if c.stages else None,
            "fmu_start_values": fmu_start_values(c, Ts) if c.stages else None})
    return out


def _ident(name: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in name.split(":")[-1])


def to_json(cal) -> dict:
    ref = cal.reference
    doc = {"reference": asdict(ref), "max_delay": cal.max_delay,
           "max_smoothing": cal.max_smoothing,
           "axes": [axis_json(a, ref.Ts) for a in cal.axes], "skipped": cal.skipped,
           "firmware": cal.firmware, "firmware_config": firmware_config(cal)}
    if len(doc["axes"]) == 1:        # one axis: its results at the top level too
        for key in ("modes", "candidates", "recommended"):
            doc[key] = doc["axes"][0][key]
    return doc


def write_json(cal, path: str) -> None:
    """All results as JSON at ``path`` (its folder is created, like the --out folder)."""
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(to_json(cal), fh, indent=1, default=_default)
        fh.write("\n")


def _default(o):
    import numpy as np
    if isinstance(o, np.generic):
        return o.item()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _fmt(v, spec=".3g"):
    if v is None:
        return "-"
    if isinstance(v, float) and math.isinf(v):
        return "unbounded"
    return format(v, spec)


def _candidate_design(c) -> str:
    if c.firmware is not None:
        shaper, freq, damping = c.firmware
        return f"{shaper.firmware} {shaper.name} {freq:.4g} Hz damping {damping:.3g}"
    if len(c.stages) == 1 and c.stages[0].kind == "impulses" and c.design:
        (f, z), = c.design
        return f"{c.name} {f:.4g} Hz damping {z:.3g}: {c.stages[0].order} impulses"
    return "; ".join(_design_text(s) for s in c.stages) or "-"


def range_statement(c) -> str:
    """What a range from the measured spectrum is: the spectrum's bounds (every bin of the
    vibration content a mode anywhere within its half-power width, at any damping of the
    band: not a standard deviation), joined with the modal fit's +-3 sd where a fit was found
    that does not explain the spectrum (the two disagree, and either may hold)."""
    parts = {k: (lo, hi) for k, lo, hi in c.range_parts}
    lo, hi = parts["measured spectrum"]
    text = (f"(the measured spectrum bounds it to {lo:.3g} to {hi:.3g} %: each bin a mode "
            "anywhere within its half-power width, at any damping, a bound and not 3 sd")
    if "modal fit" in parts:
        mlo, mhi = parts["modal fit"]
        text += (f"; joined with the modal fit's +-3 sd, {mlo:.3g} to {mhi:.3g} %, from a fit "
                 "that does not explain the spectrum")
    return text + ")"


#: What each remaining-vibration figure of a candidate is about (the text report's legend and
#: the JSON's ``figures``).
FIGURES = {
    "vibration_spectrum": "measured PSD %: what the filter leaves of the measured PSD (above a "
                          "twentieth of its peak, worst damping: the established tool's estimate)",
    "vibration_modal": "modal plant %: what it leaves of the fitted modal plant (the identified "
                       "modes by their energy)",
    "vibration_estimate": "plant estimate %: the estimate of what the plant is left with, and "
                          "its range (+-3 sd of a modal fit that explains the spectrum, else "
                          "the measured spectrum's bounds)",
}

#: The ranking figure by the objective's kind (``AxisResult.ranked_by``).
RANKED_BY = {"measured spectrum": "what it leaves of the measured PSD",
             "modal fit": "what it leaves of the fitted modal plant"}


def report_text(cal, top: int = 12) -> str:
    """The stdout report: what was analysed, the modes, notes and the ranked candidates per
    axis, with both figures and which one ranked."""
    out = []
    ref = cal.reference
    for res in cal.axes:
        rec = res.record
        head = f"== axis {res.name} ({rec.path}, {rec.kind} record"
        if rec.kind in ("raw", "decay"):
            head += f", {rec.signals.shape[0]} samples at {1 / rec.Ts:.6g} Hz"
            if rec.resampled:
                head += f", time stamps resampled (jitter {100 * rec.jitter:.2g} % of Ts)"
        if res.signal and res.signal != res.name:
            head += f"; analysed: {res.signal}"
        out.append(head + ")")
        fit = ""
        if res.fit_r2 is not None:
            fit = f", decay fit explains {100 * res.fit_r2:.1f} %"
        elif res.misfit is not None and res.modes:
            fit = (f", modal fit misplaces {100 * min(res.misfit, 9.99):.3g} % of the vibration "
                   f"({'explains' if res.explains else 'does not explain'} the spectrum)")
        out.append(f"band {res.band[0]:.4g} to {res.band[1]:.4g} Hz, resolution "
                   f"{res.resolution:.4g} Hz" + fit)
        out.append("modes (+- 1 standard deviation):" if res.modes else
                   "modes: no peak a modal fit confirms (the measured spectrum ranks)")
        total = sum(x.weight for x in res.modes) or 1.0
        for i, m in enumerate(res.modes, 1):
            out.append(f"  {i}: {m.f_hz:.4g} Hz = {m.wn:.5g} +- {m.wn_std:.2g} rad/s, zeta "
                       f"{m.zeta:.4g} +- {m.zeta_std:.2g}, share {100 * m.weight / total:.0f} %"
                       + (" (end of band)" if m.at_edge else ""))
        for note in res.notes:
            out.append(f"note: {note}")
        rows = []
        for c in res.candidates[:top]:
            mark = "*" if c is res.recommended else (" " if c.meets else "x")
            rows.append([mark + c.name, _fmt(c.vibration_spectrum), _fmt(c.vibration_modal),
                         f"{_fmt(c.vibration_estimate)} ({_fmt(c.vibration_range[0])} .. "
                         f"{_fmt(c.vibration_range[1])})",
                         _fmt(c.length, ".4g"), _fmt(c.lag, ".4g"), _fmt(c.smoothing),
                         _fmt(c.peak_accel), _fmt(c.peak_jerk), c.continuity,
                         _candidate_design(c)])
        head = ["candidate", "measured PSD %", "modal plant %", "plant estimate % (range)",
                "delay s", "lag s",
                "smoothing", "peak acc", "peak jerk", "class", "design"]
        widths = [max(len(r[i]) for r in rows + [head]) for i in range(len(head))]
        out.append("  ".join(h.ljust(w) for h, w in zip(head, widths)).rstrip())
        out += ["  ".join(v.ljust(w) for v, w in zip(r, widths)).rstrip() for r in rows]
        limits = []
        if cal.max_delay is not None:
            limits.append(f"delay <= {cal.max_delay:g} s")
        if cal.max_smoothing is not None:
            limits.append(f"smoothing <= {cal.max_smoothing:g}")
        lim = " and ".join(limits) or "no limits"
        if getattr(res, "default_limit", None) is not None:
            lim = (f"delay <= {res.default_limit.max_delay:g} s, the default: the established "
                   f"trade-off's {res.default_limit.shaper} at {res.default_limit.freq:.1f} Hz")
        if res.recommended is None:
            out.append(f"no candidate meets {lim}: relax --max-delay / --max-smoothing")
        else:
            c = res.recommended
            # three figures, each named by what it is about: the two the ranking can use
            # (the measured PSD's, the fitted modal plant's) and the estimate of the plant's
            # remaining vibration the +-3 sd range is about (the measured-PSD figure counts
            # nothing under a twentieth of the peak, so it is often 0 % where the plant keeps
            # several %)
            out.append(f"recommended ({lim}): {c.name}: {_candidate_design(c)}, delay "
                       f"{c.length:.4g} s")
            if res.spectrum is None:             # a free decay: its modes are all there is
                out.append(f"  it leaves of the fitted modal plant {c.vibration_modal:.3g} %; "
                           "ranked by it (a free decay has no PSD)")
            else:
                modal = ("" if c.vibration_modal is None else
                         f", of the fitted modal plant {c.vibration_modal:.3g} %")
                out.append(f"  it leaves of the measured PSD {c.vibration_spectrum:.3g} %{modal};"
                           f" ranked by {RANKED_BY[res.ranked_by]}")
            out.append(f"  estimated remaining vibration of the plant {c.vibration_estimate:.3g} "
                       f"% ({'range' if c.range_parts else '+-3 sd'}: "
                       f"{c.vibration_range[0]:.3g} to {c.vibration_range[1]:.3g} %, "
                       f"from the {c.range_from})")
            if c.range_parts:
                out.append("  " + range_statement(c))
            if c.firmware is None and cal.firmware == "none":
                out.append("  (a smoothshaper filter, for the C library and the FMUs; "
                           "--firmware klipper|marlin|rrf|prusa ranks what that firmware runs)")
        out.append(f"(* recommended, x outside the limits; {FIGURES['vibration_spectrum']}; "
                   f"{FIGURES['vibration_modal']}; {FIGURES['vibration_estimate']}; smoothing "
                   f"and peaks for a move at {ref.accel:g}/s^2, corner velocity "
                   f"{ref.corner_velocity:g}/s, filters at Ts = {ref.Ts:g} s)")
        out.append("")
    for why in cal.skipped:
        out.append(f"skipped: {why}")
    return "\n".join(out) + ("\n" if cal.skipped else "")


def _design_text(s) -> str:
    if s.kind in ("rectangular", "harmonic", "damped_harmonic", "exponential"):
        text = f"{s.kind} T={s.T:.5g} s"
        return text + (f" sigma={s.sigma:.4g}" if s.sigma else "")
    text = f"{s.kind} {s.wn / (2 * math.pi):.4g} Hz ({s.wn:.5g} rad/s) zeta={s.zeta:.3g}"
    if s.kind == "gmzv":
        text += f" n={s.order} D={s.duration:.3g}"
    return text
