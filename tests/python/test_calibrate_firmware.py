# SPDX-License-Identifier: Apache-2.0
"""Firmware shaper definitions (calibrate.firmware): each firmware's impulses against its own
numbers and against closed forms, Klipper's max_accel rule, and the configuration text."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from smoothshaper.calibrate import firmware as fw
from test_api import raises

# Klipper3d/klipper at 84104bbbd7625d28b4eaaad83f4562972460ecd9 (2026-08-07): outputs of
# shaper_defs.init_shaper(name, freq, damping) (amplitudes as returned, before Klipper's
# normalisation in kin_shaper.c) and ShaperCalibrate.find_shaper_max_accel(shaper, scv=5),
# obtained by running those two files (klippy/extras/shaper_defs.py, shaper_calibrate.py) from
# that commit.
KLIPPER_EXPECTED = {
    ('zv', 35.0, 0.0): (
        [1.0, 1.0],
        [0.0, 0.014285714285714285],
        4703.999999998895),
    ('zv', 47.3, 0.1): (
        [1.0, 0.7292476142876709],
        [0.0, 0.010624078385403933],
        8719.027801826353),
    ('mzv', 23.0, 0.05): (
        [0.2928932188134524, 0.36812568993994826, 0.23134117638973944],
        [0.0, 0.0163247665539704, 0.0326495331079408],
        1507.7095072081502),
    ('mzv', 61.8, 0.15): (
        [0.2928932188134524, 0.28971800709501827, 0.14328860868671958],
        [0.0, 0.006137399726021524, 0.012274799452043048],
        11410.114606069339),
    ('zvd', 29.0, 0.1): (
        [1.0, 1.4584952285753419, 0.5318020829442597],
        [0.0, 0.017328238194124344, 0.03465647638824869],
        1610.6042531741077),
    ('zvd', 88.4, 0.3): (
        [1.0, 0.7446522098531728, 0.13862672840980345],
        [0.0, 0.005929212877386416, 0.011858425754772832],
        17265.46670033985),
    ('ei', 29.0, 0.0): (
        [0.2621605, 0.4756125, 0.262227],
        [0.0, 0.01723793103448276, 0.034482758620689655],
        1539.6247469078153),
    ('ei', 52.6, 0.1): (
        [0.35488138, 0.45299809, 0.19212052999999998],
        [0.0, 0.009643348833595841, 0.01910718279960479],
        5038.2017526317495),
    ('ei', 70.0, 0.4): (
        [0.7116017800000001, 0.23378553999999996, 0.05461267999999997],
        [0.0, 0.008851597563743843, 0.015586992159713743],
        8767.549899843916),
    ('2hump_ei', 39.0, 0.1): (
        [0.2586675, 0.36011950000000004, 0.27290311, 0.10882055],
        [0.0, 0.013228348717948717, 0.025851441025641027, 0.03817759743589744],
        1476.264639534449),
    ('2hump_ei', 66.6, 0.3): (
        [0.5613985, 0.2889665, 0.10581297, 0.044334849999999995],
        [0.0, 0.009988630630630633, 0.016979060060060062, 0.022461659159159163],
        4394.6746099052525),
    ('3hump_ei', 48.0, 0.1): (
        [0.2208542, 0.2772112, 0.25969944, 0.167055, 0.0751792],
        [0.0, 0.011260456249999998, 0.021417729166666667, 0.03137289583333333,
         0.041310981249999996],
        1387.329525500536),
    ('3hump_ei', 95.0, 0.2): (
        [0.3861276, 0.29498559999999996, 0.17723152000000003, 0.093218, 0.048434799999999986],
        [0.0, 0.0070000800000000005, 0.012112778947368421, 0.016579073684210525,
         0.021168298947368422],
        5744.05270464703),
}


@pytest.mark.parametrize("key", list(KLIPPER_EXPECTED))
def test_klipper_impulses_and_max_accel_are_klippers_own(key):
    """Amplitudes to 1e-15 (the same arithmetic; Klipper's are normalised as kin_shaper.c
    does), times to 1e-16 s; Klipper bisects max_accel until the bracket is under 1e-8 mm/s^2
    and returns its lower end, so the exact root lies 0 to 1e-8 above it."""
    name, freq, damping = key
    A_k, T_k, accel_k = KLIPPER_EXPECTED[key]
    A, t = fw.by_name("klipper", name).impulses(freq, damping)
    A_k = np.array(A_k) / sum(A_k)
    np.testing.assert_allclose(A, A_k, rtol=0, atol=1e-15)
    np.testing.assert_allclose(t, T_k, rtol=0, atol=1e-16)
    accel = fw.max_accel(A, t)
    assert 0 <= accel - accel_k <= 1e-8 + 1e-12 * accel_k


# Values from compiling each firmware's own function (float arithmetic, as on the printer) at
# inputs exact in binary32, so only the firmware's float rounding separates them from ours:
# amplitudes agree to 2e-7 (under two float32 epsilons for the few rounded operations behind
# each amplitude), times exactly (whole samples / step clocks).
#
# Marlin src/module/ft_motion/shaping.cpp AxisShaping::set_axis_shaping_A (vtol 0.05) and
# set_axis_shaping_N (FTM_FS 1000): (M493 C code, freq, zeta) -> (Ai, Ni - Ni[0] in samples)
MARLIN_FTM_EXPECTED = {
    (1, 41.25, 0.125): ([0.597678959, 0.402321011], [0, 12]),
    (2, 37.5, 0.0625): ([0.301429003, 0.495192975, 0.203377977], [0, 13, 26]),
    (3, 55.0, 0.1875): ([0.269065738, 0.443139106, 0.243276715, 0.0445184149], [0, 9, 18, 27]),
    (4, 47.875, 0.125): ([0.127606243, 0.343586951, 0.346922636, 0.155684784, 0.0261993725],
                         [0, 11, 22, 33, 44]),
    (5, 60.0, 0.125): ([0.37436679, 0.45600161, 0.169631615], [0, 8, 16]),
    (6, 72.5, 0.25): ([0.407485873, 0.385479122, 0.171285421, 0.0357495993], [0, 7, 14, 21]),
    (7, 88.0, 0.0625): ([0.162204713, 0.281578153, 0.292391241, 0.189984351, 0.073841624],
                        [0, 6, 12, 18, 24]),
    (8, 45.5, 0.125): ([0.415786862, 0.395813376, 0.188399717], [0, 8, 16]),
}
# Marlin src/module/stepper.cpp Stepper::set_shaping_damping_ratio: zeta -> factor2 (of 128)
MARLIN_CLASSIC_FACTOR2 = {0.0: 64, 0.0625: 58, 0.125: 52, 0.25: 39, 0.5: 18, 1.0: 0}
# RepRapFirmware src/Movement/AxisShaper.cpp AxisShaper::Configure (StepClockRate 750 kHz):
# (P name, F, S) -> (coefficients, delays in step clocks)
RRF_EXPECTED = {
    ("zvd", 41.25, 0.125): ([0.357220143, 0.480917603, 0.161862254], [0, 9163, 18326]),
    ("zvdd", 55.0, 0.1875): ([0.269065708, 0.443139076, 0.243276685, 0.0445184708],
                             [0, 6941, 13883, 20824]),
    ("zvddd", 47.875, 0.0625): ([0.0908594579, 0.298531085, 0.367824107, 0.201422676,
                                 0.0413626432], [0, 7848, 15696, 23544, 31392]),
    ("mzv", 45.5, 0.125): ([0.212148711, 0.403716803, 0.384134471], [0, 6230, 12460]),
    ("ei2", 60.0, 0.125): ([0.289416283, 0.358527839, 0.254054636, 0.0980012417],
                           [0, 6587, 12746, 18732]),
    ("ei3", 72.5, 0.25): ([0.487495631, 0.304549366, 0.120472498, 0.0512090623, 0.0362734795],
                          [0, 8355, 13791, 17786, 21923]),
}
# Prusa-Firmware-Buddy feature/input_shaper/input_shaper.cpp input_shaper::get (vibration
# reduction 20), normalised as init_input_shaper_pulses does: (M593 T, F, D) -> (a, t [s])
PRUSA_EXPECTED = {
    (0, 41.25, 0.125): ([0.597678982, 0.402321018], [0, 0.0122170337]),
    (1, 55.0, 0.1875): ([0.416778786, 0.457610557, 0.125610657], [0, 0.00925505161, 0.0185101032]),
    (2, 47.875, 0.0625): ([0.337306115, 0.411584248, 0.251109637],
                          [0, 0.0078482423, 0.0156964846]),
    (3, 60.0, 0.125): ([0.37436679, 0.456001604, 0.169631606], [0, 0.00839921087, 0.0167984217]),
    (4, 72.5, 0.25): ([0.407485869, 0.38547911, 0.171285424, 0.0357495978],
                      [0, 0.00712272804, 0.0142454561, 0.0213681832]),
    (5, 88.0, 0.0625): ([0.162204717, 0.281578133, 0.292391223, 0.189984322, 0.0738416046],
                        [0, 0.00569294812, 0.0113858962, 0.0170788448, 0.0227717925]),
}
F32 = 2e-7      # amplitudes: float32 firmware arithmetic against ours in double


def _by_code(firmware, codes, code):
    return fw.by_name(firmware, {v: k for k, v in codes.items()}[code])


@pytest.mark.parametrize("key", list(MARLIN_FTM_EXPECTED))
def test_marlin_ft_motion_is_marlins_own(key):
    code, freq, zeta = key
    A_m, N_m = MARLIN_FTM_EXPECTED[key]
    A, t = _by_code("marlin", fw.defs.MARLIN_FTM_CODES, code).impulses(freq, zeta)
    np.testing.assert_allclose(A, A_m, rtol=0, atol=F32)
    np.testing.assert_array_equal(np.round(t * 1000).astype(int), N_m)
    np.testing.assert_allclose(t * 1000, np.round(t * 1000), rtol=0, atol=1e-12)   # on the grid


@pytest.mark.parametrize("zeta", list(MARLIN_CLASSIC_FACTOR2))
def test_marlin_classic_zv_is_marlins_fixed_point_echo(zeta):
    """M593's ZV: the echo carries factor2/128 of each step, half an undamped period later."""
    A, t = fw.by_name("marlin", "M593 ZV").impulses(40.0, zeta)
    f2 = MARLIN_CLASSIC_FACTOR2[zeta]
    np.testing.assert_allclose(A, [(128 - f2) / 128, f2 / 128], rtol=0, atol=1e-15)
    np.testing.assert_allclose(t, [0.0, 1 / 80.0], rtol=0, atol=1e-18)


