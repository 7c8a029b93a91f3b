# SPDX-License-Identifier: Apache-2.0
"""Input shapers exactly as 3-D printer firmware defines them: each function is one firmware's
formula, re-derived from its source (project, file and commit below), returning the impulse
amplitudes and times [s] before normalisation. :mod:`.firmware` wraps them.

Sources (read at these commits):

* Klipper: Klipper3d/klipper ``klippy/extras/shaper_defs.py`` (last changed in 19da135,
  2026-03-22; read at 84104bb, 2026-08-07), limits from ``input_shaper.py`` and
  ``shaper_calibrate.py`` at the same commit. The EI family is the one Klipper has used since
  its 2025-09-16 change (``docs/Config_Changes.md``): fitted polynomials in the damping ratio,
  not the closed forms of the papers.
* Marlin: MarlinFirmware/Marlin ``Marlin/src/module/ft_motion/shaping.cpp`` (fixed-time motion,
  ``M493``; FT Motion version 2 of Marlin 2.1.3) and ``Marlin/src/module/stepper.cpp``
  ``Stepper::set_shaping_damping_ratio`` / ``set_shaping_frequency`` (classic input shaping,
  ``M593``, ZV only), bugfix-2.1.x of 2025.
* RepRapFirmware: Duet3D/RepRapFirmware ``src/Movement/AxisShaper.cpp`` (branch 3.6-dev, file
  last changed in a75f911, 2024-07-20; read at 8875b7e, 2024-10-24).
* Prusa: prusa3d/Prusa-Firmware-Buddy ``lib/Marlin/Marlin/src/feature/input_shaper/
  input_shaper.cpp`` and ``input_shaper_config.hpp`` (master at 818d812, 2025-03-28): Klipper's
  definitions of before its 2025 EI change, with a vibration reduction of 20 (tolerance 5 %).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["KLIPPER", "MARLIN", "RRF", "PRUSA", "MARLIN_FTM_FS", "RRF_STEP_CLOCK",
           "EI_TOLERANCE", "rrf_custom"]

#: Vibration tolerance of every firmware's EI family (Klipper SHAPER_VIBRATION_REDUCTION = 20,
#: Marlin FTM_SHAPING_V_TOL = 0.05, Prusa vibration_reduction = 20).
EI_TOLERANCE = 0.05
#: Marlin FT Motion's trajectory rate FTM_FS [Hz] (Configuration_adv.h default): its impulse
#: times are whole periods of it.
MARLIN_FTM_FS = 1000.0
#: RepRapFirmware's step clock on Duet 3 boards (48 MHz / 64) [Hz]: its delays are whole clocks.
RRF_STEP_CLOCK = 750000.0
#: Just below 1: the largest damping ratio a firmware that divides by sqrt(1 - zeta^2) can use.
BELOW_ONE = math.nextafter(1.0, 0.0)


def _damped(f, zeta):
    """(sqrt(1 - zeta^2), exp(-zeta pi / sqrt(1 - zeta^2)), damped period 1 / (f df))."""
    df = math.sqrt(1.0 - zeta * zeta)
    return df, math.exp(-zeta * math.pi / df), 1.0 / (f * df)


def _binomial(K, n):
    """(1 + K)^n expanded: the ZV^n amplitudes [C(n, i) K^i]."""
    return [math.comb(n, i) * K ** i for i in range(n + 1)]


# ---------------------------------------------------------------- Klipper (shaper_defs.py)
def klipper_zv(f, zeta):
    _, K, td = _damped(f, zeta)
    return [1.0, K], [0.0, 0.5 * td]


def klipper_zvd(f, zeta):
    _, K, td = _damped(f, zeta)
    return [1.0, 2.0 * K, K * K], [0.0, 0.5 * td, td]


def klipper_mzv(f, zeta):
    # get_mzv_shaper(n=3, t=0.75): get_mzv_coeffs(3, 0.75) solves to [1 - 1/sqrt2, sqrt2 - 1,
    # 1 - 1/sqrt2], damped by K = exp(-2 t zeta pi / ((n - 1) df)) per impulse
    df = math.sqrt(1.0 - zeta * zeta)
    K = math.exp(-0.75 * zeta * math.pi / df)
    td = 1.0 / (f * df)
    a1 = 1.0 - 1.0 / math.sqrt(2.0)
    return [a1, (math.sqrt(2.0) - 1.0) * K, a1 * K * K], [0.0, 0.375 * td, 0.75 * td]


def klipper_gmzv(n, t):
    """get_mzv_shaper(n, t): n impulses over t damped periods, amplitudes the least-squares
    solution (get_mzv_coeffs: sum A = 1 and zeros at 1 + i/tau, i < n - 1,
    tau = t (n - 2)/(n - 2t - 1)), impulse j damped by K^j with K = exp(-2 t zeta pi/((n-1) df));
    ValueError where Klipper raises ShaperError (n < 3, t >= (n-1)/2, a negative amplitude)."""
    if n < 3:
        raise ValueError(f"n must be at least 3, got {n}")
    if n <= 2 * t + 1 + 1e-7:
        raise ValueError(f"t must be less than {0.5 * (n - 1):g} for n = {n}, got {t:g}")
    tau = t * (n - 2.0) / (n - 2.0 * t - 1.0)
    T = [i * t / (n - 1.0) for i in range(n)]
    rows, rhs = [[1.0] * n], [1.0]
    for i in range(n - 1):
        w = [2.0 * math.pi * (1.0 + i / tau) * tj for tj in T]
        rows += [[math.cos(x) for x in w], [math.sin(x) for x in w]]
        rhs += [0.0, 0.0]
    A0 = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0].tolist()
    if any(a < -0.00001 for a in A0):
        raise ValueError(f"mzv(n={n}, t={t:g}) has a negative amplitude")

    def gmzv(f, zeta):
        df = math.sqrt(1.0 - zeta * zeta)
        K = math.exp(-2.0 * t * zeta * math.pi / ((n - 1.0) * df))
        td = 1.0 / (f * df)
        return [a * K ** j for j, a in enumerate(A0)], [x * td for x in T]
    return gmzv


def klipper_ei(f, zeta, v=EI_TOLERANCE):
    # get_ei_shaper: amplitudes and middle time fitted in zeta and v_tol; the ends at 0 and td
    td = 1.0 / (f * math.sqrt(1.0 - zeta * zeta))
    a1 = (0.24968 + 0.24961 * v) + ((0.80008 + 1.23328 * v)
                                   + (0.49599 + 3.17316 * v) * zeta) * zeta
    a3 = (0.25149 + 0.21474 * v) + ((-0.83249 + 1.41498 * v)
                                   + (0.85181 - 4.90094 * v) * zeta) * zeta
    t2 = 0.4999 + (((0.46159 + 8.57843 * v) * v)
                   + (((4.26169 - 108.644 * v) * v)
                      + ((1.75601 + 336.989 * v) * v) * zeta) * zeta) * zeta
    return [a1, 1.0 - a1 - a3, a3], [0.0, t2 * td, td]


def _cubic(c, zeta):
    return c[0] + zeta * (c[1] + zeta * (c[2] + zeta * c[3]))


# Expansion coefficients (constant, zeta, zeta^2, zeta^3) of each impulse's time (in periods of
# the undamped frequency 1/f) and amplitude: Klipper's get_2hump_ei_shaper / get_3hump_ei_shaper
# (the same numbers as RepRapFirmware's ei2 / ei3, which multiply the damped period instead)
EI2_T = ((0.0, 0.0, 0.0, 0.0), (0.49890, 0.16270, -0.54262, 6.16180),
         (0.99748, 0.18382, -1.58270, 8.17120), (1.49920, -0.09297, -0.28338, 1.85710))
EI2_A = ((0.16054, 0.76699, 2.26560, -1.22750), (0.33911, 0.45081, -2.58080, 1.73650),
         (0.34089, -0.61533, -0.68765, 0.42261), (0.15997, -0.60246, 1.00280, -0.93145))
EI3_T = ((0.0, 0.0, 0.0, 0.0), (0.49974, 0.23834, 0.44559, 12.4720),
         (0.99849, 0.29808, -2.36460, 23.3990), (1.49870, 0.10306, -2.01390, 17.0320),
         (1.99960, -0.28231, 0.61536, 5.40450))
EI3_A = ((0.11275, 0.76632, 3.29160, -1.44380), (0.23698, 0.61164, -2.57850, 4.85220),
         (0.30008, -0.19062, -2.14560, 0.13744), (0.23775, -0.73297, 0.46885, -2.08650),
         (0.11244, -0.45439, 0.96382, -1.46000))


def _klipper_expansion(f, zeta, tcoef, acoef):
    return [_cubic(c, zeta) for c in acoef], [_cubic(c, zeta) / f for c in tcoef]


def klipper_2hump_ei(f, zeta):
    return _klipper_expansion(f, zeta, EI2_T, EI2_A)


def klipper_3hump_ei(f, zeta):
    return _klipper_expansion(f, zeta, EI3_T, EI3_A)


#: (name, formula, min_freq [Hz], max_freq [Hz], damping range) per shaper. Klipper accepts any
#: shaper_freq > 0; min_freq is shaper_defs.py's per-shaper minimum, "chosen to have projected
#: max_accel ~= 1500", below which its own calibration never proposes the shaper; the damping
#: caps are its max_damping_ratio (input_shaper.py refuses more).
KLIPPER = (
    ("zv", klipper_zv, 21.0, math.inf, (0.0, 0.99)),
    ("mzv", klipper_mzv, 23.0, math.inf, (0.0, 0.99)),
    ("zvd", klipper_zvd, 29.0, math.inf, (0.0, 0.99)),
    ("ei", klipper_ei, 29.0, math.inf, (0.0, 0.4)),
    ("2hump_ei", klipper_2hump_ei, 39.0, math.inf, (0.0, 0.3)),
    ("3hump_ei", klipper_3hump_ei, 48.0, math.inf, (0.0, 0.2)),
)


# ------------------------------------------------- Marlin FT Motion (ft_motion/shaping.cpp)
def _ftm(amplitudes, base, f, zeta):
    """set_axis_shaping_N: impulse i at i * LROUND(base / (f df) * FTM_FS) trajectory samples."""
    df = math.sqrt(1.0 - zeta * zeta)
    n1 = math.floor(base / f / df * MARLIN_FTM_FS + 0.5)     # LROUND: half away from zero
    return amplitudes, [i * n1 / MARLIN_FTM_FS for i in range(len(amplitudes))]


def _ftm_K(zeta):
    return math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta * zeta))


def weighted_ei(K, v=EI_TOLERANCE):
    """EI: (1 + V)/4, (1 - V)K/2, (1 + V)K^2/4 (Singhose, Seering and Singer 1990), the
    K-weighted closed form of Marlin, Prusa (and Klipper before 2025)."""
    a1 = 0.25 * (1.0 + v)
    return [a1, 0.5 * (1.0 - v) * K, a1 * K * K]


def weighted_ei2(K, v=EI_TOLERANCE):
    """2-hump EI (Singhose, Porter, Tuttle and Singer 1997), K-weighted."""
    v2 = v * v
    X = (v2 * (math.sqrt(1.0 - v2) + 1.0)) ** (1.0 / 3.0)
    a1 = (3.0 * X * X + 2.0 * X + 3.0 * v2) / (16.0 * X)
    a2 = (0.5 - a1) * K
    return [a1, a2, a2 * K, a1 * K ** 3]


def weighted_ei3(K, v=EI_TOLERANCE):
    """3-hump EI (Singhose et al. 1997), K-weighted."""
    a1 = 0.0625 * (1.0 + 3.0 * v + 2.0 * math.sqrt(2.0 * (v + 1.0) * v))
    a2 = 0.25 * (1.0 - v) * K
    return [a1, a2, (0.5 * (1.0 + v) - 2.0 * a1) * K * K, a2 * K * K, a1 * K ** 4]


def marlin_weighted(amplitudes):
    """A K-weighted family on FT Motion's grid, impulses half a damped period apart."""
    def shaper(f, zeta):
        return _ftm(amplitudes(_ftm_K(zeta)), 0.5, f, zeta)
    return shaper


