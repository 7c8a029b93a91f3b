# SPDX-License-Identifier: Apache-2.0
"""calibrate.peaks finds the peaks, prominences, bases and widths scipy.signal finds, exactly."""
import numpy as np
import pytest
import scipy.signal

from smoothshaper.calibrate.peaks import find_peaks, peak_widths


def _curves():
    rng = np.random.default_rng(4)
    yield rng.normal(size=500)                                   # noise: many small peaks
    yield np.round(rng.normal(size=400) * 3) / 3                 # quantised: flat tops
    x = np.linspace(0, 10, 2000)
    yield np.log10(1 / ((1 - (x / 4) ** 2) ** 2 + (0.05 * x) ** 2) + 1e-3 * rng.random(2000))
    yield np.r_[np.ones(5), 2, 2, 2, 1, 3, 3, 0, 0, 5]           # plateaus, flat start
    yield np.r_[0.0, 1.0, 1.0, 1.0]                              # a plateau up to the end
    yield np.zeros(7)
    yield np.array([1.0, 2.0])


@pytest.mark.parametrize("i", range(7))
@pytest.mark.parametrize("prominence", [0.0, 0.05, 0.5])
def test_same_as_scipy(i, prominence):
    x = list(_curves())[i]
    pk, props = find_peaks(x, prominence=prominence)
    ref, ref_props = scipy.signal.find_peaks(x, prominence=prominence)
    np.testing.assert_array_equal(pk, ref)
    np.testing.assert_array_equal(props["prominences"], ref_props["prominences"])
    np.testing.assert_array_equal(props["left_bases"], ref_props["left_bases"])
    np.testing.assert_array_equal(props["right_bases"], ref_props["right_bases"])


@pytest.mark.parametrize("i", range(7))
@pytest.mark.parametrize("rel_height", [0.0, 0.5, 1.0])
def test_widths_same_as_scipy(i, rel_height):
    x = list(_curves())[i]
    pk, props = find_peaks(x, prominence=0.0)
    data = (props["prominences"], props["left_bases"], props["right_bases"])
    ref = scipy.signal.peak_widths(x, pk, rel_height=rel_height, prominence_data=data)[0]
    np.testing.assert_array_equal(peak_widths(x, pk, rel_height, data), ref)