@pytest.mark.parametrize("key", list(RRF_EXPECTED))
def test_rrf_is_reprapfirmwares_own(key):
    name, freq, zeta = key
    A_r, D_r = RRF_EXPECTED[key]
    A, t = fw.by_name("rrf", name).impulses(freq, zeta)
    np.testing.assert_allclose(A, A_r, rtol=0, atol=F32)
    np.testing.assert_array_equal(np.round(t * 750000).astype(int), D_r)


@pytest.mark.parametrize("key", list(PRUSA_EXPECTED))
def test_prusa_is_prusas_own(key):
    code, freq, zeta = key
    A_p, T_p = PRUSA_EXPECTED[key]
    A, t = _by_code("prusa", fw.defs.PRUSA_CODES, code).impulses(freq, zeta)
    np.testing.assert_allclose(A, A_p, rtol=0, atol=F32)
    np.testing.assert_allclose(t, T_p, rtol=3e-7, atol=0)   # float32 times: 2.5 epsilons


# -- closed forms and the shapers' defining properties ----------------------------------------

def residual(A, t, freq, zeta):
    """Residual vibration of a mode (freq [Hz], zeta) after the impulses, relative to an
    unshaped step: |sum A_i exp(-zeta w (t_n - t_i)) exp(j wd t_i)| / sum A (Singer and Seering,
    "Preshaping command inputs to reduce system vibration", 1990, eq. 5; Klipper's
    _estimate_shaper evaluates the same)."""
    w = 2 * np.pi * np.atleast_1d(np.asarray(freq, float))[:, None]
    wd = w * math.sqrt(1 - zeta * zeta)
    W = A * np.exp(-zeta * w * (t[-1] - t))
    return np.abs((W * np.exp(1j * wd * t)).sum(axis=1)) / A.sum()


