# SPDX-License-Identifier: Apache-2.0
"""The tuning loop's remembered impulses and ZV spans are the reference design's, bit for bit."""
import numpy as np
import pytest

from smoothshaper import shaper
from smoothshaper.calibrate.design_memo import impulses, zv_span
from smoothshaper.reference import shaper_impulses


def _stages():
    rng = np.random.default_rng(7)
    for kind, kw in (("zv", {}), ("mzv", {}), ("zvd", {}), ("ei", {}), ("ei2", {}),
                     ("zvn", {"order": 4}), ("gmzv", {"order": 5, "duration": 1.3})):
        for wn, zeta in zip(rng.uniform(20.0, 2000.0, 20), rng.uniform(0.0, 0.6, 20)):
            yield shaper(kind, wn=float(wn), zeta=float(zeta), **kw)


@pytest.mark.parametrize("stage", list(_stages()), ids=lambda s: f"{s.kind}-{s.wn:.0f}-{s.zeta:.3f}")
def test_same_as_reference(stage):
    A, t = impulses(stage)
    A_ref, t_ref = shaper_impulses(stage)
    np.testing.assert_array_equal(A, A_ref)
    np.testing.assert_array_equal(t, t_ref)
    assert impulses(stage) is impulses(stage)            # one computation per stage
    assert not A.flags.writeable and not t.flags.writeable
    assert zv_span(stage) == float(shaper_impulses(stage.with_(kind="zv"))[1][-1])
