"""A segment's start, and a located start, in one compiled call (spatialkin.tracing.march.segments.segment_start,
start.locate_on_curve; kernels.restart).

Oracle: the same steps taken one by one from Python (segments.charts_at, curvature_vector, charts_at along the
curvature vector, segments.project_state): the same charts, state, point and tangent, bit for bit (tolerance 0:
the same kernels in the same order), at points along traced curves of re-charting (sphere) and non-re-charting
pairs, in both directions of travel, from states nudged off the curve. The same for a start located on the curve
(start.locate_on_curve on kernels.restart.locate) against its steps taken one by one.
"""
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.march import curve as kc
from spatialkin.tracing.march.segments import charts_at, project_state, segment_start
from spatialkin.geometry.traits import traits
from spatialkin.tracing.march.trace import make_settings

#: The kinds checked: spheres (re-charted) against each other kind, and pairs that keep their charts.
KINDS = ("sphere-cylinder", "sphere-cone", "sphere-torus", "cylinder-torus", "torus-torus", "plane-torus")
#: States nudged off the curve by this (relative to the scale), so that the projection has work to do.
NUDGE = 1e-6
#: Points checked along each curve.
SAMPLES = 7


def curvature_vector(y, a, b):
    """C'' (3,) of the curve at the state y (charts a, b), or None at a singular point (read from Python, one call
    of kernels.curve.curve_derivatives)."""
    dy, ddy, d1, d2 = np.empty(4), np.empty(4), np.empty(3), np.empty(3)
    return d2 if kc.curve_derivatives(np.ascontiguousarray(y, dtype=float), a, b, 1.0, dy, ddy, d1, d2) else None


def python_start(a_user, b_user, point, direction, y_prev, settings):
    """The oracle: a segment's start as separate Python steps (charts_at, the curvature vector, project_state)."""
    a, b, y = charts_at(a_user, b_user, point, direction, y_prev)
    if traits(a_user).recharts or traits(b_user).recharts:
        bend = curvature_vector(y, a, b)
        if bend is not None:
            a, b, y = charts_at(a_user, b_user, point, direction, y, bend)
    y, p, t, ok = project_state(y, a, b, settings)
    return a, b, y, p, t, ok


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_segment_start_matches_python_steps(kind, order):
    cases = {k: (a, b) for k, a, b in pair_kind_cases()}
    a, b = cases[kind] if order == "ab" else cases[kind][::-1]
    settings = make_settings(a, b, 1e-10, "compiled", 1e-10, None, None, 1e-7, 1.0, True,
                             np.concatenate([a.frame.origin, b.frame.origin]))
    recharts = (traits(a).recharts, traits(b).recharts)
    curves = [c for c in sk.intersect(a, b) if len(c.points) > 1]
    assert curves
    rng = np.random.default_rng(7)
    checked = 0
    for curve in curves:
        for k in np.linspace(0, len(curve.points) - 1, SAMPLES).astype(int):
            y_prev = curve.params[k] + NUDGE * rng.standard_normal(4)
            point = curve.points[k] + NUDGE * settings.scale * rng.standard_normal(3)
            tangent = curve.tangent(curve.s[k])
            for sign in (1.0, -1.0):
                want = python_start(a.data, b.data, point, sign * tangent, y_prev, settings)
                got = segment_start(a.data, b.data, recharts, point, sign * tangent, y_prev, settings)
                for w, g in zip(want[:2], got[:2]):
                    assert np.array_equal(w, g)
                    assert (w is a.data or w is b.data) == (g is a.data or g is b.data)
                    assert not g.flags.writeable
                for w, g in zip(want[2:5], got[2:5]):
                    np.testing.assert_array_equal(g, w)
                assert want[5] == got[5]
                checked += 1
    assert checked >= 2 * SAMPLES


def python_locate(a, b, guess, gap_tol, y_guess=None):
    """The oracle: start.locate_on_curve's steps as separate Python calls ((point, y_user) or None)."""
    from spatialkin.kernels.march import curve as kc
    from spatialkin.tracing.march.segments import NEWTON_MAX_ITER
    point = np.asarray(guess, dtype=float).copy()
    a_chart, b_chart, y = charts_at(a.data, b.data, point, np.zeros(3), y_guess)
    iters = kc.project_to_curve(y, a_chart, b_chart, point.copy(), np.zeros(3), gap_tol, NEWTON_MAX_ITER)
    p1, t = np.empty(3), np.empty(3)
    kc.curve_frame(y, a_chart, b_chart, p1, t)
    if iters < 0 or not np.all(np.isfinite(p1)):
        return None
    y_user = y.copy()
    for k, surf in enumerate((a, b)):
        if traits(surf).recharts:
            y_user[2 * k:2 * k + 2] = surf.parameters(p1)
    return p1, y_user


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_locate_matches_python_steps(kind, order):
    """locate_on_curve (kernels.restart.locate) against its former steps, bit for bit, from points near the curve
    with and without a parameter guess, and from a point far from it (both fail, or both give the same)."""
    from spatialkin.tracing.march.start import locate_on_curve
    from spatialkin.tracing.curve.result import TracingError
    cases = {k: (a, b) for k, a, b in pair_kind_cases()}
    a, b = cases[kind] if order == "ab" else cases[kind][::-1]
    gap_tol = 1e-12
    rng = np.random.default_rng(5)
    curve = sk.intersect(a, b)[0]
    for k in np.linspace(0, len(curve.points) - 1, SAMPLES).astype(int):
        guess = curve.points[k] + 1e-3 * rng.standard_normal(3)
        for y_guess in (None, curve.params[k] + 1e-3 * rng.standard_normal(4)):
            want = python_locate(a, b, guess, gap_tol, y_guess)
            got = locate_on_curve(a, b, guess, gap_tol, y_guess)
            np.testing.assert_array_equal(got[0], want[0])
            np.testing.assert_array_equal(got[1], want[1])
    far = 1e3 * (np.abs(curve.points).max() + 1.0) * np.ones(3)
    want = python_locate(a, b, far, gap_tol)
    try:
        got = locate_on_curve(a, b, far, gap_tol)
    except TracingError:
        assert want is None
    else:
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])
