"""trace.in_order: a piece's arc lengths and states in order of s.

Oracle: np.argsort, as trace_from used it (tolerance 0: the same arrays), on strictly increasing, strictly
decreasing, tied and shuffled arc lengths.
"""
import numpy as np
import pytest

from spatialkin.tracing.march.trace import in_order


@pytest.mark.parametrize("case", ["increasing", "decreasing", "ties", "shuffled", "one", "empty"])
def test_in_order_matches_argsort(case):
    rng = np.random.default_rng(11)
    s = np.cumsum(rng.uniform(0.1, 1.0, 50))
    if case == "decreasing":
        s = 100.0 - s
    elif case == "ties":
        s[10:13] = s[10]
    elif case == "shuffled":
        s = rng.permutation(s)
    elif case == "one":
        s = s[:1]
    elif case == "empty":
        s = s[:0]
    y = rng.standard_normal((4, len(s))).T          # a transposed view, as trace_from passes seg.y.T
    order = np.argsort(s)
    got_s, got_y = in_order(s, y)
    np.testing.assert_array_equal(got_s, s[order])
    np.testing.assert_array_equal(got_y, y[order])