def marlin_zvn(n):
    """ZV^n: binomial (1 + K)^n amplitudes (ZV, ZVD, ZVDD, ZVDDD)."""
    return marlin_weighted(lambda K: _binomial(K, n))


def marlin_mzv(f, zeta):
    # Marlin damps MZV with the half-period K = exp(-zeta pi / df) although its impulses are
    # 0.375 damped periods apart (Klipper: exp(-0.75 zeta pi / df)): exact only at zeta = 0
    K = _ftm_K(zeta)
    return _ftm([1.0, math.sqrt(2.0) * K, K * K], 0.375, f, zeta)


def marlin_classic_zv(f, zeta):
    """Classic input shaping (M593): the echo carries floor(cubic(zeta)) / 128 of each step,
    1 / (2 f) later (the undamped half period; stepper.cpp)."""
    if zeta <= 0.0:
        factor2 = 64.0
    elif zeta >= 1.0:
        factor2 = 0.0
    else:
        factor2 = math.floor(64.44056192 - 99.02008832 * zeta - 7.58095488 * zeta ** 2
                             + 43.073216 * zeta ** 3)
    return [128.0 - factor2, factor2], [0.0, 0.5 / f]


#: Marlin FT Motion accepts A (frequency) in [FTM_MIN_SHAPE_FREQ, FTM_FS / 2] = [20, 500] Hz
#: (Configuration_adv.h defaults) and I (zeta) in [0.01, 1] (at 1 its formulas divide by zero:
#: BELOW_ONE); classic M593 takes any F > 0 and D in [0, 1] (its echo buffer is sized at build
#: time for SHAPING_MIN_FREQ; the configuration lines say so).
MARLIN = (
    ("ZV", marlin_zvn(1), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("ZVD", marlin_zvn(2), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("ZVDD", marlin_zvn(3), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("ZVDDD", marlin_zvn(4), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("EI", marlin_weighted(weighted_ei), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("2HEI", marlin_weighted(weighted_ei2), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("3HEI", marlin_weighted(weighted_ei3), 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("MZV", marlin_mzv, 20.0, MARLIN_FTM_FS / 2, (0.01, BELOW_ONE)),
    ("M593 ZV", marlin_classic_zv, 0.0, math.inf, (0.0, 1.0)),
)
#: M493 C<mode> codes of the FT Motion shapers (shaping.h ftMotionShaper_t).
MARLIN_FTM_CODES = {"ZV": 1, "ZVD": 2, "ZVDD": 3, "ZVDDD": 4, "EI": 5, "2HEI": 6, "3HEI": 7,
                    "MZV": 8}


# --------------------------------------------- RepRapFirmware (src/Movement/AxisShaper.cpp)
def _rrf_period(f, zeta):
    """(damped period in whole step clocks, K): lrintf(StepClockRate / dampedFrequency)."""
    df = math.sqrt(1.0 - zeta * zeta)
    return round(RRF_STEP_CLOCK / (f * df)), math.exp(-zeta * math.pi / df)


def _rrf_last(coefficients, delays):
    # "The sum of the coefficients must total 1, use this to fill in the last coefficient"
    return coefficients + [1.0 - sum(coefficients)], [d / RRF_STEP_CLOCK for d in delays]


def rrf_zvdn(n):
    def zvdn(f, zeta):
        P, k = _rrf_period(f, zeta)
        j = (1.0 + k) ** n
        return _rrf_last([math.comb(n, i) * k ** i / j for i in range(n)],
                         [(P * i) // 2 for i in range(n + 1)])
    return zvdn


def rrf_mzv(f, zeta):
    # RRF stores Klipper's a3 = a1 K^2 first and a1 last (the reverse of Klipper's order, which
    # Klipper applies reversed in time): exact only at zeta = 0
    P, _ = _rrf_period(f, zeta)
    df = math.sqrt(1.0 - zeta * zeta)
    k = math.exp(-zeta * 0.75 * math.pi / df)
    a1 = 1.0 - 0.5 * math.sqrt(2.0)
    a2 = (math.sqrt(2.0) - 1.0) * k
    a3 = a1 * k * k
    s = a1 + a2 + a3
    d1 = (3 * P) // 8
    return _rrf_last([a3 / s, a2 / s], [0, d1, 2 * d1])


def _rrf_ei(tcoef, acoef):
    def ein(f, zeta):
        P, _ = _rrf_period(f, zeta)
        return _rrf_last([_cubic(c, zeta) for c in acoef[:-1]],
                         [round(_cubic(c, zeta) * P) for c in tcoef])
    return ein


def rrf_custom(amplitudes, delays=None):
    """``M593 P"custom" H<a1:...:a(n-1)> [T<t1:...:t(n-1)>]``: n <= 5 impulses, the last
    amplitude 1 - sum(H); without T the delays are i/2 damped periods (in whole clocks)."""
    a = [float(x) for x in amplitudes]

    def custom(f, zeta):
        P, _ = _rrf_period(f, zeta)
        if delays is None:
            d = [(P * i) // 2 for i in range(len(a) + 1)]
        else:
            d = [0] + [round(t * RRF_STEP_CLOCK) for t in delays]
        return _rrf_last(list(a), d)
    return custom


#: RRF's M593 takes F in [StepClockRate / (2 * 65535), 1000] Hz (5.72 Hz on Duet 3) and S in
#: [0, 0.99]; it has no plain ZV or single-hump EI. Its ei2 / ei3 are Klipper's fitted
#: polynomials (which Klipper caps at zeta 0.3 / 0.2) on the damped period: from zeta 0.413 /
#: 0.304 on they give negative amplitudes or out-of-order times, so they are capped at 0.4 / 0.3.
RRF_MIN_FREQ = RRF_STEP_CLOCK / (2 * 65535)
RRF = (
    ("zvd", rrf_zvdn(2), RRF_MIN_FREQ, 1000.0, (0.0, 0.99)),
    ("zvdd", rrf_zvdn(3), RRF_MIN_FREQ, 1000.0, (0.0, 0.99)),
    ("zvddd", rrf_zvdn(4), RRF_MIN_FREQ, 1000.0, (0.0, 0.99)),
    ("mzv", rrf_mzv, RRF_MIN_FREQ, 1000.0, (0.0, 0.99)),
    ("ei2", _rrf_ei(EI2_T, EI2_A), RRF_MIN_FREQ, 1000.0, (0.0, 0.4)),
    ("ei3", _rrf_ei(EI3_T, EI3_A), RRF_MIN_FREQ, 1000.0, (0.0, 0.3)),
)


# ------------------------------------ Prusa Buddy (feature/input_shaper/input_shaper.cpp)
def prusa_weighted(amplitudes):
    """A K-weighted family as input_shaper::get places it: half a damped period apart."""
    def shaper(f, zeta):
        _, K, td = _damped(f, zeta)
        a = amplitudes(K)
        return a, [0.5 * i * td for i in range(len(a))]
    return shaper


#: Prusa clamps the frequency to [10, 100] Hz (150 Hz on the MINI; clamp_frequency_to_safe_values)
#: and takes D in [0, 1], but stops with an error at a damping ratio of 1 (BELOW_ONE).
PRUSA = (
    ("ZV", klipper_zv, 10.0, 100.0, (0.0, BELOW_ONE)),
    ("ZVD", klipper_zvd, 10.0, 100.0, (0.0, BELOW_ONE)),
    ("MZV", klipper_mzv, 10.0, 100.0, (0.0, BELOW_ONE)),
    ("EI", prusa_weighted(weighted_ei), 10.0, 100.0, (0.0, BELOW_ONE)),
    ("EI_2HUMP", prusa_weighted(weighted_ei2), 10.0, 100.0, (0.0, BELOW_ONE)),
    ("EI_3HUMP", prusa_weighted(weighted_ei3), 10.0, 100.0, (0.0, BELOW_ONE)),
)
#: M593 T<type> codes (input_shaper_config.hpp input_shaper::Type).
PRUSA_CODES = {"ZV": 0, "ZVD": 1, "MZV": 2, "EI": 3, "EI_2HUMP": 4, "EI_3HUMP": 5}
