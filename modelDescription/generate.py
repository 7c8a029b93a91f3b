#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Generate an FMU's modelDescription.xml, FMI 2.0 and FMI 3.0, and the matching C headers.

One source of truth for every variable: the model tables below, emitted for both FMI versions
(an array variable, such as MultiAxisGenerator's per-axis ones, is one FMI 3.0 array and
`name[i]` scalars in FMI 2.0, with the value references of its elements consecutive). The C
model files include the generated `<Model>_variables.h` (value references, the FMI 2.0 guid,
array sizes), and the FMI 3.0 glue `fmu_fmi3_variables.h` (its instantiation token, the arrays),
so the XML and the C code cannot disagree. Per-stage variables come from a loop, not by hand.

Usage: generate.py MODEL OUT_DIR [SOURCE_FILE...]   (MODEL is SmoothShaper, TrajectoryGenerator,
ElasticPlant, MultiAxisGenerator or ServoDrive). Writes OUT_DIR/modelDescription.xml (FMI 2.0,
listing the source files), OUT_DIR/fmi3/modelDescription.xml, OUT_DIR/<Model>_variables.h and
OUT_DIR/fmu_fmi3_variables.h.
"""
from __future__ import annotations

import hashlib
import math
import sys
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from xml.sax.saxutils import quoteattr

# The licence every FMU states (LICENSE at the repository's root, packaged as
# documentation/licenses/LICENSE.txt).
COPYRIGHT = "Copyright the smoothshaper authors"
LICENSE = ("Apache License 2.0 (SPDX-License-Identifier: Apache-2.0); the full text is in "
           "documentation/licenses/LICENSE.txt")

# FMI 3.0 needs an independent variable: `time`, at a value reference no model uses.
TIME_VR = 2147483647


@dataclass
class Var:
    name: str
    vr: int
    type: str                  # Real or Integer (choices are Integer codes: see CHOICES)
    causality: str             # input, output, parameter
    description: str
    unit: str = ""             # Real only (FMI 2.0 allows units on Real variables only)
    start: object = None
    choices: str = ""          # Integer code list (CHOICES key): min/max and names from it
    variability: str = ""
    min: object = None
    max: object = None
    c_name: str = ""           # macro suffix in the generated header
    initial_depends_on: list = field(default_factory=list)   # outputs: what they are computed
    # from at initialization (the rest point). No output depends on an input within a step (the
    # input set before doStep reaches the outputs only through that step), so <Outputs> lists no
    # direct feedthrough.
    dims: int = 0              # > 0: an array of dims elements at value references vr, vr + 1,
    # ...; its description says "{axis}" where FMI 2.0's element i says "axis i", and a
    # dependency on another array of the same size is element by element.


def fmi2_scalars(variables: list[Var]) -> list[Var]:
    """The variables as FMI 2.0 sees them: every array as its elements name[i]."""
    out = []
    arrays = {v.name for v in variables if v.dims}
    for v in variables:
        if not v.dims:
            out.append(v)
            continue
        for i in range(v.dims):
            deps = [f"{d}[{i}]" if d in arrays else d for d in v.initial_depends_on]
            out.append(Var(f"{v.name}[{i}]", v.vr + i, v.type, v.causality,
                           v.description.format(axis=f"axis {i}"), v.unit, v.start, v.choices,
                           v.variability, v.min, v.max, "", deps))
    return out


UNITS = {  # unit name -> SI base-unit exponents. Signals carry no unit: the filters and the
    # generator work in whatever unit the input has (m, rad, mm, counts).
    "1": {}, "s": {"s": 1}, "1/s": {"s": -1}, "rad/s": {"rad": 1, "s": -1},
    "kg.m2": {"kg": 1, "m": 2}, "N.m/rad": {"kg": 1, "m": 2, "s": -2, "rad": -1},
    "N.m.s/rad": {"kg": 1, "m": 2, "s": -1, "rad": -1},
    "rad": {"rad": 1}, "N.m": {"kg": 1, "m": 2, "s": -2},
}

KINDS = ("rectangular", "harmonic", "damped_harmonic", "exponential", "zv", "zvd", "zvdd", "zvn",
         "ei", "ei2", "mzv", "notch_tustin", "notch_matched", "ei3", "gmzv", "smooth_zv",
         "smooth_mzv", "smooth_ei", "smooth_ei2", "smooth_zvd_ei", "smooth_si", "si",
         "impulses")  # == sms_kind 0..22
KIND_TEXT = ("moving average M", "sinusoidal smoother S",
             "damped sinusoidal smoother S_sigma", "exponential smoother M_sigma",
             "ZV input shaper", "ZVD input shaper", "ZVDD input shaper", "ZV^n input shaper (order n)",
             "extra-insensitive shaper", "two-hump extra-insensitive shaper", "modified ZV shaper",
             "notch, Tustin pre-warped at wn", "notch, pole-zero matched",
             "three-hump extra-insensitive shaper",
             "generalised MZV shaper (order impulses over duration damped periods)",
             "smooth ZV input smoother (zeta in [0, 0.25])",
             "smooth MZV input smoother (zeta in [0, 0.25])",
             "smooth EI input smoother (zeta in [0, 0.25])",
             "smooth two-hump EI input smoother", "smooth ZVD-EI input smoother",
             "smooth SI input smoother",
             "specified-insensitivity shaper (order impulses over duration damped periods)",
             "user-defined impulses (order of them: stage[k].amplitude[i] at stage[k].time[i])")

# SmoothShaper value references: globals below 100, stage k field f at 100 + 16 k + f.
SS_MAX_STAGES = 8
SS_DEFAULT_KINDS = {0: 0, 1: 4}   # stage[0] rectangular, stage[1] zv, the others none
SS_STAGE_BASE = 100
SS_STAGE_STRIDE = 16
SS_FIELDS = (  # (name, type, unit, start, description, choices, min, max)
    ("kind", "Integer", "", -1, "stage family", "StageKind", None, None),
    ("design", "Integer", "", 0, "how T and sigma are chosen", "StageDesign", None, None),
    ("timing", "Integer", "", 0, "how T maps to the sample grid", "Timing", None, None),
    ("T", "Real", "s", 0.01, "duration of a smoother's impulse response (smoothers, design = raw); "
     "finite, >= Ts", "", 0.0, None),
    ("sigma", "Real", "1/s", 0.0, "decay rate of damped harmonic and exponential smoothers "
     "(design = raw); finite, <= 0", "", None, 0.0),
    ("k", "Integer", "", 1, "multiple: which zero exact timing pins (smoothers), T = k * base "
     "period for design = for_mode; >= 1, odd for the harmonic families", "", 1, None),
    ("wn", "Real", "rad/s", 100.0, "natural frequency of the mode (shapers, notches, design = "
     "for_mode); finite, 0 < wn < pi/Ts", "", 0.0, None),
    ("zeta", "Real", "1", 0.0, "damping ratio of the mode (shapers, notch zeros, design = "
     "for_mode); in [0, 1)", "", 0.0, 1.0),
    ("order", "Integer", "", 1, "n of the ZV^n shaper (kind = zvn), 1..8; impulses of the "
     "generalised MZV (kind = gmzv), 3..9, of the SI shaper (kind = si), 3, 5, 7 or 9, and of "
     "the user-defined impulses (kind = impulses), 1..9", "", 1, 9),
    ("tolerance", "Real", "1", 0.05, "vibration tolerance of the EI and SI shapers; in (0, 1)",
     "", 0.0, 1.0),
    ("notch_pole_zeta", "Real", "1", 0.7, "pole damping of the notch; finite, > zeta, <= 1e6", "",
     0.0, 1e6),
    ("duration", "Real", "1", 0.75, "span of the generalised MZV (kind = gmzv) in damped periods; "
     "in (0.5, (order-1)/2) (0.75 with order 3 is MZV); of the SI shaper (kind = si) in "
     "[(order-1)/4, (order-1)/2]", "", 0.0, 4.0),
)

# User-defined impulses (kind = impulses): stage k's impulse i has its amplitude at
# SS_IMPULSE_BASE + SS_IMPULSE_STRIDE k + i and its time SS_MAX_IMPULSES further.
SS_MAX_IMPULSES = 9
SS_IMPULSE_BASE = 1000
SS_IMPULSE_STRIDE = 32

# Stage fields that stay fixed when the others are tunable (the family and how it is designed).
SS_FIXED_FIELDS = ("kind", "design", "timing")
# The scheduled shaper's table: row j at SS_SCHEDULE_BASE + 3 j + (value, wn, zeta).
SS_SCHEDULE_POINTS = 8
SS_SCHEDULE_BASE = 40
SS_SCHEDULE_FIELDS = (  # (name, unit, start(j), description)
    ("value", "", lambda j: float(j), "scheduling value of row {j} (strictly increasing over the "
     "rows in use)"),
    ("wn", "rad/s", lambda j: 100.0, "natural frequency of the mode at row {j}; finite, "
     "0 < wn < pi/Ts"),
    ("zeta", "1", lambda j: 0.0, "damping ratio of the mode at row {j}; in [0, 1)"),
)

# Choices travel as Integer codes (FMI 2.0 Enumerations are not settable in every importer:
# libcosim and FMI Library based hosts ignore them). Each variable's min/max bound the codes and
# its description lists every code with its name.
CHOICES = {
    "StageKind": [("none", -1, "no filter: the stage is skipped")]
                 + [(k, i, t) for i, (k, t) in enumerate(zip(KINDS, KIND_TEXT))],
    "StageDesign": [("raw", 0, "use T, sigma, k as given"),
                    ("for_mode", 1, "design T and sigma for the mode (wn, zeta) with multiple k")],
    "Timing": [("exact", 0, "zeros exactly on the sampled continuous design for any Ts"),
               ("paper", 1, "N = round(T/Ts), as in the source papers"),
               ("bounded", 2, "the exact zero with one more tap, no tap above the continuous "
                              "peak density (rectangular, exponential)")],
    "Interface": [("position", 0, "arrive at target with target_velocity and "
                               "target_acceleration"),
                  ("velocity", 1, "reach target_velocity with target_acceleration, the "
                               "position free"),
                  ("stop", 2, "brake to rest at once")],
    "ScheduleKind": [("none", -1, "no scheduled shaper"), ("zv", 0, "ZV"), ("zvd", 1, "ZVD"),
                     ("zvdd", 2, "ZVDD"), ("zvn", 3, "ZV^n, n = schedule.order")],
    "Profile": [("polynomial", 0, "linear ramps of the acceleration: time-optimal double-S"),
                ("trigonometric", 1, "half-cosine transitions, continuous jerk (modified "
                                     "double-S)"),
                ("damped", 2, "linear ramps through the exponential stage cancelling the "
                              "damped mode wn, zeta (damped-jerk)")],
}


def choice_text(choices: str) -> str:
    """'codes: -1 = none (no filter ...), 0 = rectangular (...), ...' for a description."""
    return "codes: " + ", ".join(f"{v} = {n} ({t})" for n, v, t in CHOICES[choices])


def smooth_shaper() -> tuple[list[Var], list[str], str]:
    vs = [
        Var("u", 0, "Real", "input", "input command (any unit), held over each communication "
            "step; its value at the end of initialization is the rest point", "", 0.0, c_name="U"),
        Var("y", 1, "Real", "output", "filtered command (the unit of u): output of the last "
            "internal tick at k*Ts", "", variability="discrete", c_name="Y",
            initial_depends_on=["u"]),
        Var("Ts", 2, "Real", "parameter", "sample period of the internal ticks; finite, > 0", "s",
            0.001, variability="fixed", min=0.0, c_name="TS"),
        Var("retune_max_delay", 3, "Real", "parameter", "0: the stages are fixed; > 0: their "
            "parameters (all but kind, design and timing) are tunable, applied at the next "
            "communication point, and each stage's memory holds any configuration of its kind "
            "whose impulse response lasts at most this long (docs/retune.md)", "s", 0.0,
            variability="fixed", min=0.0, c_name="RETUNE_MAX_DELAY"),
        Var("s", 4, "Real", "input", "scheduling value of the scheduled shaper (position, load, "
            "...; unit of schedule.value[j]), held over each communication step", "", 0.0,
            c_name="S"),
        Var("lag", 5, "Real", "output", "lag of the filtered command behind u at constant "
            "speed, in seconds: the sum of the active stages' DC group delays (docs/align.md)",
            "", variability="discrete", c_name="LAG", initial_depends_on=["s"]),
        Var("schedule.kind", 6, "Integer", "parameter", "scheduled ZV^n shaper after the "
            "stages, its mode following the input s through the table (docs/scheduled.md); "
            + choice_text("ScheduleKind"), "", -1, "ScheduleKind", "fixed", c_name="SCHED_KIND"),
        Var("schedule.order", 7, "Integer", "parameter", "n of ZV^n for schedule.kind = zvn, "
            "1..8", "", 1, variability="fixed", min=1, max=8, c_name="SCHED_ORDER"),
        Var("schedule.update_every", 8, "Integer", "parameter", "the scheduled shaper's taps are "
            "recomputed every this many ticks (1: every tick)", "", 1, variability="fixed",
            min=1, c_name="SCHED_EVERY"),
        Var("schedule.points", 9, "Integer", "parameter", f"rows of the schedule table in use, "
            f"1..{SS_SCHEDULE_POINTS}", "", 1, variability="fixed", min=1,
            max=SS_SCHEDULE_POINTS, c_name="SCHED_POINTS"),
    ]
    for j in range(SS_SCHEDULE_POINTS):
        for f, (name, unit, start, desc) in enumerate(SS_SCHEDULE_FIELDS):
            lo, hi = {"value": (None, None), "wn": (0.0, None), "zeta": (0.0, 1.0)}[name]
            vs.append(Var(f"schedule.{name}[{j}]", SS_SCHEDULE_BASE + 3 * j + f, "Real",
                          "parameter", desc.format(j=j), unit, start(j), variability="fixed",
                          min=lo, max=hi))
    for k in range(SS_MAX_STAGES):
        for f, (name, typ, unit, start, desc, choices, lo, hi) in enumerate(SS_FIELDS):
            if name == "kind":   # default chain M(T) * ZV(wn): useful out of the box
                start = SS_DEFAULT_KINDS.get(k, -1)
            if choices:
                desc = f"{desc}; {choice_text(choices)}"
            variability = "fixed" if name in SS_FIXED_FIELDS else "tunable"
            if variability == "tunable":
                desc = f"{desc}; tunable when retune_max_delay > 0"
            vs.append(Var(f"stage[{k}].{name}", SS_STAGE_BASE + SS_STAGE_STRIDE * k + f, typ,
                          "parameter", f"stage {k}: {desc}", unit, start, choices, variability,
                          lo, hi))
    for k in range(SS_MAX_STAGES):
        for i in range(SS_MAX_IMPULSES):
            base = SS_IMPULSE_BASE + SS_IMPULSE_STRIDE * k
            vs.append(Var(f"stage[{k}].amplitude[{i}]", base + i, "Real", "parameter",
                          f"stage {k}, kind = impulses: amplitude of impulse {i} (the first "
                          "order of them; of positive sum, normalised to 1; within +-1e300, "
                          "so that the sum of nine stays finite)", "1", 0.0,
                          variability="fixed", min=-1e300, max=1e300))
            vs.append(Var(f"stage[{k}].time[{i}]", base + SS_MAX_IMPULSES + i, "Real",
                          "parameter", f"stage {k}, kind = impulses: time of impulse {i} "
                          "(finite, >= 0, strictly increasing over the first order)", "s", 0.0,
                          variability="fixed", min=0.0))
    header = [f"#define SS_MAX_STAGES {SS_MAX_STAGES}", f"#define SS_STAGE_BASE {SS_STAGE_BASE}",
              f"#define SS_STAGE_STRIDE {SS_STAGE_STRIDE}",
              f"#define SS_MAX_IMPULSES {SS_MAX_IMPULSES}",
              f"#define SS_IMPULSE_BASE {SS_IMPULSE_BASE}",
              f"#define SS_IMPULSE_STRIDE {SS_IMPULSE_STRIDE}"]
    header += [f"#define SS_FIELD_{name.upper()} {f}" for f, (name, *_rest) in enumerate(SS_FIELDS)]
    header.append(f"#define SS_FIELD_COUNT {len(SS_FIELDS)}")
    header += [f"#define SS_SCHEDULE_POINTS {SS_SCHEDULE_POINTS}",
               f"#define SS_SCHEDULE_BASE {SS_SCHEDULE_BASE}"]
    header.append("#define SS_KIND_NONE (-1)")
    header.append(f"#define SS_KIND_COUNT {len(KINDS)}   /* codes 0 .. SS_KIND_COUNT - 1 */")
    header.append("#define SS_DEFAULT_KIND(k) ((k) == 0 ? %d : (k) == 1 ? %d : SS_KIND_NONE)"
                  % (SS_DEFAULT_KINDS[0], SS_DEFAULT_KINDS[1]))
    return vs, header, ("Chain of up to 8 discrete smoothers, input shapers and notches (smoothshaper)")


def trajectory_generator() -> tuple[list[Var], list[str], str]:
    # Position in any unit P (m, mm, rad, ...): the bounds and outputs are in P/s, P/s2, P/s3.
    outs = [("q", "position"), ("v", "velocity (P/s)"), ("a", "acceleration (P/s2)"),
            ("j", "jerk (P/s3)")]
    vs = [Var("target", 0, "Real", "input", "target position in any unit P (piecewise constant "
              "via-points), held over each communication step; a target other than q0 from the "
              "first step on is a move", "", 0.0, c_name="TARGET")]
    for i, (n, text) in enumerate(outs):
        vs.append(Var(n, 1 + i, "Real", "output", f"{text} of the trajectory at the last internal "
                      "tick", "", variability="discrete", c_name=n.upper(),
                      initial_depends_on=["target"]))
    vs += [
        Var("target_velocity", 5, "Real", "input", "velocity (P/s) at arrival on target "
            "(interface position), or the velocity to reach (interface velocity); |.| <= vmax "
            "(0 for a position target of the trigonometric profile)", "", 0.0,
            c_name="TARGET_VELOCITY"),
        Var("target_acceleration", 6, "Real", "input", "acceleration (P/s2) at arrival; "
            "|.| <= amax, and target_velocity -+ a|a|/(2 jmax) within +-vmax (the velocity "
            "where the acceleration was zero on the way in and where it returns to zero after); "
            "0 for the trigonometric profile", "", 0.0, c_name="TARGET_ACCELERATION"),
        Var("interface", 7, "Integer", "input", "what the target asks for; "
            + choice_text("Interface"), "", 0, "Interface", "discrete", c_name="INTERFACE"),
        Var("minimum_duration", 8, "Real", "input", "least duration of the move to this target "
            "(ruckig's minimum_duration), from the tick it is given on: the target is reached "
            "exactly on the first tick at or after both this and the time-optimal duration at "
            "which a motion within the limits exists; 0 = as fast as possible; finite, >= 0 "
            "(0 for the trigonometric profile; ignored for a stop)", "s", 0.0, min=0.0,
            c_name="MINIMUM_DURATION"),
    ]
    vs += [
        Var("Ts", 10, "Real", "parameter", "sample period of the internal ticks; finite, > 0", "s",
            0.001, variability="fixed", min=0.0, c_name="TS"),
        Var("vmax", 11, "Real", "parameter", "velocity bound (P/s); finite, > 0", "", 1.0,
            variability="fixed", min=0.0, c_name="VMAX"),
        Var("amax", 12, "Real", "parameter", "acceleration bound (P/s2); finite, > 0", "", 10.0,
            variability="fixed", min=0.0, c_name="AMAX"),
        Var("jmax", 13, "Real", "parameter", "jerk bound (P/s3); finite, > 0", "", 100.0,
            variability="fixed", min=0.0, c_name="JMAX"),
        Var("profile", 14, "Integer", "parameter", "shape of the acceleration's transitions; "
            + choice_text("Profile"), "", 0, "Profile", "fixed", c_name="PROFILE"),
        Var("wn", 15, "Real", "parameter", "natural frequency of a mode to cancel; 0 = none, else "
            "finite, 0 < wn < pi/Ts", "rad/s", 0.0, variability="fixed", min=0.0, c_name="WN"),
        Var("zeta", 16, "Real", "parameter", "damping ratio of the mode to cancel; in [0, 1)", "1",
            0.0, variability="fixed", min=0.0, max=1.0, c_name="ZETA"),
        Var("q0", 17, "Real", "parameter", "initial position (P): the generator starts at rest "
            "there; finite", "", 0.0, variability="fixed", c_name="Q0"),
        Var("vmin", 18, "Real", "parameter", "lower velocity bound (P/s) for asymmetric limits; "
            "0 = -vmax (symmetric), else finite, < 0 (polynomial and damped profiles)", "", 0.0,
            variability="fixed", max=0.0, c_name="VMIN"),
        Var("amin", 19, "Real", "parameter", "lower acceleration bound (P/s2) for asymmetric "
            "limits; 0 = -amax (symmetric), else finite, < 0 (polynomial and damped profiles)",
            "", 0.0, variability="fixed", max=0.0, c_name="AMIN"),
        Var("qmin", 20, "Real", "parameter", "lower position limit (P); with qmax both 0 = none, "
            "else finite, < qmax (polynomial and damped profiles); targets and q0 inside", "",
            0.0, variability="fixed", c_name="QMIN"),
        Var("qmax", 21, "Real", "parameter", "upper position limit (P); with qmin both 0 = none, "
            "else finite, > qmin: every output q stays in [qmin, qmax]", "", 0.0,
            variability="fixed", c_name="QMAX"),
    ]
    return vs, [], ("Online time-optimal jerk-limited trajectory generator to any target state "
                    "(smoothshaper)")


def elastic_plant() -> tuple[list[Var], list[str], str]:
    # Value references 0..5 in this order: elastic_plant_model.c indexes its fields by them.
    vs = [
        Var("u", 0, "Real", "input", "motor-side position command (any unit), held over each "
            "internal tick (zero-order hold); its value at the end of initialization is the rest "
            "position", "", 0.0, c_name="U"),
        Var("y", 1, "Real", "output", "load position (the unit of u) at the last internal tick",
            "", variability="discrete", c_name="Y", initial_depends_on=["u"]),
        Var("Ts", 2, "Real", "parameter", "sample period of the internal ticks (the hold); "
            "finite, > 0", "s", 0.001, variability="fixed", min=0.0, c_name="TS"),
        Var("J_l", 3, "Real", "parameter", "load inertia; > 0 (default: Table 1 of Biagiotti and "
            "Melchiorri 2012)", "kg.m2", 0.23e-5, variability="fixed", min=0.0, c_name="J_L"),
        Var("k_t", 4, "Real", "parameter", "torsional stiffness of the transmission; > 0",
            "N.m/rad", 0.156, variability="fixed", min=0.0, c_name="K_T"),
        Var("b_t", 5, "Real", "parameter", "internal damping of the transmission; >= 0, "
            "underdamped (b_t < 2 sqrt(k_t J_l))", "N.m.s/rad", 1.0e-5, variability="fixed",
            min=0.0, c_name="B_T"),
    ]
    return vs, [], ("Two-mass elastic transmission: load position of one lightly damped mode, "
                    "exact zero-order-hold discretisation (smoothshaper)")


MA_MAX_AXES = 8   # == SMS_MULTI_MAX_AXES
# MultiAxisGenerator value references: globals below 100, axis i of field f at 100 f + i.
MA_FIELDS = (  # (name, causality, start, description); units: those of axis i (P)
    ("target", "input", 0.0, "target position of {axis} (piecewise constant via-points, any "
     "unit P), held over each communication step"),
    ("q", "output", None, "position of {axis} at the last internal tick"),
    ("v", "output", None, "velocity of {axis} (P/s) at the last internal tick"),
    ("a", "output", None, "acceleration of {axis} (P/s2) at the last internal tick"),
    ("j", "output", None, "jerk of {axis} (P/s3) at the last internal tick (right limit)"),
    ("vmax", "parameter", 1.0, "velocity limit of {axis} (P/s); finite, > 0 (axes in use)"),
    ("amax", "parameter", 10.0, "acceleration limit of {axis} (P/s2); finite, > 0 (axes in use)"),
    ("jmax", "parameter", 100.0, "jerk limit of {axis} (P/s3); finite, > 0 (axes in use)"),
    ("q0", "parameter", 0.0, "initial rest position of {axis} (P)"),
)
# Vibration stages per axis: stage k of axis i is designed for the mode (wn, zeta) of that
# axis (the SmoothShaper FMU's kind codes, design = for_mode with k = 1); value reference
# MA_STAGE_BASE + 100 (MA_STAGE_STRIDE k + g) + i for field g.
MA_MAX_STAGES = 3
MA_STAGE_BASE = 1000
MA_STAGE_FIELDS = (  # (name, type, unit, start, description, choices, min, max)
    ("kind", "Integer", "", -1, "family of vibration stage {k} of {axis}, designed for the "
     "mode (wn, zeta); the same stages on every axis keep straight moves straight", "StageKind",
     None, None),
    ("wn", "Real", "rad/s", 100.0, "natural frequency of the mode stage {k} of {axis} cancels; "
     "finite, 0 < wn < pi/Ts", "", 0.0, None),
    ("zeta", "Real", "1", 0.0, "damping ratio of the mode stage {k} of {axis} cancels; in "
     "[0, 1)", "", 0.0, 1.0),
)
MA_STAGE_STRIDE = len(MA_STAGE_FIELDS)
# Position limits per axis (both 0: none): qmin[i] at MA_QLIM_BASE + i, qmax[i] 100 above.
MA_QLIM_BASE = 2000
MA_QLIM_FIELDS = (
    ("qmin", "lower position limit of {axis} (P); with qmax[i], every sample's q[i] stays in "
     "[qmin[i], qmax[i]] (targets outside fail the step); both 0: none"),
    ("qmax", "upper position limit of {axis} (P), above qmin[i]; both 0: none"),
)
CHOICES["Sync"] = [("phase", 0, "one common profile: straight lines, every axis starts and "
                    "arrives on the same sample, time-optimal under every axis's limits"),
                   ("independent", 1, "each axis time-optimal on its own")]


def multi_axis_generator() -> tuple[list[Var], list[str], str]:
    vs = [
        Var("Ts", 1, "Real", "parameter", "sample period of the internal ticks; finite, > 0", "s",
            0.001, variability="fixed", min=0.0, c_name="TS"),
        Var("axes", 2, "Integer", "parameter", f"number of axes in use, 1..{MA_MAX_AXES} (the "
            "variables of the other axes are ignored)", "", 3, variability="fixed", min=1,
            max=MA_MAX_AXES, c_name="AXES"),
        Var("sync", 3, "Integer", "parameter", "coordination of the axes; " + choice_text("Sync"),
            "", 0, "Sync", "fixed", c_name="SYNC"),
        Var("align", 4, "Integer", "parameter", "1: pad every axis with a delay to the common lag "
            "of the axes' stages, so straight moves stay on the line at constant speed whatever "
            "stages the axes carry; 0: off", "", 0, variability="fixed", min=0, max=1,
            c_name="ALIGN"),
        Var("lag", 5, "Real", "output", "lag of the outputs behind the profile, in seconds: with "
            "align = 1 every axis's, else the largest axis's (fixed at initialisation; 0 without "
            "stages)", "", variability="discrete", c_name="LAG", initial_depends_on=["q0[0]"]),
    ]
    for f, (name, causality, start, desc) in enumerate(MA_FIELDS, 1):
        extra = {}
        if causality == "parameter":
            extra = dict(variability="fixed")
            if name != "q0":
                extra["min"] = 0.0
        if causality == "output":
            extra = dict(variability="discrete", initial_depends_on=["q0"])
        vs.append(Var(name, 100 * f, "Real", causality, desc, "", start, dims=MA_MAX_AXES,
                      **extra))
    for k in range(MA_MAX_STAGES):
        for g, (name, typ, unit, start, desc, choices, lo, hi) in enumerate(MA_STAGE_FIELDS):
            if choices:
                desc = f"{desc}; {choice_text(choices)}"
            vs.append(Var(f"stage[{k}].{name}", MA_STAGE_BASE + 100 * (MA_STAGE_STRIDE * k + g),
                          typ, "parameter", desc.replace("{k}", str(k)), unit, start, choices,
                          "fixed", lo, hi, dims=MA_MAX_AXES))
    for g, (name, desc) in enumerate(MA_QLIM_FIELDS):
        vs.append(Var(name, MA_QLIM_BASE + 100 * g, "Real", "parameter", desc, "", 0.0,
                      variability="fixed", dims=MA_MAX_AXES))
    header = [f"#define MA_MAX_AXES {MA_MAX_AXES}", f"#define MA_MAX_STAGES {MA_MAX_STAGES}",
              f"#define MA_QLIM_BASE {MA_QLIM_BASE}",
              f"#define MA_STAGE_BASE {MA_STAGE_BASE}",
              f"#define MA_STAGE_STRIDE {MA_STAGE_STRIDE}"]
    header += [f"#define MA_STAGE_{name.upper()} {g}"
               for g, (name, *_rest) in enumerate(MA_STAGE_FIELDS)]
    header += [f"#define MA_VR_{name.upper()}(i) ({100 * f} + (i))"
               for f, (name, *_rest) in enumerate(MA_FIELDS, 1)]
    header.append(f"#define MA_FIELD_COUNT {len(MA_FIELDS)}")
    return vs, header, ("Online multi-axis jerk-limited generator, phase-synchronised or "
                        "independent axes (smoothshaper)")


# ServoDrive: the servomechanism of Bascetta's motion-control notes in closed loop (the Python
# testbed smoothshaper.servo, whose defaults these are: servo.NOTES and servo.presets).
SV_NOTES = {"Jm": 0.00015, "Jl": 2.7, "n": 100.0, "Dm": 0.0034, "Kel": 3.1, "Del": 0.0022}
SV_TS = 5e-4
SV_WZ = math.sqrt(SV_NOTES["Kel"] * SV_NOTES["n"] ** 2 / SV_NOTES["Jl"])   # presets.pid's rule
CHOICES["Controller"] = [
    ("pid", 0, "P position loop, PI velocity loop with velocity feed-forward (pid.*, notch.*)"),
    ("pid_tdo", 1, "the same with a torque disturbance observer on the motor (tdo.*)"),
    ("pole_placement", 2, "observer-based pole placement with integral action and the "
                          "reference model's feed-forward (place.*, observer.*, wf)"),
    ("lqg", 3, "LQ state feedback with integral action and a steady-state Kalman predictor "
               "(lq.*, kalman.*, wf)")]
CHOICES["NotchAt"] = [("none", 0, "no notch"),
                      ("loop", 1, "on the velocity PI's output (the torque)"),
                      ("reference", 2, "on the velocity reference")]
CHOICES["NotchDiscretization"] = [("matched", 0, "pole-zero matched"),
                                  ("tustin", 1, "Tustin pre-warped at notch.wn")]


def _pole(value: complex) -> tuple[float, float]:
    """(wn, zeta) of a continuous pole."""
    return abs(value), -value.real / abs(value)


def servo_drive() -> tuple[list[Var], list[str], str]:
    """The variables in value-reference order; servo_drive_model.c reads them through the
    SV_VARIABLES table of the generated header (its struct fields are the lower-case c_names)."""
    pp = [_pole(complex(-105, 105)), _pole(complex(-175, 175))]   # presets.PP_POLES
    obs = _pole(complex(-420, 420))                                # presets.PP_OBSERVER
    def par(name, vr, desc, unit, start, c_name, lo=0.0, hi=None, typ="Real", choices=""):
        return Var(name, vr, typ, "parameter", desc, unit, start, choices, "fixed", lo, hi,
                   c_name)

    def out(name, vr, desc, unit, c_name):
        return Var(name, vr, "Real", "output", desc, unit, variability="discrete",
                   c_name=c_name, initial_depends_on=["q_ref", "tau_load"])

    vs = [
        Var("q_ref", 0, "Real", "input", "load position reference (load side), held over each "
            "internal tick; its value at the end of initialization is the rest position", "rad",
            0.0, c_name="Q_REF"),
        Var("tau_load", 1, "Real", "input", "load torque disturbance (on the load side, opposing "
            "motion), held over each internal tick", "N.m", 0.0, c_name="TAU_LOAD"),
        out("q_m", 2, "motor position at the last internal tick", "rad", "Q_M"),
        out("w_m", 3, "motor velocity at the last internal tick", "rad/s", "W_M"),
        out("q_l", 4, "load position at the last internal tick", "rad", "Q_L"),
        out("w_l", 5, "load velocity at the last internal tick", "rad/s", "W_L"),
        out("tau_m", 6, "motor torque held over the last internal tick", "N.m", "TAU_M"),
        par("Ts", 10, "sample period of the drive (controller and zero-order hold); finite, > 0",
            "s", SV_TS, "TS"),
        par("controller", 11, "the control law; " + choice_text("Controller"), "", 0,
            "CONTROLLER", None, None, "Integer", "Controller"),
        par("Jm", 12, "motor inertia; > 0", "kg.m2", SV_NOTES["Jm"], "JM"),
        par("Jl", 13, "load inertia; > 0", "kg.m2", SV_NOTES["Jl"], "JL"),
        par("n", 14, "transmission ratio (motor turns per load turn); > 0", "1", SV_NOTES["n"],
            "N"),
        par("Dm", 15, "motor viscous friction; >= 0", "N.m.s/rad", SV_NOTES["Dm"], "DM"),
        par("Kel", 16, "transmission stiffness (motor side); > 0", "N.m/rad", SV_NOTES["Kel"],
            "KEL"),
        par("Del", 17, "transmission damping (motor side); >= 0", "N.m.s/rad", SV_NOTES["Del"],
            "DEL"),
        par("pid.wcv", 20, "velocity loop crossover: K_pv = J wcv; finite, > pid.wcp", "rad/s",
            SV_WZ, "PID_WCV"),
        par("pid.Ti", 21, "velocity loop integral time; finite, > 0", "s", 10.0 / SV_WZ,
            "PID_TI"),
        par("pid.wcp", 22, "position loop crossover: K_pp = wcp; finite, > 0", "rad/s",
            0.1 * SV_WZ, "PID_WCP"),
        par("pid.J", 23, "inertia the velocity gain is sized for; 0 = the rule: Jm + Jl/n^2, or "
            "Jm behind the TDO", "kg.m2", 0.0, "PID_J"),
        par("tdo.Tf", 24, "time constant of the TDO's filter Q(s) = 1/(1 + s Tf); finite, > 0",
            "s", 2 * SV_TS, "TDO_TF"),
        par("tdo.Jn", 25, "nominal inertia of the TDO's motor model 1/(Jn s + Dn); > 0", "kg.m2",
            SV_NOTES["Jm"], "TDO_JN"),
        par("tdo.Dn", 26, "nominal friction of the TDO's motor model; >= 0", "N.m.s/rad",
            SV_NOTES["Dm"], "TDO_DN"),
        par("notch.at", 27, "where the P/PI cascade's notch sits; " + choice_text("NotchAt"), "",
            0, "NOTCH_AT", None, None, "Integer", "NotchAt"),
        par("notch.discretization", 28, "the notch's discretisation; "
            + choice_text("NotchDiscretization"), "", 0, "NOTCH_DISCRETIZATION", None, None,
            "Integer", "NotchDiscretization"),
        par("notch.wn", 29, "centre of the notch (default: the resonance of the default plant); "
            "finite, 0 < wn < pi/Ts", "rad/s", 179.0, "NOTCH_WN"),
        par("notch.zeta", 30, "damping of the notch's zeros; in [0, 1)", "1", 0.104,
            "NOTCH_ZETA", 0.0, 1.0),
        par("notch.pole_zeta", 31, "damping of the notch's poles; > notch.zeta, <= 1e6", "1", 0.7,
            "NOTCH_POLE_ZETA", 0.0, 1e6),
    ]
    for k, (wn, zeta) in enumerate(pp):
        vs += [par(f"place.wn[{k}]", 32 + 2 * k, f"natural frequency of the closed loop's pole "
                   f"pair {k}; finite, > 0", "rad/s", wn, f"PLACE_WN{k}"),
               par(f"place.zeta[{k}]", 33 + 2 * k, f"damping ratio of the closed loop's pole "
                   f"pair {k}; in (0, 1)", "1", zeta, f"PLACE_ZETA{k}", 0.0, 1.0)]
    vs += [
        par("place.real", 36, "the closed loop's real pole is at -place.real; finite, > 0",
            "1/s", 30.0, "PLACE_REAL"),
        par("observer.wn", 37, "natural frequency of the observer's pole pair; finite, > 0",
            "rad/s", obs[0], "OBSERVER_WN"),
        par("observer.zeta", 38, "damping ratio of the observer's pole pair; in (0, 1)", "1",
            obs[1], "OBSERVER_ZETA", 0.0, 1.0),
        par("observer.real[0]", 39, "an observer pole at -observer.real[0]; finite, > 0", "1/s",
            800.0, "OBSERVER_REAL0"),
        par("observer.real[1]", 40, "an observer pole at -observer.real[1]; finite, > 0", "1/s",
            1000.0, "OBSERVER_REAL1"),
    ]
    lq_q = (1e2, 0.0, 1e4, 0.0, 1e7)   # presets.LQ_Q (Bryson's rule)
    state = ("q_m", "q_m'", "n q_l", "n q_l'", "the integrated motor error x_I")
    vs += [par(f"lq.Q[{i}]", 41 + i, f"LQ weight of {state[i]} in sum (z' Q z + R u^2) Ts; "
               "finite, >= 0", "", q, f"LQ_Q{i}") for i, q in enumerate(lq_q)]
    vs += [
        par("lq.R", 46, "LQ weight of the motor torque; finite, > 0", "", 1.0, "LQ_R"),
        par("kalman.torque_noise", 47, "standard deviation of the motor torque noise the Kalman "
            "predictor assumes; >= 0", "N.m", 0.01, "KALMAN_TORQUE_NOISE"),
        par("kalman.load_torque_noise", 48, "standard deviation of the load torque noise (load "
            "side); >= 0, not both 0", "N.m", 10.0, "KALMAN_LOAD_TORQUE_NOISE"),
        par("kalman.encoder_noise", 49, "standard deviation of the encoder noise (default: the "
            "quantisation of 20 bits); finite, > 0", "rad", 2.0 * math.pi / 2 ** 20
            / math.sqrt(12.0), "KALMAN_ENCODER_NOISE"),
        par("wf", 50, "bandwidth of the reference model wf^3/(s + wf)^3 behind the state "
            "feedback's feed-forward; 0 = none (the integrator tracks q_ref)", "rad/s", 60.0,
            "WF"),
    ]
    rows = [f'    X({v.vr}, "{v.name}", {v.c_name.lower()}, '
            f"{'INTEGER' if v.type == 'Integer' else 'REAL'}, {v.causality.upper()}, "
            f"{_fmt(v.start if v.start is not None else 0.0)})" for v in vs]
    header = ["/* X(vr, name, struct field, type, class, start) for every variable, vr order */",
              "#define SV_VARIABLES(X) \\", " \\\n".join(rows),
              f"#define SV_VR_END {vs[-1].vr + 1}   /* every value reference is below */"]
    return vs, header, ("Servo drive in closed loop: elastic motor-transmission-load plant "
                        "under P/PI, TDO, pole-placement or LQG control (smoothshaper)")



MODELS = {"SmoothShaper": smooth_shaper, "TrajectoryGenerator": trajectory_generator,
          "ElasticPlant": elastic_plant, "MultiAxisGenerator": multi_axis_generator,
          "ServoDrive": servo_drive}
PREFIXES = {"SmoothShaper": "SS", "TrajectoryGenerator": "TG", "ElasticPlant": "EP",
            "MultiAxisGenerator": "MA", "ServoDrive": "SV"}


def _fmt(v) -> str:
    if isinstance(v, float):
        return repr(v)
    return str(v)


def unit_definitions(variables: list[Var]) -> list[str]:
    out = ['  <UnitDefinitions>']
    for u in sorted({v.unit for v in variables if v.unit}):
        exps = " ".join(f'{k}="{e}"' for k, e in UNITS[u].items())
        out.append(f'    <Unit name="{u}"><BaseUnit {exps}/></Unit>' if exps else f'    <Unit name="{u}"/>')
    out += ['  </UnitDefinitions>', '  <LogCategories>']
    out += [f'    <Category name="{n}" description={quoteattr(d)}/>' for n, d in LOG_CATEGORIES]
    out += ['  </LogCategories>', '  <DefaultExperiment startTime="0" stopTime="1" stepSize="0.001"/>']
    return out


def header_attributes(model: str, description: str) -> list[str]:
    return [f'  description={quoteattr(description)}',
            '  generationTool="smoothshaper modelDescription/generate.py" author="smoothshaper"',
            f'  copyright={quoteattr(COPYRIGHT)} license={quoteattr(LICENSE)}']


def bounds(v: Var) -> tuple[object, object]:
    """min and max: an Integer code's from its list."""
    if v.choices:
        codes = [c[1] for c in CHOICES[v.choices]]
        return min(codes), max(codes)
    return v.min, v.max


