"""The stored points of a traced curve in one compiled call (spatialkin.tracing.march.trace._corrected on
spatialkin.kernels.curve.stored.corrected_spans).

Oracle: the same work span by span from Python (corrected_many per span, result.user_params, a numpy unwrap_turns), on
the very arguments sk.intersect hands _corrected for re-charting (sphere) and non-re-charting pairs, both argument
orders: the same points, parameters and gaps, bit for bit (tolerance 0: the same kernels and operations in the same
order). The compiled unwrap_turns against the numpy one on angles with jumps of many turns, also bit for bit.
"""
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.march import curve as kc
from spatialkin.kernels.curve import stored as kst
from spatialkin.tracing.march import trace as tr
from spatialkin.tracing.curve.result import user_params
from spatialkin.tracing.march.segments import NEWTON_MAX_ITER
from spatialkin.geometry.traits import traits

#: Pairs checked: spheres (re-charted) and pairs that keep their charts.
KINDS = ("sphere-cylinder", "sphere-torus", "sphere-cone", "cylinder-cylinder", "cone-cone", "torus-torus")
#: Of those, the pairs traced in several spans (the sphere re-charted on the way).
SEVERAL_SPANS = ("sphere-cylinder", "sphere-torus")


def python_corrected(a, b, y_all, span_of, spans, settings):
    """The oracle: the spans corrected one by one from Python, one compiled call and user_params per span."""
    points = np.empty((len(y_all), 3))
    params = np.empty((len(y_all), 4))
    raw_gap = np.empty(len(y_all))
    cuts = [0] + (np.flatnonzero(np.diff(span_of)) + 1).tolist() + [len(span_of)]
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        seg = spans[span_of[lo]].seg
        y = y_all[lo:hi].copy()
        kc.corrected_many(y, seg.a, seg.b, seg.normal, settings.gap_tol, NEWTON_MAX_ITER, points[lo:hi],
                          raw_gap[lo:hi])
        params[lo:hi] = user_params((a, b), y, points[lo:hi], seg.a, seg.b)
    for k, surf in enumerate((a, b)):
        if traits(surf).recharts:
            unwrap_turns(params[:, 2 * k])
    return points, params, raw_gap


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_corrected_matches_span_by_span(kind, order, monkeypatch):
    cases = {k: (a, b) for k, a, b in pair_kind_cases()}
    a, b = cases[kind] if order == "ab" else cases[kind][::-1]
    calls = []
    original = tr._corrected

    def spy(*args):
        calls.append(args)
        return original(*args)

    monkeypatch.setattr(tr, "_corrected", spy)
    sk.intersect(a, b)
    assert calls
    for args in calls:
        got = original(*args)
        want = python_corrected(*args)
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)
    if kind in SEVERAL_SPANS:
        assert any(len(np.unique(args[3])) > 1 for args in calls)      # several spans were checked


def unwrap_turns(u):
    """numpy's: the angles u (N,) in place, whole turns removed from the jumps between neighbours."""
    u[1:] -= 2.0 * np.pi * np.add.accumulate(np.rint((u[1:] - u[:-1]) / (2.0 * np.pi)))


def test_unwrap_turns_matches_numpy():
    rng = np.random.default_rng(3)
    u = np.cumsum(rng.uniform(-0.5, 0.5, 400)) + 2 * np.pi * rng.integers(-5, 6, 400)
    want = u.copy()
    unwrap_turns(want)
    got = u.copy()
    kst.unwrap_turns(got)
    np.testing.assert_array_equal(got, want)
    strided = np.stack([u, u]).T.copy()
    kst.unwrap_turns(strided[:, 1])
    np.testing.assert_array_equal(strided[:, 1], want)
    np.testing.assert_array_equal(strided[:, 0], u)
