"""A curve that grazes out of a trim and back within one solver step ends at the edge (the compiled method probes
the bounds inside each step, spatialkin.kernels.ode.rk.PROBES), checked on the general path against the closed form
(spatialkin.tracing.closed.forms) and a dense sampling of the true circle; and the step reach that decides where to
probe bounds the dense output."""
import math

import numpy as np
import pytest

import spatialkin as sk
import spatialkin.tracing.components as intersect_module
from spatialkin.kernels.ode import rk

#: A pair found by a random sweep of the closed forms against the tracer: the plane's rectangle cuts the circle
#: four times, and between two of those cuts the circle leaves across v_min for an arc 0.15 long and 2.7e-3 deep
#: (the tracer before the probes, handing edges to DOP853, stepped over it).
PLANE = sk.Plane(sk.Frame([-0.5523879885672389, -0.08928690230167596, 0.12607836007907872],
                          [[-0.060366508727972334, 0.25941428288252233, 0.9638776449635827],
                           [-0.5574749736002153, 0.7922439357508919, -0.24813544703523524],
                           [-0.8279960980786293, -0.5523167353090828, 0.09679197003926343]]),
                 (-1.1486097622476277, 1.7858576728468885), (-0.8542926269204929, 0.11675909175501697))
SPHERE = sk.Sphere(1.072878977396994, sk.Frame([-0.28245991117022656, 0.18465057879768043, 0.29193087797790135],
                                               [[0.9393923273152404, 0.24643500451583844, 0.23835235247535333],
                                                [-0.2612261280947865, 0.9647443149278069, 0.032082967678860236],
                                                [-0.22204271071544449, -0.09240235583444448, 0.9706486693208733]]))
#: The same plane's v_min lowered by this much: the excursion is then 5e-5 deep and about 0.02 long, shorter
#: than a solver step there (about 0.05): without the probes the traced arc runs through it.
SHALLOW = 2.65e-3
#: Lengths agree with the closed form to this (relative), and samples lie inside the trim to this (absolute).
LENGTH_RTOL = 1e-8
TRIM_SLACK = 1e-9


def lowered(plane, by):
    return sk.Plane(plane.frame, plane.u_range, (plane.v_range[0] - by, plane.v_range[1]))


def inside_lengths(plane):
    """Oracle: the circle sampled densely; the lengths of its runs inside the rectangle, sorted."""
    rot, origin = plane.frame.rotation, plane.frame.origin
    d = float(rot[:, 2] @ (SPHERE.frame.origin - origin))
    centre = SPHERE.frame.origin - d * rot[:, 2]
    radius = math.sqrt(SPHERE.radius ** 2 - d * d)
    angles = np.linspace(0.0, 2 * math.pi, 200001)[:-1]
    uv = PLANE.frame.to_local(centre + radius * (np.cos(angles)[:, None] * rot[:, 0]
                                                 + np.sin(angles)[:, None] * rot[:, 1]))[:, :2]
    inside = ((uv[:, 0] >= plane.u_range[0]) & (uv[:, 0] <= plane.u_range[1])
              & (uv[:, 1] >= plane.v_range[0]) & (uv[:, 1] <= plane.v_range[1]))
    start = int(np.argmin(inside))                      # roll so that the first sample is outside
    runs, count = [], 0
    for flag in np.roll(inside, -start):
        if flag:
            count += 1
        elif count:
            runs.append(count)
            count = 0
    if count:
        runs.append(count)
    return sorted(r * 2 * math.pi * radius / len(angles) for r in runs), 2 * math.pi * radius / len(angles)


@pytest.mark.parametrize("depth", ["deep", "shallow"])
@pytest.mark.parametrize("order", ["ab", "ba"])
def test_grazing_excursion_ends_the_traced_arc(monkeypatch, order, depth):
    plane = PLANE if depth == "deep" else lowered(PLANE, SHALLOW)
    pair = (plane, SPHERE) if order == "ab" else (SPHERE, plane)
    exact = sk.intersect(*pair)
    assert [c.status for c in exact] == ["boundary", "boundary"] and exact[0].topology.mode == "closed_form"
    monkeypatch.setattr(intersect_module, "CLOSED_FORMS", False)
    traced = sk.intersect(*pair)
    assert traced[0].topology.mode != "closed_form"
    assert [c.status for c in traced] == ["boundary", "boundary"]
    np.testing.assert_allclose([c.length for c in traced], [c.length for c in exact], rtol=LENGTH_RTOL)
    runs, step = inside_lengths(plane)
    np.testing.assert_allclose(sorted(c.length for c in exact), runs, atol=2 * step)
    np.testing.assert_allclose(sorted(c.length for c in traced), runs, atol=2 * step)
    for c in traced:
        uv = plane.parameters(c.sample(2000))
        assert uv[:, 1].min() >= plane.v_range[0] - TRIM_SLACK
        assert uv[:, 0].min() >= plane.u_range[0] - TRIM_SLACK and uv[:, 0].max() <= plane.u_range[1] + TRIM_SLACK