def model_description(model: str, variables: list[Var], description: str, guid: str) -> str:
    """FMI 2.0: every array as its scalar elements."""
    variables = fmi2_scalars(variables)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<fmiModelDescription fmiVersion="2.0" modelName="{model}" guid="{guid}"']
    out += header_attributes(model, description)
    out += ['  version="0.1.0" variableNamingConvention="structured" numberOfEventIndicators="0">',
           f'  <CoSimulation modelIdentifier="{model}" canHandleVariableCommunicationStepSize="true"',
           '    canInterpolateInputs="false" maxOutputDerivativeOrder="0" canRunAsynchronuously="false"',
           '    canBeInstantiatedOnlyOncePerProcess="false" canNotUseMemoryManagementFunctions="false"',
           '    canGetAndSetFMUstate="true" canSerializeFMUstate="true"',
           '    providesDirectionalDerivative="false">',
           '    <SourceFiles>']
    out += [f'      <File name="{f}"/>' for f in SOURCE_FILES_PLACEHOLDER]
    out += ['    </SourceFiles>', '  </CoSimulation>']
    out += unit_definitions(variables)
    out += ['  <ModelVariables>']
    for i, v in enumerate(variables, 1):
        attrs = f'name="{v.name}" valueReference="{v.vr}" causality="{v.causality}"'
        if v.variability:
            attrs += f' variability="{v.variability}"'
        if v.causality == "parameter":
            attrs += ' initial="exact"'
        if v.causality == "output":
            attrs += ' initial="calculated"'
        attrs += f' description={quoteattr(v.description)}'
        inner = ""
        lo, hi = bounds(v)
        if v.unit:
            inner += f' unit="{v.unit}"'
        if lo is not None:
            inner += f' min="{_fmt(lo)}"'
        if hi is not None:
            inner += f' max="{_fmt(hi)}"'
        if v.start is not None:
            inner += f' start="{_fmt(v.start)}"'
        out.append(f'    <!-- index {i} -->')
        out.append(f'    <ScalarVariable {attrs}>')
        out.append(f'      <{v.type}{inner}/>')
        out.append('    </ScalarVariable>')
    index = {v.name: i for i, v in enumerate(variables, 1)}
    out += ['  </ModelVariables>', '  <ModelStructure>', '    <Outputs>']
    outputs = [v for v in variables if v.causality == "output"]
    for v in outputs:   # no direct feedthrough: an input reaches the outputs only via doStep
        out.append(f'      <Unknown index="{index[v.name]}" dependencies=""/>')
    out += ['    </Outputs>', '    <InitialUnknowns>']
    for v in outputs:
        deps = " ".join(str(index[d]) for d in v.initial_depends_on)
        out.append(f'      <Unknown index="{index[v.name]}" dependencies="{deps}"/>')
    out += ['    </InitialUnknowns>', '  </ModelStructure>', '</fmiModelDescription>', '']
    return "\n".join(out)


