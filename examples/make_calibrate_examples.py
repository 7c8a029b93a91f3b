# SPDX-License-Identifier: Apache-2.0
"""Regenerate the resonance examples that `smoothshaper calibrate` reads.

Run from the repository's root: ``python examples/make_calibrate_examples.py``. Both files are
synthetic (``smoothshaper.calibrate.synthetic``: exact simulation of known modes under a
frequency sweep, 30 dB signal-to-noise ratio, fixed seeds), so the modes calibrate should find
are known:

* ``resonance_xy.csv``: a raw accelerometer log (``#time,accel_x,accel_y``, 1 kHz with 1 %
  time-stamp jitter, 8 s); x has one mode at 42 Hz (zeta 0.06), y two at 33 Hz (zeta 0.04) and
  68 Hz (zeta 0.07). Both columns share x's time stamps.
* ``resonance_psd.csv``: a PSD table as a firmware tool writes it (``freq,psd_x,psd_y,psd_xyz``,
  Welch estimates of 30 s at 3.2 kHz, up to 200 Hz); x has one mode at 47 Hz (zeta 0.05), y two
  at 31 Hz (zeta 0.06) and 58 Hz (zeta 0.05).

``decay.csv`` (a free decay for ``smoothshaper identify``) is not made here.
"""
import math

import numpy as np

from smoothshaper.calibrate import synthetic
from smoothshaper.calibrate.modes import welch

TWO_PI = 2 * math.pi


def main() -> None:
    fs = 1000.0
    tx, ax = synthetic.resonance_record([(TWO_PI * 42.0, 0.06)], fs=fs, T=8.0, snr_db=30,
                                        seed=11, axes=1, offsets=(0,))
    _, ay = synthetic.resonance_record([(TWO_PI * 33.0, 0.04), (TWO_PI * 68.0, 0.07)], fs=fs,
                                       T=8.0, snr_db=30, seed=12, axes=1, offsets=(0,))
    np.savetxt("examples/resonance_xy.csv", np.c_[tx, ax[:, 0], ay[:, 0]], delimiter=",",
               header="time,accel_x,accel_y", comments="#", fmt=["%.6f", "%.2f", "%.2f"])

    columns = []
    for modes, seed in (([(TWO_PI * 47.0, 0.05)], 21),
                        ([(TWO_PI * 31.0, 0.06), (TWO_PI * 58.0, 0.05)], 22)):
        _, a = synthetic.resonance_record(modes, fs=3200.0, T=30.0, snr_db=30, seed=seed,
                                          axes=1, offsets=(0,))
        spectrum = welch(a[:, 0], 1 / 3200.0)
        columns.append(spectrum.P)
    f = spectrum.f
    keep = (f > 0) & (f <= 200)
    np.savetxt("examples/resonance_psd.csv",
               np.c_[f[keep], columns[0][keep], columns[1][keep], (columns[0] + columns[1])[keep]],
               delimiter=",", header="freq,psd_x,psd_y,psd_xyz", comments="", fmt="%.6g")


if __name__ == "__main__":
    main()
