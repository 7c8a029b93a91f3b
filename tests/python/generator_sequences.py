# SPDX-License-Identifier: Apache-2.0
"""Per-sample target sequences for the generator's tests against the NumPy reference.

``sequence`` draws blocks of targets of every kind (position, velocity, stop), each held 1 to
150 samples, a third of them with a minimum duration of up to 0.4 s; ``pad`` appends a held
position target at rest so that every run ends landed on it.
"""
from __future__ import annotations

import numpy as np

from smoothshaper.bench import targets as bt


def sequence(rng, n_blocks, vmax=1.0, amax=10.0, jmax=100.0, vmin=None, amin=None,
             profile="polynomial"):
    """(position, velocity, acceleration, interface, stop, minimum_duration) per sample.

    Target states are drawn within the bounds ([vmin, vmax], [amin, amax] when given); the
    trigonometric profile takes position targets at rest, velocity targets at a = 0 and no
    minimum duration."""
    pos, vel, acc, itf, stop, tmin = [], [], [], [], [], []
    for _ in range(n_blocks):
        k = int(rng.integers(1, 150))
        kind = rng.choice(3, p=[0.55, 0.35, 0.10])
        if vmin is None and amin is None:
            v, a = bt._state(rng, vmax, amax, jmax, True)
        else:
            v, a = bt._state(rng, vmax, amax, jmax, True, vmin, amin)
        if profile == "trigonometric":
            a, v = 0.0, (0.0 if kind == 0 else v)
        pos += [rng.uniform(-2, 2)] * k
        vel += [v] * k
        acc += [a] * k
        itf += ["velocity" if kind == 1 else "position"] * k
        stop += [kind == 2] * k
        stretch = profile != "trigonometric" and rng.random() < 1 / 3
        tmin += [rng.uniform(0, 0.4) if stretch else 0.0] * k
    return (np.array(pos), np.array(vel), np.array(acc), np.array(itf), np.array(stop),
            np.array(tmin))


def pad(seq, n, position):
    """``seq`` (as from ``sequence``) followed by n samples of a position target at rest."""
    pos, vel, acc, itf, stop, tmin = seq
    return (np.r_[pos, np.full(n, position)], np.r_[vel, np.zeros(n)],
            np.r_[acc, np.zeros(n)], np.r_[itf, ["position"] * n],
            np.r_[stop, np.zeros(n, bool)], np.r_[tmin, np.zeros(n)])