FMI3_TYPES = {"Real": "Float64", "Integer": "Int32"}


def model_description_fmi3(model: str, variables: list[Var], description: str,
                           token: str) -> str:
    """FMI 3.0: arrays as arrays (a Dimension of fixed size), Integer codes as Int32 with
    min/max, the independent variable `time`, fixedInternalStepSize = Ts's start value."""
    ts = next((v.start for v in variables if v.name == "Ts"), 0.001)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<fmiModelDescription fmiVersion="3.0" modelName="{model}"',
           f'  instantiationToken="{token}"']
    out += header_attributes(model, description)
    out += ['  version="0.1.0" variableNamingConvention="structured">',
            f'  <CoSimulation modelIdentifier="{model}" canHandleVariableCommunicationStepSize="true"',
            f'    fixedInternalStepSize="{_fmt(ts)}" hasEventMode="false"',
            '    canBeInstantiatedOnlyOncePerProcess="false" canGetAndSetFMUState="true"',
            '    canSerializeFMUState="true" providesDirectionalDerivatives="false"',
            '    providesAdjointDerivatives="false" providesIntermediateUpdate="false"',
            '    canReturnEarlyAfterIntermediateUpdate="false"/>']
    out += unit_definitions(variables)
    out += ['  <ModelVariables>',
            f'    <Float64 name="time" valueReference="{TIME_VR}" causality="independent" '
            'variability="continuous" description="simulation time (the communication point '
            'reached)"/>']
    for v in variables:
        typ = FMI3_TYPES[v.type]
        attrs = f'name="{v.name}" valueReference="{v.vr}" causality="{v.causality}"'
        if v.variability:
            attrs += f' variability="{v.variability}"'
        if v.causality == "parameter":
            attrs += ' initial="exact"'
        if v.causality == "output":
            attrs += ' initial="calculated"'
        description_text = v.description.format(axis="each axis") if v.dims else v.description
        attrs += f' description={quoteattr(description_text)}'
        lo, hi = bounds(v)
        if v.unit:
            attrs += f' unit="{v.unit}"'
        if lo is not None:
            attrs += f' min="{_fmt(lo)}"'
        if hi is not None:
            attrs += f' max="{_fmt(hi)}"'
        if v.start is not None:
            attrs += f' start="{" ".join([_fmt(v.start)] * max(v.dims, 1))}"'
        if v.dims:
            out.append(f'    <{typ} {attrs}>')
            out.append(f'      <Dimension start="{v.dims}"/>')
            out.append(f'    </{typ}>')
        else:
            out.append(f'    <{typ} {attrs}/>')
    vr = {v.name: v.vr for v in variables}
    outputs = [v for v in variables if v.causality == "output"]
    out += ['  </ModelVariables>', '  <ModelStructure>']
    for v in outputs:   # no direct feedthrough: an input reaches the outputs only via doStep
        out.append(f'    <Output valueReference="{v.vr}" dependencies=""/>')
    for v in outputs:   # an element name[i] of FMI 2.0 is the array `name` here
        deps = " ".join(str(vr[d] if d in vr else vr[d.split("[")[0]])
                        for d in v.initial_depends_on)
        out.append(f'    <InitialUnknown valueReference="{v.vr}" dependencies="{deps}"/>')
    out += ['  </ModelStructure>', '</fmiModelDescription>', '']
    return "\n".join(out)