ALL = [s for f in fw.FIRMWARES for s in fw.shapers(f)]


@pytest.mark.parametrize("s", ALL, ids=lambda s: f"{s.firmware}-{s.name}")
def test_every_definition_is_a_normalised_causal_sequence(s):
    lo, hi = s.damping_range()
    fmin = max(s.min_freq, 10.0)
    for freq in (fmin, min(3 * fmin, s.max_freq), min(150.0, s.max_freq)):
        for zeta in (lo, min(max(lo, 0.1), hi), hi if hi < 0.99 else 0.5):
            A, t = s.impulses(freq, zeta)
            assert A.shape == t.shape and 2 <= A.size <= 5
            assert abs(A.sum() - 1) <= 4e-16 and np.all(A > 0), (freq, zeta, A)
            assert t[0] == 0 and np.all(np.diff(t) > 0), (freq, zeta, t)
            # the sequence spans 1/2 to 2 damped periods (ZV to ZVDDD / 3-hump EI)
            period = 1 / (freq * math.sqrt(1 - zeta * zeta))
            assert 0.3 * period < t[-1] < 2.2 * period, (freq, zeta, t[-1] / period)


# Designed for zero residual at the design point (the ZV family and MZV): 1e-12 is rounding
ZERO_AT_DESIGN = [("klipper", "zv"), ("klipper", "mzv"), ("klipper", "zvd"),
                  ("prusa", "ZV"), ("prusa", "ZVD"), ("prusa", "MZV"),
                  ("marlin", "ZV"), ("marlin", "ZVD"), ("marlin", "ZVDD"), ("marlin", "ZVDDD"),
                  ("rrf", "zvd"), ("rrf", "zvdd"), ("rrf", "zvddd")]


@pytest.mark.parametrize("firmware,name", ZERO_AT_DESIGN)
@pytest.mark.parametrize("zeta", [0.01, 0.1, 0.2])
def test_zero_residual_at_the_design_point(firmware, name, zeta):
    """At a damped frequency of 50 Hz the half period is 10 ms, whole samples of Marlin's
    1 ms grid and 7500 of RepRapFirmware's step clocks, so their grids cost nothing there."""
    freq = 50 / math.sqrt(1 - zeta * zeta)
    A, t = fw.by_name(firmware, name).impulses(freq, zeta)
    assert residual(A, t, freq, zeta)[0] < 1e-12


def test_zvd_family_is_repeated_zv():
    """ZVD^n = ZV convolved n + 1 times (Singer and Seering 1990): the binomial amplitudes of
    Marlin's ZVDD/ZVDDD and RepRapFirmware's zvdd/zvddd."""
    zeta, freq = 0.1, 50 / math.sqrt(0.99)
    zv, _ = fw.by_name("marlin", "ZV").impulses(freq, zeta)
    for n, marlin, rrf in ((2, "ZVD", "zvd"), (3, "ZVDD", "zvdd"), (4, "ZVDDD", "zvddd")):
        expect = zv
        for _ in range(n - 1):
            expect = np.convolve(expect, zv)
        for firmware, name in (("marlin", marlin), ("rrf", rrf)):
            A, _ = fw.by_name(firmware, name).impulses(freq, zeta)
            np.testing.assert_allclose(A, expect, rtol=0, atol=1e-15)


V = 0.05