@pytest.mark.parametrize("columns", [4, 7])
def test_step_reach_and_speed_bound_the_dense_output(columns):
    """step_reach bounds how far the dense output (RK45's 4 columns, DOP853's 7) moves from the step's start and
    step_speed bounds its rate (oracle: the polynomial and its derivative sampled at 401 points, the derivative by
    central differences of dense_state), so that the probes' skipping (keeps_sign) only skips points where a
    1-Lipschitz event cannot have changed sign."""
    rng = np.random.default_rng(7)
    for _ in range(50):
        q = rng.normal(size=(4, columns))
        step = float(rng.uniform(0.01, 2.0))
        y_old = rng.normal(size=4)
        reach, speed = rk.step_reach(step, q), rk.step_speed(q)
        out, lo, hi = np.empty(4), np.empty(4), np.empty(4)
        worst, fastest = 0.0, 0.0
        dt = 1e-6 * step
        for t in np.linspace(dt, step - dt, 401):
            rk.dense_state(0.0, step, y_old, q, t, out)
            worst = max(worst, float(np.max(np.abs(out - y_old))))
            rk.dense_state(0.0, step, y_old, q, t - dt, lo)
            rk.dense_state(0.0, step, y_old, q, t + dt, hi)
            fastest = max(fastest, float(np.max(np.abs(hi - lo))) / (2 * dt))
        assert worst <= reach * (1 + 1e-12)
        assert fastest <= speed * (1 + 1e-6)
        assert fastest >= 0.05 * speed           # (a bound, not a gross one, on random coefficients)


def test_probes_skip_only_where_the_sign_is_kept():
    """keeps_sign: an event of value g at t_from with rate at most speed keeps its sign up to t exactly when
    speed |t - t_from| < |g| (the boundary case counts as possibly zero)."""
    assert rk.keeps_sign(1.0, 0.0, 0.5, 1.9)
    assert not rk.keeps_sign(1.0, 0.0, 0.5, 2.0)
    assert rk.keeps_sign(-1.0, 1.0, 0.5, 1.9)
    assert not rk.keeps_sign(0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize("depth", [1e-7, 1e-9])
def test_grazing_between_two_probes_ends_the_arc(depth):
    """A torus cut by the plane 0.1 up its axis (two circles) with the plane trimmed at u <= r_out - depth: the outer
    circle (radius r_out = R + sqrt(r^2 - 0.01)) leaves the trim for an arc of about 2 sqrt(2 r_out depth), 1e-3
    long at 1e-7, between two probes 3e-3 apart: probes alone would trace a closed loop 1e-7 outside the patch (2000
    tolerances). The probes bisect where neither the event's rate nor its bend (rk.step_bend) excludes a dip
    (rk.hidden_crossing): one arc from edge to edge. Oracle: its length r_out (2 pi - 2 phi), phi = acos((r_out -
    depth) / r_out), within the ends' conditioning (each end on the edge to the tolerance, 1e-10 x the scale 0.3,
    moves along a curve crossing the edge at the angle phi by that over sin phi: 1.5e-7 at 1e-7, 1.5e-6 at 1e-9,
    where the arc outside is 1e-3 and 1e-4 long; measured 8e-9 and 1.8e-8), every dense sample inside the trim to
    1e-10; the inner circle closed, 2 pi r_in to 1e-9."""
    rng = np.random.default_rng(0)
    rot, origin = sk.rotation_about(rng.normal(size=3), rng.uniform(0, 6)), rng.uniform(-1, 1, 3)
    torus = sk.Torus(1.0, 0.3, sk.Frame(origin, rot))
    r_out, r_in = 1.0 + math.sqrt(0.08), 1.0 - math.sqrt(0.08)
    plane = sk.Plane(sk.Frame(origin + 0.1 * rot[:, 2], rot), (-3.0, r_out - depth), (-3.0, 3.0))
    phi = math.acos((r_out - depth) / r_out)
    arc = r_out * (2 * math.pi - 2 * phi)
    for pair in ((torus, plane), (plane, torus)):
        curves = sk.intersect(*pair)
        assert [c.status for c in curves] == ["boundary", "closed"]
        assert abs(curves[0].length - arc) <= 2 * 1e-10 * 0.3 / math.sin(phi)
        assert abs(curves[1].length - 2 * math.pi * r_in) <= 1e-9 * r_in
        assert plane.parameters(curves[0](np.linspace(0.0, curves[0].length, 200001)))[:, 0].max() <= (
            plane.u_range[1] + 1e-10)


@pytest.mark.parametrize("columns", [4, 7])
def test_step_bend_bounds_the_dense_output(columns):
    """step_bend bounds the dense output's second derivative (oracle: second central differences of dense_state at
    401 points), not grossly."""
    rng = np.random.default_rng(8)
    for _ in range(50):
        q = rng.normal(size=(4, columns))
        step = float(rng.uniform(0.01, 2.0))
        y_old = rng.normal(size=4)
        bend = rk.step_bend(step, q)
        mid, lo, hi = np.empty(4), np.empty(4), np.empty(4)
        dt = 1e-4 * step
        worst = 0.0
        for t in np.linspace(dt, step - dt, 401):
            rk.dense_state(0.0, step, y_old, q, t, mid)
            rk.dense_state(0.0, step, y_old, q, t - dt, lo)
            rk.dense_state(0.0, step, y_old, q, t + dt, hi)
            worst = max(worst, float(np.max(np.abs(hi - 2 * mid + lo))) / dt ** 2)
        assert worst <= bend * (1 + 1e-5)
        assert worst >= 0.05 * bend


def test_may_dip_by_hand():
    """may_dip: an event of one sign at both ends of an interval of width w may reach zero inside only when its
    rate allows it (|g_a| + |g_b| <= speed w) and its bend does (min |g| <= bend w^2 / 8)."""
    assert rk.may_dip(1e-3, 2e-3, 1.0, 1.0, 1.0)            # both allow it
    assert not rk.may_dip(0.6, 0.6, 1.0, 1.0, 100.0)        # the rate forbids: 1.2 > 1
    assert not rk.may_dip(0.2, 0.3, 1.0, 1.0, 1.0)          # the bend forbids: 0.2 > 1/8
    assert rk.may_dip(-0.1, -0.3, 1.0, 1.0, 1.0)            # one sign either way
