# SPDX-License-Identifier: Apache-2.0
"""Pure-NumPy reference of every smoothshaper stage and chain (the test oracle).

Written from ``docs/filters.md`` and ``docs/exact-mode.md`` only; it never imports or calls the C
core. Public API:

* ``impulse_response(stage, *, Ts, length=None)``: discrete taps (DC gain 1);
* ``notch_coefficients(stage, *, Ts) -> (b, a)``; ``discrete_transfer(stage, z, *, Ts)``;
* ``shaper_impulses(stage) -> (amplitudes, times)``: the continuous shaper design;
* ``continuous_impulse_response(stage, t)``, ``continuous_transfer(stage, s)``;
* ``filter(stages, x, *, Ts, zi=None)``, ``filter_zi(stages, *, Ts, x0=0.0)``;
* ``switched(stages, x, *, Ts, switch_at, rest=0.0)``: one stage retuned at given samples
  (each input increment through the stage active when it arrived);
* ``scheduled(kind, table, x, schedule, *, Ts, ...)``: a ZV^n shaper whose mode follows a
  schedule through a table (value -> wn, zeta);
* ``lag(stages, *, Ts)`` (samples) and ``delay(x, *, samples, rest=None)``: a chain's DC
  group delay and the fractional delay that pads chains to a common lag;
* closed-form trajectories: ``harmonic_trajectory``, ``damped_harmonic_trajectory``,
  ``exponential_trajectory``, ``rectangular_chain_trajectory``.
"""
from .continuous import continuous_impulse_response, continuous_transfer
from .filtering import discrete_transfer, filter, filter_zi, impulse_response
from .notch import notch_coefficients
from .retune import switched
from .align import delay, lag
from .scheduled import schedule_mode, scheduled
from .shapers import mode_pole, shaper_impulses
from .smoothers import pinned_frequency
from .trajectories import (damped_harmonic_trajectory, exponential_trajectory,
                           harmonic_trajectory, rectangular_chain_trajectory)

__all__ = [
    "impulse_response", "notch_coefficients", "discrete_transfer", "shaper_impulses",
    "mode_pole", "pinned_frequency", "continuous_impulse_response", "continuous_transfer",
    "filter", "filter_zi", "switched", "lag", "delay", "scheduled", "schedule_mode", "harmonic_trajectory", "damped_harmonic_trajectory",
    "exponential_trajectory", "rectangular_chain_trajectory",
]