def hump_top(A, t, f0, zeta):
    """The highest residual between the outermost zeros (minima under V/5) around f0."""
    f = np.linspace(0.4 * f0, 1.6 * f0, 48001)
    r = residual(A, t, f, zeta)
    zeros = np.flatnonzero((r[1:-1] < r[:-2]) & (r[1:-1] < r[2:]) & (r[1:-1] < V / 5)) + 1
    return r[zeros[0]:zeros[-1] + 1].max()


#: (firmware, name, residual at the design point in units of V, number of impulses)
OLD_EI = [("prusa", "EI", 1.0, 3), ("prusa", "EI_2HUMP", 0.0, 4), ("prusa", "EI_3HUMP", 1.0, 5),
          ("marlin", "EI", 1.0, 3), ("marlin", "2HEI", 0.0, 4), ("marlin", "3HEI", 1.0, 5)]


@pytest.mark.parametrize("firmware,name,at_design,m", OLD_EI)
def test_papers_ei_family_holds_its_tolerance(firmware, name, at_design, m):
    """Prusa's and Marlin's EI shapers (Klipper's before 2025) are the closed forms of
    Singhose, Seering and Singer (1990; Singhose et al. 1997 for 2 and 3 humps) weighted by
    K = exp(-zeta pi / df) per half period. Undamped they leave exactly V = 5 % at the design
    frequency (EI, 3-hump EI) or 0 (2-hump EI), and their humps rise to exactly V (found to
    1e-6 on the grid); damped, the K weighting scales the residual at the design point by
    K^(m-1) / sum(a_i K^i) (m impulses, a_i the undamped amplitudes), so it is no longer V:
    3.6 % for EI at zeta = 0.1, the departure Klipper's fitted EI removes. Marlin is checked
    at 50 Hz damped, on its 1 ms grid, and from zeta 0.01, the least M493 takes."""
    s = fw.by_name(firmware, name)
    z0 = s.damping_range()[0]
    if z0 == 0:
        A0, t = s.impulses(50.0, 0.0)
        assert abs(residual(A0, t, 50.0, 0.0)[0] - at_design * V) < 1e-12
        assert abs(hump_top(A0, t, 50.0, 0.0) - V) < 1e-6
    A0 = fw.by_name("prusa", {"2HEI": "EI_2HUMP", "3HEI": "EI_3HUMP"}.get(name, name)) \
        .impulses(50.0, 0.0)[0]
    for zeta in (max(z0, 0.05), 0.1, 0.2):
        K = math.exp(-zeta * math.pi / math.sqrt(1 - zeta * zeta))
        freq = 50 / math.sqrt(1 - zeta * zeta)
        A, t = s.impulses(freq, zeta)
        scale = K ** (m - 1) / np.sum(A0 * K ** np.arange(m))
        assert abs(residual(A, t, freq, zeta)[0] - at_design * V * scale) < 1e-12


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.1, 0.2, 0.3, 0.4])
def test_klipper_ei_keeps_its_tolerance_at_every_damping(zeta):
    """Klipper's fitted EI (get_ei_shaper, 2025) leaves V = 5 % at the design point for every
    damping ratio it accepts, to the accuracy of its 5-digit polynomial fit: 4e-3 (measured
    3.9e-3 at its cap, zeta = 0.4; 1.2e-3 undamped)."""
    A, t = fw.by_name("klipper", "ei").impulses(50.0, zeta)
    assert abs(residual(A, t, 50.0, zeta)[0] - V) < 4e-3


#: (firmware, name, residual at the design point in units of V, tolerance of the fit)
FITTED = [("klipper", "2hump_ei", 0.0, 3.3e-3), ("rrf", "ei2", 0.0, 3.7e-3),
          ("klipper", "3hump_ei", 1.0, 8e-4), ("rrf", "ei3", 1.0, 1.1e-3)]


@pytest.mark.parametrize("firmware,name,at_design,tol", FITTED)
@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.1])
def test_fitted_multi_hump_ei_near_their_design(firmware, name, at_design, tol, zeta):
    """The fitted 2- and 3-hump EI (Klipper on the undamped period 1/f; the same coefficients
    in RepRapFirmware on the damped period) leave about 0 and V at the design point; the
    tolerances are the fits' worst over zeta <= 0.1 (measured 3.23e-3, 3.68e-3, 8.0e-4,
    1.02e-3). Their first hump stays within 4e-3 of V undamped."""
    A, t = fw.by_name(firmware, name).impulses(50.0, zeta)
    assert abs(residual(A, t, 50.0, zeta)[0] - at_design * V) < tol
    if zeta == 0:
        assert abs(hump_top(A, t, 50.0, 0.0) - V) < 4e-3


