# SPDX-License-Identifier: Apache-2.0
"""Firmware shaper definitions (calibrate.firmware): each firmware's impulses against its own
numbers and against closed forms, Klipper's max_accel rule, and the configuration text."""
from __future__ import annotations

import math

import numpy as np
import pytest

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
