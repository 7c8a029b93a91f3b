# SPDX-License-Identifier: Apache-2.0
"""calibrate with ``--firmware marlin|rrf|prusa`` and no limit: the pick leaves, by the
established tool's own estimate (klipper_pick, its ``_estimate_remaining_vibrations`` on the
PSD it reads), at most 0.1 percentage point more than the established tool's pick, as with
Klipper's own shapers; and a table of several data sets of one axis is scored as that tool
scores it, the worst data set counting.

The records are built here, shaped like the public tables the fault was found on (Klipper
tables of 1.56 Hz bins to 200 Hz, one resonance): a narrow mode near 60 Hz, where Marlin's
trade-off took its classic ``M593 ZV`` (last in its list), which no rule made give way (only a
shaper named ``zv`` did) and whose 8 ms left 0.3 to 0.6 % where the established MZV of 12 ms
left 0.01 to 0.02 %; and a broad mode over a strong low-frequency floor, where Marlin's
trade-off over its own shapers set a budget of 26 ms under the established pick's 34.5 ms and
its pick left 39.7 % against 36.8 %."""
from __future__ import annotations

import functools

import numpy as np
import pytest

from smoothshaper import calibrate
from smoothshaper.calibrate import default_limit as dl

import calibrate_checks
import klipper_pick

#: By the established estimate, the pick may leave at most this much more [percentage points]
#: than the established pick (the acceptance bar; the pick is held to 0.05 of it).
VIBRATION_PP = calibrate_checks.VIBRATION_PP


def _table(path, modes, *, low=0.0, floor=20.0, df=1.5625):
    """A Klipper PSD table (``freq,psd_x,psd_y,psd_z,psd_xyz``) of base-excited modes
    [(f Hz, zeta, weight)] (:func:`_mode`), a low-frequency floor ``low exp(-f/30)`` (the
    test's slow back-and-forth and belt noise) and a deterministic ripple of +-15 % (the
    scatter of a Welch estimate)."""
    f = np.arange(0.0, 200.0, df)
    P = floor + low * np.exp(-f / 30.0)
    for fn, z, w in modes:
        P = P + _mode(f, fn, z, w)
    P = P * (1 + 0.15 * np.sin(1.7 * f))
    path.write_text("freq,psd_x,psd_y,psd_z,psd_xyz\n" + "".join(
        f"{a:.1f},{0.6 * b:.4e},{0.3 * b:.4e},{0.1 * b:.4e},{b:.4e}\n" for a, b in zip(f, P)))
    return path



#: name: (modes, low-frequency floor)
TABLES = {
    "narrow 60 Hz": ([(59.5, 0.06, 1e4)], 0.0),
    "broad 52 Hz on a low floor": ([(52.0, 0.12, 1e4)], 1.5e7),
}


@functools.lru_cache(maxsize=None)
def _established(name, folder):
    """(path, data sets, the established pick) of a table, built once per test session."""
    modes, low = TABLES[name]
    path = _table(folder / f"resonances_x_{name.replace(' ', '_')}.csv", modes, low=low)
    data = klipper_pick.load(path)
    return path, data, klipper_pick.best_shaper(data)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("firmware_budget")


@pytest.mark.parametrize("firmware", ["marlin", "rrf", "prusa"])
@pytest.mark.parametrize("name", list(TABLES))
def test_firmware_pick_as_good_as_the_established(folder, name, firmware):
    """The firmware's budget covers the established pick's length and its pick is held to
    that pick's estimate: at most 0.1 point more (before: +0.5 and +2.9 points with Marlin)."""
    path, data, pick = _established(name, folder)
    cal = calibrate.run([str(path)], firmware=firmware)
    res = cal.axes[0]
    c = res.recommended
    assert c is not None and c.firmware is not None and c.firmware[0].firmware == firmware
    lim = res.default_limit
    assert lim.established is not None
    assert lim.established.shaper == f"klipper {pick['name']}"
    assert lim.max_delay >= pick["duration"] - 1e-12
    if lim.match is not None:        # the firmware's design that matches the established pick
        assert lim.match[4] <= pick["vibrs"] + VIBRATION_PP / 100
        # held to the established pick's estimate, or to the match where that leaves less
        # (0.05: the ranking's tie; 1e-3: the exact filters' length, rounded to Ts)
        assert c.vibration_established <= max(100 * lim.match[4], 100 * pick["vibrs"]) \
            + 0.05 + 1e-3
    ours = calibrate_checks.estimate(c, cal.reference.Ts, data)
    assert ours <= 100 * pick["vibrs"] + VIBRATION_PP, (c.name, ours, 100 * pick["vibrs"])


def test_every_two_impulse_shaper_gives_way_as_a_zv():
    """The rule that makes a ZV pick give way to a shaper leaving 10 % less holds for every
    shaper of the ZV form: both of Marlin's (FT Motion ``ZV`` and classic ``M593 ZV``; only
    the one named ``zv`` did), none of RepRapFirmware's, Prusa's ``ZV`` and Klipper's ``zv``."""
    zv = {f: [s.name for s in dl.trade_off_shapers(f) if dl._is_zv(s)]
          for f in ("klipper", "marlin", "rrf", "prusa")}
    assert zv == {"klipper": ["zv"], "marlin": ["ZV", "M593 ZV"], "rrf": [], "prusa": ["ZV"]}


def _mode(f, fn, z, w):
    """A base-excited mode's PSD under the test's excitation growing with the frequency."""
    r = f / fn
    return w * f * (1 + 4 * z * z * r * r) / ((1 - r * r) ** 2 + (2 * z * r) ** 2)


def test_several_data_sets_scored_by_the_worst(tmp_path):
    """A table of two test points (``freq,point_a,point_b``, Klipper's table of several data
    sets): a strong 42 Hz mode at one point, a weak one and a 68 Hz mode at the other. The
    established tool scores each point on its own and takes the worst; scored on their sum the
    68 Hz mode sits under the floor (a twentieth of the sum's peak) and the sum's pick (an MZV
    of 17 ms) leaves 1.05 % by the established estimate, where the established pick leaves
    0.50 %. Every firmware candidate's established figure is the established estimate, and the
    pick is within 0.1 point of the established pick."""
    f = np.arange(0.0, 200.0, 0.2)
    a = 50.0 + _mode(f, 42.0, 0.05, 1e4)
    b = 50.0 + _mode(f, 42.5, 0.05, 4e2) + _mode(f, 68.0, 0.04, 3e2)
    path = tmp_path / "calibration_data_x_points.csv"
    path.write_text("freq,point_a,point_b\n" + "".join(
        f"{x:.1f},{p:.5e},{q:.5e}\n" for x, p, q in zip(f, a, b)))
    data = klipper_pick.load(path)
    assert len(data) == 2
    pick = klipper_pick.best_shaper(data)
    summed = klipper_pick.best_shaper([klipper_pick.Dataset(f, data[0].psd + data[1].psd)])
    # the fault this guards against: the sum's pick is worse on the worst point
    assert 100 * klipper_pick.remaining(summed["A"], summed["T"], data) > \
        100 * pick["vibrs"] + VIBRATION_PP
    cal = calibrate.run([str(path)], firmware="klipper")
    res = cal.axes[0]
    assert res.datasets == (0, 1)
    calibrate_checks.assert_held_to_pick(res, cal.reference.Ts, data, pick)