def test_firmware_differences_from_the_papers():
    """Where firmware departs from the papers (docs/calibrate.md): Marlin's MZV damps with
    the half-period K, RepRapFirmware stores MZV's amplitudes reversed, Marlin's classic ZV
    spaces its echo by the undamped half period; all exact at zeta = 0, residuals of 4.9 %,
    16.2 % and 0.67 % at the design point for zeta = 0.1."""
    zeta = 0.1
    freq = 50 / math.sqrt(1 - zeta * zeta)
    klipper, tk = fw.by_name("klipper", "mzv").impulses(freq, zeta)
    rrf, tr = fw.by_name("rrf", "mzv").impulses(freq, zeta)
    np.testing.assert_allclose(rrf, klipper[::-1], rtol=0, atol=1e-15)
    np.testing.assert_allclose(tr, tk, rtol=0, atol=1 / 750000)
    K = math.exp(-zeta * math.pi / math.sqrt(1 - zeta * zeta))
    marlin, _ = fw.by_name("marlin", "MZV").impulses(freq, zeta)
    expect = np.array([1, math.sqrt(2) * K, K * K])
    np.testing.assert_allclose(marlin, expect / expect.sum(), rtol=0, atol=1e-15)
    for (firmware, name), expect in {("marlin", "MZV"): 0.0486, ("rrf", "mzv"): 0.1623,
                                     ("marlin", "M593 ZV"): 0.00666}.items():
        A, t = fw.by_name(firmware, name).impulses(freq, zeta)
        assert abs(residual(A, t, freq, zeta)[0] - expect) < 5e-5    # the figures' rounding
    A, t = fw.by_name("rrf", "mzv").impulses(50.0, 0.0)
    assert residual(A, t, 50.0, 0.0)[0] < 1e-12
    A, t = fw.by_name("marlin", "M593 ZV").impulses(50.0, 0.0)
    assert residual(A, t, 50.0, 0.0)[0] < 1e-12


# -- max_accel: Klipper's rule for any sequence -----------------------------------------------

def klipper_smoothing(A, T, accel, scv=5.0):
    """shaper_calibrate.py _get_shaper_smoothing, term by term."""
    inv_D = 1.0 / sum(A)
    ts = sum(a * t for a, t in zip(A, T)) * inv_D
    off90 = sum(a * (scv + 0.5 * accel * (t - ts)) * (t - ts) for a, t in zip(A, T) if t >= ts)
    off180 = sum(a * 0.5 * accel * (t - ts) ** 2 for a, t in zip(A, T))
    return max(off90 * inv_D * math.sqrt(2.0), off180 * inv_D)


def klipper_bisect(A, T, scv=5.0, target=0.12):
    """shaper_calibrate.py _bisect on find_shaper_max_accel's predicate."""
    def ok(a):
        return klipper_smoothing(A, T, a, scv) <= target
    left = right = 1.0
    if not ok(1e-9):
        return 0.0
    while not ok(left):
        right = left
        left *= 0.5
    if right == left:
        while ok(right):
            right *= 2.0
    while right - left > 1e-8:
        middle = (left + right) * 0.5
        if ok(middle):
            left = middle
        else:
            right = middle
    return left


@pytest.mark.parametrize("s", [s for f in ("marlin", "rrf", "prusa") for s in fw.shapers(f)],
                         ids=lambda s: f"{s.firmware}-{s.name}")
def test_max_accel_is_klippers_bisection_for_every_firmware(s):
    for freq in (max(s.min_freq, 25.0), 61.3):
        A, t = s.impulses(freq, 0.1 if s.damping_range()[0] <= 0.1 else 0.2)
        got, ref = fw.max_accel(A, t), klipper_bisect(list(A), list(t))
        assert 0 <= got - ref <= 1e-8 + 1e-12 * ref


def test_max_accel_edges_and_options():
    assert fw.max_accel([1.0], [0.0]) == math.inf                  # nothing to smooth
    assert fw.max_accel([1.0, 1.0], [0.0, 0.0]) == math.inf
    A, t = fw.by_name("klipper", "zv").impulses(40.0, 0.1)
    assert fw.max_accel(A, t, scv=1e6) == 0.0                      # scv alone too much
    assert klipper_bisect(list(A), list(t), scv=1e6) == 0.0
    a = fw.max_accel(A, t, scv=2.0, target_smoothing=0.05)
    assert 0 <= a - klipper_bisect(list(A), list(t), scv=2.0, target=0.05) <= 1e-8
    np.testing.assert_allclose(fw.max_accel(3 * A, t), fw.max_accel(A, t), rtol=1e-14)


@settings(max_examples=60)
@given(st.lists(st.tuples(st.floats(0.01, 1.0), st.floats(0.0, 0.05)), min_size=2, max_size=6),
       st.floats(0.0, 20.0), st.floats(0.01, 1.0))
def test_max_accel_is_the_exact_limit(pulses, scv, target):
    """For random sequences: the smoothing at max_accel is the target (to rounding) and any
    larger acceleration exceeds it, so the closed form is the supremum Klipper bisects for."""
    A = np.array([p[0] for p in pulses])
    t = np.sort(np.array([p[1] for p in pulses]))
    a = fw.max_accel(A, t, scv=scv, target_smoothing=target)
    if math.isinf(a):
        assert np.ptp(t) == 0 or klipper_smoothing(A, t, 1e12, scv) <= target
    elif a == 0:
        assert klipper_smoothing(A, t, 1e-9, scv) > target
    else:
        assert abs(klipper_smoothing(A, t, a, scv) - target) <= 1e-12 * target
        assert klipper_smoothing(A, t, a * (1 + 1e-9), scv) > target


# -- configuration text -----------------------------------------------------------------------

def pick(firmware, name, freq, damping=0.1):
    s = fw.by_name(firmware, name)
    return fw.Pick(s, freq, damping, fw.max_accel(*s.impulses(freq, damping)))


def klipper_section(text):
    """[input_shaper] as Klipper reads printer.cfg (configfile.py: RawConfigParser,
    inline comments after ';' or '#')."""
    import configparser
    cp = configparser.RawConfigParser(strict=False, inline_comment_prefixes=(";", "#"))
    cp.read_string(text)
    return dict(cp["input_shaper"])


