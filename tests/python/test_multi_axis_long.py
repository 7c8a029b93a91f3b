# SPDX-License-Identifier: Apache-2.0
"""Multi-axis generator on long moves (1e3 to 1e5 s at Ts = 1 ms), double and float, both sync
modes: windows of samples around every breakpoint, reached through a saved state (it carries
each move's sample count), keep every limit to the rounding of the positions, and a
phase-synchronised move arrives on the sample of its time-optimal duration.

The rule is the single-axis generator's: with u the unit roundoff of the build (float 2^-24,
double 2^-53) and Q the largest |q| of the axis's move, each sample carries at most 8 u Q of
rounding, so |d^i q| / Ts^i <= L_i (1 + 1e-9) + 2^i 8 u Q / Ts^i; the reported v, a, j stay
within (1 + 32 u) of their limits (the arrival's rounding onto the grid, up to 8 u of the
cruise velocity, and the roundings of the plan and of the evaluation). Before each phase was evaluated by its own time, a float move
of 1000 s had |dq|/Ts up to 8.7 vmax (770 vmax at 1e5 s)."""
import numpy as np
import pytest

from smoothshaper.reference.multi_axis import phase_duration
from smoothshaper.trajectory import MultiAxisGenerator

IDENTITY = 7 + 6 * 8   # SMS_MULTI_IDENTITY_COUNT = 7 + 6 SMS_MULTI_MAX_AXES
AXIS_FIELDS = 5
MOVE_FIELDS = 12  # T1, rho1, tau, T2, rho2, off, seen, k, k_end, active, pending, refused
WIN = 1000
UNIT = {"double": 2.0 ** -53, "float": 2.0 ** -24}


def _move_fields(state, axes, group):
    return IDENTITY + AXIS_FIELDS * axes + MOVE_FIELDS * group


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("sync", ["phase", "independent"])
@pytest.mark.parametrize("T", [1.3e3, 2.7e4, 1.1e5])
def test_long_move_keeps_limits(precision, sync, T):
    real = np.float32 if precision == "float" else np.float64
    vmax = np.array([2.5, 0.75, 40.0], dtype=real).astype(float)
    amax = np.array([30.0, 2.0, 900.0], dtype=real).astype(float)
    jmax = np.array([500.0, 60.0, 5e4], dtype=real).astype(float)
    Ts = float(real(1e-3))
    start = np.array([3.0, -7.5, 1.25])
    target = (start + np.array([1.0, -0.6, 0.3]) * vmax * T).astype(real).astype(float)
    Q = np.maximum(np.abs(start), np.abs(target))
    u = UNIT[precision]
    gen = MultiAxisGenerator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, sync=sync, q0=start,
                             precision=precision)
    gen.process(target[None, :])
    assert gen.dropped == 0 and gen.busy
    saved = gen.get_state()
    groups = 1 if sync == "phase" else 3
    fields = [saved[_move_fields(saved, 3, i):][:MOVE_FIELDS] for i in range(groups)]
    if sync == "phase":
        n = phase_duration(target - start, vmax=vmax, amax=amax, jmax=jmax) / Ts
        k_end = fields[0][8]
        assert n - 16 * u * n <= k_end <= n + 1 + 16 * u * n
    L = np.stack([vmax, amax, jmax])  # (3, axes)
    for w in range(5):
        state = saved.copy()
        for i, f in enumerate(fields):
            T1, T2, k_end = f[0], f[3], f[8]
            k0 = [1, T1 / Ts - WIN / 2, k_end / 2, k_end - T2 / Ts - WIN / 2, k_end - WIN + 50][w]
            k0 = int(min(max(k0, 1), k_end - 1))
            state[_move_fields(state, 3, i) + 7] = k0 - 1  # the next sample is k0
        gen.set_state(state)
        out = gen.process(np.tile(target, (WIN, 1)))
        reported = np.abs(out[:, :, 1:]) / L.T[None, :, :]
        assert reported.max() <= 1 + 32 * u, reported.max()
        q = out[:, :, 0]
        for order in (1, 2, 3):
            d = np.abs(np.diff(q, n=order, axis=0)) / Ts ** order
            rounding = 2 ** order * 8 * u * Q / Ts ** order
            ratio = (d - rounding) / L[order - 1]
            assert ratio.max() <= 1 + 1e-9, (w, order, ratio.max())
        if w == 4:  # arrived: exactly on the target, at rest
            assert np.array_equal(out[-1, :, 0], target) and not out[-1, :, 1:].any()
