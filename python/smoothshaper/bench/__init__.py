# SPDX-License-Identifier: Apache-2.0
"""Benchmarks: figures to read, never timed asserts.

* ``python -m smoothshaper.bench``: every path of the library next to what it replaces, the
  tables of ``docs/benchmarks.md`` (:mod:`smoothshaper.bench.suite`, re-exported here);
* ``python -m smoothshaper.bench.trajectory``: the online generator and the kinematic design
  against ruckig, arrival times and multi-axis synchronisation;
* ``python -m smoothshaper.bench.grid_price``: what designing a kinematic chain on the sample
  grid costs, in samples (docs/sampled-limits.md);
* ``python -m smoothshaper.bench.targets``: the single-axis generator against ruckig from
  random states to every kind of target, one campaign per feature (docs/design.md).
"""
from .suite import (C_ROWS, C_STEP_ROWS, FOLLOW_ROWS, ROOT, SPEED_BENCH, Table, __all__,  # noqa: F401
                    c_tables, fmu_state_load_table, fmu_table, HAND_WRITTEN, interleaved,
                    kinematic_call_table, kinematic_parts, main, memory_tables, python_tables,
                    run_c_bench, STATE_LOAD_BENCH, trajectory_table, UNION_STAGE_BYTES)