@pytest.mark.parametrize("axes", [("x",), ("x", "y"), ("x", "y", "z")])
def test_klipper_section_for_one_two_three_axes(axes):
    kinds = {"x": ("mzv", 52.37), "y": ("ei", 41.0), "z": ("zv", 33.3)}
    picks = {f"accel_{a}": pick("klipper", *kinds[a], damping=0.12) for a in axes}
    text = fw.config_text("klipper", picks)
    assert isinstance(text, str) and text.warnings == ()
    section = klipper_section(text)
    assert len(section) == 3 * len(axes)
    for a in axes:
        assert section[f"shaper_type_{a}"] == kinds[a][0]
        assert float(section[f"shaper_freq_{a}"]) == kinds[a][1]
        assert float(section[f"damping_ratio_{a}"]) == 0.12
    lowest = min(p.max_accel for p in picks.values())
    assert f"max_accel: {int(lowest // 100) * 100}" in text
    for name, p in picks.items():
        assert f"{name} <= {int(p.max_accel // 100) * 100}" in text


def test_klipper_cannot_express_is_said_never_dropped():
    picks = {"x": pick("klipper", "mzv", 52.4), "xyz": pick("klipper", "ei", 47.0),
             "b.csv:x": pick("klipper", "zv", 50.0),
             "y": fw.Pick(fw.by_name("klipper", "ei"), 40.0, 0.5, 3000.0),
             "z": fw.Pick(None, 30.0, 0.1, 0.0)}
    text = fw.config_text("klipper", picks)
    assert klipper_section(text) == {"shaper_type_x": "mzv", "shaper_freq_x": "52.4",
                                     "damping_ratio_x": "0.1"}
    assert len(text.warnings) == 4
    for name, why in (("xyz", "no axis 'xyz'"), ("b.csv:x", "one shaper per axis"),
                      ("y", "outside its damping range, 0 to 0.4"), ("z", "no klipper shaper")):
        assert any(w.startswith(f"axis {name}:") and why in w for w in text.warnings), name
        assert f"WARNING: axis {name}:" in text
    assert "#   shaper_type_<axis>: ei" in text and "#   shaper_freq_<axis>: 47" in text
    assert "#   damping_ratio_y: 0.5" in text


def test_klipper_below_its_calibration_minimum_is_noted_not_refused():
    text = fw.config_text("klipper", {"y": pick("klipper", "zv", 18.0)})
    assert klipper_section(text)["shaper_freq_y"] == "18"
    assert "below 21 Hz" in text and text.warnings == ()


@pytest.mark.parametrize("n", [1, 2, 3])
def test_marlin_ft_motion_lines(n):
    picks = dict(list({"x": pick("marlin", "ZVD", 41.5), "y": pick("marlin", "2HEI", 58.0, 0.07),
                       "z": pick("marlin", "MZV", 33.0)}.items())[:n])
    text = fw.config_text("marlin", picks)
    lines = [ln for ln in text.splitlines() if ln.startswith("M493")]
    assert lines[0] == "M493 S1" and text.warnings == ()
    expect = ["M493 X C2 A41.5 I0.1 ; ZVD", "M493 Y C6 A58 I0.07 Q0.05 ; 2HEI",
              "M493 Z C8 A33 I0.1 ; MZV"][:n]
    assert lines[1:] == expect
    assert "; to limit acceleration as suggested: M201 X" in text


def test_marlin_classic_and_cannot_express():
    text = fw.config_text("marlin", {"x": pick("marlin", "M593 ZV", 40.2, 0.15),
                                     "y": pick("marlin", "M593 ZV", 35.0, 0.15)})
    assert "M593 X F40.2 D0.15" in text and "M593 Y F35 D0.15" in text
    assert "SHAPING_MIN_FREQ <= 35" in text and text.warnings == ()
    assert not any(ln.startswith("M493") for ln in text.splitlines())     # FT Motion left off
    mixed = fw.config_text("marlin", {"x": pick("marlin", "EI", 45.0),
                                      "y": pick("marlin", "M593 ZV", 35.0),
                                      "z": fw.Pick(fw.by_name("marlin", "ZV"), 12.0, 0.1, 500.0)})
    assert "M493 X C5 A45 I0.1 Q0.05 ; EI" in mixed
    assert "; M593 Y F35 D0.1" in mixed and "; M493 Z C1 A12 I0.1 ; ZV" in mixed
    assert len(mixed.warnings) == 2
    assert any("M593 ZV is classic input shaping (M593), the other axes use FT Motion" in w
               for w in mixed.warnings)
    assert any("outside its frequency range, 20 to 500 Hz" in w for w in mixed.warnings)


def test_rrf_one_shaper_for_all_axes():
    same = fw.config_text("rrf", {"x": pick("rrf", "ei2", 48.0), "y": pick("rrf", "ei2", 48.0)})
    assert 'M593 P"ei2" F48 S0.1 ; for x' in same and same.warnings == ()
    assert "; axis y takes the same shaper" in same
    two = fw.config_text("rrf", {"x": pick("rrf", "zvd", 48.0), "y": pick("rrf", "mzv", 40.0),
                                 "z": pick("rrf", "zvddd", 30.0)})
    assert two.count("\nM593 ") == 1 and len(two.warnings) == 2
    assert '; M593 P"mzv" F40 S0.1' in two and '; M593 P"zvddd" F30 S0.1' in two
    assert "one input shaper for all axes" in two.warnings[0]