def fmi3_header(model: str, variables: list[Var], token: str) -> str:
    """fmu_fmi3_variables.h: what the FMI 3.0 glue needs beyond the model's own header."""
    arrays = [v for v in variables if v.dims]
    lines = [f"/* Generated by modelDescription/generate.py for {model} (FMI 3.0): do not edit. */",
             "#ifndef FMU_FMI3_VARIABLES_H", "#define FMU_FMI3_VARIABLES_H", "",
             f'#define FMU_FMI3_TOKEN "{token}"',
             f"#define FMU_FMI3_TIME_VR {TIME_VR}u   /* the independent variable time */",
             "/* The array variables: value reference of the first element, element count (the",
             " * elements' value references follow it one by one). */",
             f"#define FMU_FMI3_ARRAY_COUNT {len(arrays)}"]
    table = ", ".join(f"{{{v.vr}u, {v.dims}u}}" for v in arrays)
    lines.append(f"#define FMU_FMI3_ARRAYS {{{table}}}" if arrays
                 else "#define FMU_FMI3_ARRAYS {{0u, 0u}}")
    lines += ["", "#endif", ""]
    return "\n".join(lines)


LOG_CATEGORIES = (("logStatusError", "errors: wrong call order, bad arguments, invalid "
                   "parameters (always sent to the logger)"),
                  ("logStatusWarning", "warnings (always sent to the logger)"),
                  ("logCalls", "a trace of every FMI function call"))
