"""A segment's start, and a located start, in one compiled call (spatialkin.tracing.march.segments.segment_start,
start.locate_on_curve; kernels.march.restart).

Oracles, at points along traced curves of re-charting (sphere) and non-re-charting pairs, in both directions of
travel, from states nudged off the curve: the surfaces' exact distance functions (the point lies on both within
the Newton target), the surfaces' own evaluation (the state gives the point on both charts; a re-charted sphere's
chart has the start's radial foot point at (0, 0); the user's parameters give it on the user's surfaces), and the
tangent: a small step along it stays on both surfaces to second order.
"""
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.kernels.geometry import surfaces as ks
from spatialkin.tracing.march.segments import segment_start
from spatialkin.geometry.traits import traits
from spatialkin.tracing.march.trace import make_settings

#: The kinds checked: spheres (re-charted) against each other kind, and pairs that keep their charts.
KINDS = ("sphere-cylinder", "sphere-cone", "sphere-torus", "cylinder-torus", "torus-torus", "plane-torus")
#: States nudged off the curve by this (relative to the scale), so that the projection has work to do.
NUDGE = 1e-6
#: Points checked along each curve.
SAMPLES = 7
#: The located point within this many Newton targets (gap_tol) of both surfaces.
ON_SURFACES = 2.0
#: The state's points on both charts, and the user's parameters' points, within this (relative to the scale).
SAME_POINT = 1e-9
#: A step along the tangent (relative to the scale) stays on both surfaces to second order: within
#: TANGENT_CURVATURE x step^2 / scale (a tangent off by an angle alpha leaves them by about step x alpha).
TANGENT_STEP = 1e-5
TANGENT_CURVATURE = 100.0


def on_chart(data, uv):
    out = np.empty((1, 3))
    ks.evaluate(data, np.ascontiguousarray(np.reshape(uv, (1, 2)), dtype=float), out)
    return out[0]


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_segment_start_lands_on_the_curve(kind, order):
    cases = {k: (a, b) for k, a, b in pair_kind_cases()}
    a, b = cases[kind] if order == "ab" else cases[kind][::-1]
    settings = make_settings(a, b, 1e-10, "compiled", 1e-10, None, None, 1e-7, 1.0, True,
                             np.concatenate([a.frame.origin, b.frame.origin]))
    scale = settings.scale
    recharts = (traits(a).recharts, traits(b).recharts)
    curves = [c for c in sk.intersect(a, b) if len(c.points) > 1]
    assert curves
    rng = np.random.default_rng(7)
    checked = 0
    for curve in curves:
        for k in np.linspace(0, len(curve.points) - 1, SAMPLES).astype(int):
            y_prev = curve.params[k] + NUDGE * rng.standard_normal(4)
            point = curve.points[k] + NUDGE * scale * rng.standard_normal(3)
            tangent = curve.tangent(curve.s[k])
            for sign in (1.0, -1.0):
                a_chart, b_chart, y, p, t, ok = segment_start(a.data, b.data, recharts, point, sign * tangent, y_prev,
                                                              settings)
                assert ok
                for surface, chart, rechart in ((a, a_chart, recharts[0]), (b, b_chart, recharts[1])):
                    assert (chart is surface.data) == (not rechart) and not chart.flags.writeable
                    assert surface.distance(p) <= ON_SURFACES * settings.gap_tol
                    if rechart:      # the start, projected radially onto the sphere, is the new chart's (0, 0)
                        centre, radius = surface.frame.origin, surface.radius
                        foot = centre + radius * (point - centre) / np.linalg.norm(point - centre)
                        np.testing.assert_allclose(on_chart(chart, (0.0, 0.0)), foot, rtol=0,
                                                   atol=SAME_POINT * scale)
                np.testing.assert_allclose(on_chart(a_chart, y[:2]), p, rtol=0, atol=SAME_POINT * scale)
                np.testing.assert_allclose(on_chart(b_chart, y[2:]), p, rtol=0, atol=SAME_POINT * scale)
                assert abs(np.linalg.norm(t) - 1.0) < 1e-14
                for step in (TANGENT_STEP * scale, -TANGENT_STEP * scale):
                    assert max(a.distance(p + step * t), b.distance(p + step * t)) <= \
                        TANGENT_CURVATURE * step ** 2 / scale
                assert abs(np.dot(t, tangent)) > 1.0 - 1e-9     # the curve's tangent (N_a x N_b: up to sign)
                checked += 1
    assert checked >= 2 * SAMPLES


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_locate_lands_on_the_curve(kind, order):
    """locate_on_curve (kernels.march.restart.locate) from points near the curve, with and without a parameter
    guess: a point on both surfaces whose user parameters give it on both; from a point far from it, TracingError or
    such a point."""
    from spatialkin.tracing.march.start import locate_on_curve
    from spatialkin.tracing.curve.result import TracingError
    cases = {k: (a, b) for k, a, b in pair_kind_cases()}
    a, b = cases[kind] if order == "ab" else cases[kind][::-1]
    gap_tol = 1e-12
    rng = np.random.default_rng(5)
    curve = sk.intersect(a, b)[0]
    scale = float(np.ptp(curve.points, axis=0).max())
    for k in np.linspace(0, len(curve.points) - 1, SAMPLES).astype(int):
        guess = curve.points[k] + 1e-3 * rng.standard_normal(3)
        for y_guess in (None, curve.params[k] + 1e-3 * rng.standard_normal(4)):
            point, y = locate_on_curve(a, b, guess, gap_tol, y_guess)
            assert max(a.distance(point), b.distance(point)) <= ON_SURFACES * gap_tol * max(1.0, scale)
            np.testing.assert_allclose(a.point(y[0], y[1]), point, rtol=0, atol=SAME_POINT * scale)
            np.testing.assert_allclose(b.point(y[2], y[3]), point, rtol=0, atol=SAME_POINT * scale)
    far = 1e3 * (np.abs(curve.points).max() + 1.0) * np.ones(3)
    try:
        point, _ = locate_on_curve(a, b, far, gap_tol)
    except TracingError:
        return
    assert max(a.distance(point), b.distance(point)) <= ON_SURFACES * gap_tol * max(1.0, scale)


def test_locate_accepts_a_start_already_on_a_loop_near_a_tangency():
    """On a loop 1e-6 of the scale round a plane-torus contact the tangent planes are too nearly parallel for a Newton
    step; a start already on both surfaces within gap_tol is the point itself. Oracle: the loop's points by rays from
    the contact bisected onto both surfaces (tests.oracles.ssi_cases.tiny_family); each located point lies within
    gap_tol of both surfaces (exact distance functions) and within 1e-2 of the loop's radius of its start (both lie
    within round-off over the normals' sine, about 1e-6, of the loop: measured 3e-3; 2 of the 32 starts raised
    TracingError before)."""
    from spatialkin.tracing.march.start import locate_on_curve
    from tests.oracles.ssi_cases import tiny_family
    case = next(c for c in tiny_family(np.random.default_rng(1406)) if c.name == "tiny/plane-torus/1e-06")
    gap_tol = 1e-12 * case.scale
    for start in case.samples:
        point, _ = locate_on_curve(case.a, case.b, start, gap_tol)
        assert max(case.a.distance(point), case.b.distance(point)) <= gap_tol
        assert np.linalg.norm(point - start) <= 1e-2 * 1e-6 * case.scale