def test_rrf_custom_round_trips():
    """A library sequence sent as M593 P"custom": H holds all but the last amplitude (the
    firmware makes it 1 - sum H), T the delays [s], rounded to 750 kHz step clocks."""
    A = np.array([0.3, 0.45, 0.25])
    t = np.array([0.0, 0.0093, 0.0186])
    s = fw.rrf_custom(A * 4, t)                   # any scale: normalised
    text = fw.config_text("rrf", {"x": fw.Pick(s, 53.8, 0.1, fw.max_accel(A, t))})
    line = next(ln for ln in text.splitlines() if ln.startswith("M593"))
    assert line.startswith('M593 P"custom" H0.3:0.45 T0.0093:0.0186')
    A2, t2 = s.impulses(53.8, 0.1)
    np.testing.assert_allclose(A2, A, rtol=0, atol=1e-15)
    np.testing.assert_allclose(t2, t, rtol=0, atol=0.5 / 750000)
    half = fw.rrf_custom([0.5, 0.5])             # without T: half the damped period
    A3, t3 = half.impulses(50.0, 0.0)
    np.testing.assert_allclose(t3, [0.0, 0.01], rtol=0, atol=1e-15)
    raises("A", fw.rrf_custom, np.ones(6))
    raises("A", fw.rrf_custom, [1.0, -1.0])
    raises("t", fw.rrf_custom, A, [0.0, 0.02, 0.01])
    raises("t", fw.rrf_custom, A, [0.001, 0.01, 0.02])


def test_prusa_lines_and_its_clamp():
    text = fw.config_text("prusa", {"x": pick("prusa", "MZV", 50.7), "y": pick("prusa", "EI", 40.6),
                                    "z": pick("prusa", "ZVD", 12.0)})
    assert "M593 X T2 F50.7 D0.1 ; MZV" in text and "M593 Y T3 F40.6 D0.1 R20 ; EI" in text
    assert "M593 Z T1 F12 D0.1 ; ZVD" in text and text.warnings == ()
    high = fw.config_text("prusa", {"x": fw.Pick(fw.by_name("prusa", "MZV"), 120.0, 0.1, 9e4)})
    assert "; M593 X T2 F120 D0.1 ; MZV" in high and len(high.warnings) == 1
    assert "10 to 100 Hz" in high.warnings[0]


def applied(firmware, text):
    """How many picks the text applies: Klipper's shaper_type_ keys; Marlin's and Prusa's
    active per-axis lines; RepRapFirmware's one M593 line and the axes sharing it."""
    lines = text.splitlines()
    if firmware == "klipper":
        return sum(k.startswith("shaper_type_") for k in klipper_section(text))
    if firmware == "rrf":
        return sum(ln.startswith("M593 ") for ln in lines) + text.count("takes the same shaper")
    return sum(ln[:6] in ("M493 X", "M493 Y", "M493 Z", "M593 X", "M593 Y", "M593 Z")
               for ln in lines)


@settings(max_examples=40)
@given(st.sampled_from(["klipper", "marlin", "rrf", "prusa"]),
       st.lists(st.tuples(st.sampled_from(["x", "y", "z", "xyz", "accel_x", "a.csv:y", "dir45"]),
                          st.integers(0, 8), st.floats(5.0, 600.0), st.floats(0.0, 0.9)),
                min_size=1, max_size=5, unique_by=lambda p: p[0]))
def test_no_axis_is_ever_dropped(firmware, raw):
    """Whatever the picks, each one is either applied or written as a comment with exactly
    one warning naming it."""
    options = fw.shapers(firmware)
    picks = {a: fw.Pick(options[k % len(options)], f, z, 1000.0) for a, k, f, z in raw}
    text = fw.config_text(firmware, picks)
    for a in picks:
        assert sum(w.startswith(f"axis {a}:") for w in text.warnings) <= 1
    assert applied(firmware, text) + len(text.warnings) == len(picks)


# -- invalid inputs -------------------------------------------------------------------------

def test_invalid_inputs_name_the_parameter():
    raises("firmware", fw.shapers, "duet")
    raises("firmware", fw.shapers, None)
    raises("firmware", fw.config_text, "none", {"x": pick("klipper", "zv", 40.0)})
    raises("name", fw.by_name, "klipper", "zvddd")
    s = fw.by_name("klipper", "ei")
    for bad in (float("nan"), -1.0, 0.0, "40", True, math.inf):
        raises("freq", s.impulses, bad, 0.1)
    raises("freq", fw.by_name("marlin", "ZV").impulses, 19.9, 0.1)      # FTM_MIN_SHAPE_FREQ
    raises("freq", fw.by_name("prusa", "ZV").impulses, 100.5, 0.1)
    for bad in (0.41, -0.01, float("nan"), None):
        raises("damping", s.impulses, 50.0, bad)
    raises("damping", fw.by_name("marlin", "ZVD").impulses, 50.0, 0.0)   # M493 I >= 0.01
    raises("damping", fw.by_name("marlin", "ZVD").impulses, 50.0, 1.0)
    raises("A", fw.max_accel, [1.0, float("nan")], [0.0, 0.01])
    raises("t", fw.max_accel, [1.0, 1.0], [0.0])
    raises("A", fw.max_accel, [1.0, -1.0], [0.0, 0.01])
    raises("A", fw.max_accel, [], [])
    raises("scv", fw.max_accel, [1.0], [0.0], scv=-1.0)
    raises("target_smoothing", fw.max_accel, [1.0], [0.0], target_smoothing=0.0)
    good = pick("klipper", "zv", 40.0)
    raises("picks", fw.config_text, "klipper", {})
    raises("picks", fw.config_text, "klipper", [good])
    raises("picks[x]", fw.config_text, "klipper", {"x": (1, 2)})
    raises("picks[x].shaper", fw.config_text, "klipper", {"x": pick("rrf", "zvd", 40.0)})
    raises("picks[x].shaper", fw.config_text, "klipper", {"x": ("zv", 40.0, 0.1, 1e3)})
    raises("picks[x].freq", fw.config_text, "klipper", {"x": good._replace(freq=float("nan"))})
    raises("picks[x].damping", fw.config_text, "klipper", {"x": good._replace(damping=-0.1)})
    raises("picks[x].max_accel", fw.config_text, "klipper",
           {"x": good._replace(max_accel=float("nan"))})


