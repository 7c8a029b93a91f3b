# SPDX-License-Identifier: Apache-2.0
"""The synthetic campaign of calibrate against the established tool's pick (test helper).

Each draw is one record of a category of :data:`smoothshaper.calibrate.synthetic.CATEGORIES`
with its seed (the seed perturbs the modes and draws the noise, jitter, gaps): the record is
written as Klipper writes a raw resonance test (``raw_data_x_*.csv``, ``#time,accel_x,...``),
the established tool's pick is computed on its own PSD of that file (:mod:`klipper_pick`), and
``calibrate.run`` recommends a filter no longer than that pick. Both are scored on the true
plant by :func:`synthetic.true_remaining` (the true modes, their energies in the test's
normalised spectrum). A draw is a *win* when ours leaves no more than the established pick, and
*covered* when the stated +-3 sd range of our pick holds the true value. Nothing of calibrate's
own estimate enters the truth.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from smoothshaper import calibrate
from smoothshaper.calibrate import synthetic as syn
from smoothshaper.calibrate.candidates import candidate_taps

import klipper_pick


@dataclass
class Draw:
    category: str
    seed: int
    ours: float                 # [%] on the true plant
    theirs: float               # [%] the established pick on the true plant
    low: float                  # stated +-3 sd range [%]
    high: float
    name: str                   # our pick
    pick: str                   # the established pick
    ranked_by: str
    modes: list                 # identified (f Hz, zeta)
    truth: list                 # true (f Hz, zeta, energy)

    @property
    def win(self) -> bool:
        return self.ours <= self.theirs + 1e-9

    @property
    def covered(self) -> bool:
        return self.low <= self.ours <= self.high

    @property
    def relative_width(self) -> float:
        """The stated range's width over the true value (a range wide enough to hold anything
        is no answer)."""
        return (self.high - self.low) / max(self.ours, 1e-12)

    def line(self) -> str:
        return (f"{self.category:30s} {self.seed:2d} established {self.pick:16s} "
                f"{self.theirs:7.3f} % | ours {self.name:16s} {self.ours:7.3f} % "
                f"[{self.low:.3g}, {self.high:.3g}] by {self.ranked_by:17s} "
                f"{'win ' if self.win else 'LOSS'} {'covered' if self.covered else 'MISSED'} "
                f"modes {[(round(f, 1), round(z, 3)) for f, z in self.modes]} true "
                f"{[(round(f, 1), round(z, 3)) for f, z, _ in self.truth]}")


def draw(category: str, seed: int, directory: str, fs: float = 1600.0, **run_kw) -> Draw:
    t, A, truth, shift = syn.category_record(category, seed, fs=fs)
    path = os.path.join(directory, f"raw_data_x_{seed}.csv")
    syn.write_csv(path, [t, A[:, 0], A[:, 1], A[:, 2]], ["time", "accel_x", "accel_y",
                                                        "accel_z"], fmt="%.6f")
    pick = klipper_pick.best_shaper(klipper_pick.load(path))
    cal = calibrate.run([path], max_delay=pick["duration"], **run_kw)
    res = cal.axes[0]
    c = res.recommended
    assert c is not None and c.length <= pick["duration"] * (1 + 1e-9), (category, seed)
    Ts = cal.reference.Ts
    if c.firmware is not None:
        Ai, ti = c.firmware[0].impulses(c.firmware[1], c.firmware[2])
    else:
        h = candidate_taps(c, Ts)
        Ai, ti = h, np.arange(h.size) * Ts
    ours = syn.true_remaining(Ai, ti, truth, shift)
    theirs = syn.true_remaining(pick["A"], pick["T"], truth, shift)
    lo, hi = c.vibration_range
    # the range is stated with its own value (the plant estimate) and holds it
    assert lo * (1 - 1e-9) <= c.vibration_estimate <= hi * (1 + 1e-9), (category, seed, c.name)
    return Draw(category, seed, ours, theirs, lo, hi, c.name,
                f"{pick['name']}@{pick['freq']:.1f}", res.ranked_by,
                [(m.f_hz, m.zeta) for m in res.modes], truth)


def run(seeds, directory: str, fs: float = 1600.0, categories=None, verbose=True,
        **run_kw) -> list[Draw]:
    out = []
    for name in categories or syn.CATEGORIES:
        for seed in seeds:
            d = draw(name, seed, directory, fs, **run_kw)
            if verbose:
                print(d.line(), flush=True)
            out.append(d)
    return out


def table(draws) -> str:
    """Wins, coverage and the median width of the stated ranges relative to the true value,
    per category and over all draws."""
    rows = [f"{'category':30s} {'wins':>7s} {'covered':>8s} {'width/true':>10s}"]
    names = list(dict.fromkeys(d.category for d in draws))
    for name in names + ["all"]:
        ds = [d for d in draws if name in ("all", d.category)]
        rows.append(f"{name:30s} {sum(d.win for d in ds):3d}/{len(ds):<3d} "
                    f"{sum(d.covered for d in ds):4d}/{len(ds):<3d} "
                    f"{float(np.median([d.relative_width for d in ds])):10.3g}")
    return "\n".join(rows)