SOURCE_FILES_PLACEHOLDER: list[str] = []


def c_header(model: str, variables: list[Var], extra: list[str], guid: str) -> str:
    guard = f"FMU_{model.upper()}_VARIABLES_H"
    lines = [f"/* Generated by modelDescription/generate.py for {model}: do not edit. */",
             f"#ifndef {guard}", f"#define {guard}", "",
             f'#define FMU_MODEL_IDENTIFIER "{model}"', f'#define FMU_MODEL_GUID "{guid}"']
    prefix = PREFIXES[model]
    for v in variables:
        if v.c_name:
            lines.append(f"#define {prefix}_VR_{v.c_name} {v.vr}")
    lines += extra
    lines += ["", f"#endif /* {guard} */", ""]
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    if len(argv) < 3 or argv[1] not in MODELS:
        print(__doc__, file=sys.stderr)
        return 2
    model, out_dir = argv[1], Path(argv[2])
    SOURCE_FILES_PLACEHOLDER[:] = argv[3:]   # source files listed in <SourceFiles>
    variables, extra, description = MODELS[model]()
    # A token is a hash of everything but itself: any change of the interface changes it.
    draft = model_description(model, variables, description, "{GUID}")
    guid = "{" + str(uuid.UUID(hashlib.sha256(draft.encode()).hexdigest()[:32])) + "}"
    draft3 = model_description_fmi3(model, variables, description, "{TOKEN}")
    token = "{" + str(uuid.UUID(hashlib.sha256(draft3.encode()).hexdigest()[:32])) + "}"
    (out_dir / "fmi3").mkdir(parents=True, exist_ok=True)
    (out_dir / "modelDescription.xml").write_text(model_description(model, variables,
                                                                    description, guid))
    (out_dir / "fmi3" / "modelDescription.xml").write_text(
        model_description_fmi3(model, variables, description, token))
    (out_dir / f"{model}_variables.h").write_text(c_header(model, variables, extra, guid))
    (out_dir / "fmu_fmi3_variables.h").write_text(fmi3_header(model, variables, token))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