# Klipper at the same commit, parameterised shapers: init_shaper(shaper_type, freq, damping)
# and find_shaper_max_accel, run from its files
KLIPPER_PARAMETERISED = {
    ('mzv(n=4, t=0.9)', 45.0, 0.1): (
        [0.1909830056250527, 0.25568625036953674, 0.21155942818054108, 0.10818567384361166],
        [0.0, 0.00670025210172808, 0.01340050420345616, 0.020100756305184243],
        5376.7626028856375),
    ('mzv(n=5, t=1.6)', 60.0, 0.05): (
        [0.06986162259770075, 0.22018605732555158, 0.2805768267855882, 0.1711997052818991,
         0.04223427697202066],
        [0.0, 0.006675015657623452, 0.013350031315246903, 0.020025046972870355,
         0.026700062630493807],
        5113.545954314949),
    ('mzv(n=6, t=2.2)', 38.0, 0.0): (
        [0.03267656642114567, 0.15763592171096602, 0.3096875121328388, 0.30968751196086053,
         0.15763592144613264, 0.032676566328056184],
        [0.0, 0.011578947368421053, 0.023157894736842106, 0.034736842105263156,
         0.04631578947368421, 0.05789473684210526],
        1347.2370584793716),
    ('ei(v_tol=0.1)', 50.0, 0.1): (
        [0.37511486000000005, 0.41740318, 0.20748195999999997],
        [0.0, 0.010252131674811205, 0.02010075630518424],
        4262.623291110332),
    ('ei(v_tol=0.02)', 41.0, 0.3): (
        [0.552446668, 0.36518444400000005, 0.08236888799999997],
        [0.0, 0.013091966331571727, 0.025567922846876055],
        3075.7682034325408),
}


@pytest.mark.parametrize("key", list(KLIPPER_PARAMETERISED))
def test_klipper_parameterised_shapers_are_klippers_own(key):
    """mzv(n, t) amplitudes to 1e-9: Klipper solves the normal equations M'M A = M'F, which
    squares the system's condition number (its n = 6 result is asymmetric by 1.7e-10; ours,
    a least-squares solve of M A = F, is symmetric to rounding); the rest as above."""
    shaper_type, freq, damping = key
    A_k, T_k, accel_k = KLIPPER_PARAMETERISED[key]
    inside = shaper_type[shaper_type.index("(") + 1:-1].replace(" ", "")
    args = dict(kv.split("=") for kv in inside.split(","))
    s = fw.klipper_mzv(int(args["n"]), float(args["t"])) if shaper_type.startswith("mzv") \
        else fw.klipper_ei(float(args["v_tol"]))
    assert s.name == shaper_type
    A, t = s.impulses(freq, damping)
    np.testing.assert_allclose(A, np.array(A_k) / sum(A_k), rtol=0, atol=1e-9)
    np.testing.assert_allclose(t, T_k, rtol=0, atol=1e-16)
    assert abs(fw.max_accel(A, t) - accel_k) <= 1e-8 + 1e-9 * accel_k
    assert klipper_section(fw.config_text("klipper", {"x": fw.Pick(s, freq, damping, 1e3)})) \
        ["shaper_type_x"] == shaper_type


def test_klipper_parameterised_refusals_are_klippers():
    """Klipper raises ShaperError for n < 3, t >= (n-1)/2 and negative amplitudes
    (mzv(n=3, t=0.2)); mzv(n=3, t=0.75) is its plain mzv."""
    raises("n", fw.klipper_mzv, 2, 0.5)
    raises("t", fw.klipper_mzv, 4, 1.5)
    raises("t", fw.klipper_mzv, 3, 0.2)
    raises("t", fw.klipper_mzv, 4, -1.0)
    raises("v_tol", fw.klipper_ei, 1.0)
    raises("v_tol", fw.klipper_ei, 1e-9)
    A, t = fw.klipper_mzv(3, 0.75).impulses(52.0, 0.2)
    B, u = fw.by_name("klipper", "mzv").impulses(52.0, 0.2)
    np.testing.assert_allclose(A, B, rtol=0, atol=1e-15)
    np.testing.assert_allclose(t, u, rtol=0, atol=1e-18)
