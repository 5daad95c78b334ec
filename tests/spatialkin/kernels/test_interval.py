"""Interval kernels: every enclosure holds the exact values it encloses, and the certified searches isolate the
roots they claim. Oracles: float evaluation of the surfaces and the polynomial implicit functions written here
(numpy, apart from the kernels), and closed-form roots."""
import math

import numpy as np
import pytest
from oracles import random_rotation

import spatialkin as sk
from spatialkin.kernels import interval as ki
from spatialkin.kernels import topology as kt

SAMPLES = 400


def poly_implicit(surface, x):
    """The polynomial implicit function of the surface at global points x (..., 3) (numpy, written apart)."""
    q = (np.asarray(x) - surface.frame.origin) @ surface.frame.rotation
    r2 = q[..., 0] ** 2 + q[..., 1] ** 2
    if isinstance(surface, sk.Plane):
        return q[..., 2]
    if isinstance(surface, sk.Sphere):
        return r2 + q[..., 2] ** 2 - surface.radius ** 2
    if isinstance(surface, sk.Cylinder):
        return r2 - surface.radius ** 2
    if isinstance(surface, sk.Cone):
        return r2 - math.tan(surface.half_angle) ** 2 * q[..., 2] ** 2
    big, small = surface.major_radius, surface.minor_radius
    return (r2 + q[..., 2] ** 2 + big ** 2 - small ** 2) ** 2 - 4 * big ** 2 * r2


def surfaces(rng):
    frame = sk.Frame(rng.uniform(-3, 3, 3), random_rotation(rng))
    return [sk.Torus(2.0, 0.7, frame), sk.Sphere(1.5, frame), sk.Plane(frame), sk.Cylinder(0.8, frame),
            sk.Cone(0.6, frame)]


@pytest.mark.parametrize("seed", range(3))
def test_jet_encloses_values_and_derivatives(seed):
    """g, g_u, g_v, g_uu, g_uv, g_vv over random boxes contain the values at points inside (the derivatives
    from central differences of the numpy oracle, within their truncation error)."""
    rng = np.random.default_rng(seed)
    for s in surfaces(rng):
        for t in surfaces(rng):
            m, c = np.empty((3, 3)), np.empty(3)
            mag = ki.relative_placement(s.data, t.data, m, c)
            pad, cpad = ki.PLACEMENT_ULPS * ki.EPS, ki.PLACEMENT_ULPS * ki.EPS * mag
            u0, v0 = rng.uniform(-3, 3, 2)
            w = 10 ** rng.uniform(-6, 0, 2)
            enc = ki.jet(s.data, t.data, m, c, pad, cpad, (u0, u0 + w[0]), (v0, v0 + w[1]))
            uu = u0 + w[0] * rng.uniform(0, 1, SAMPLES)
            vv = v0 + w[1] * rng.uniform(0, 1, SAMPLES)
            g = poly_implicit(t, s.point(uu, vv))
            size = np.max(np.abs(g)) + 1.0
            assert np.all(g >= enc[0][0] - 1e-12 * size) and np.all(g <= enc[0][1] + 1e-12 * size)
            h = 1e-5
            gu = (poly_implicit(t, s.point(uu + h, vv)) - poly_implicit(t, s.point(uu - h, vv))) / (2 * h)
            gv = (poly_implicit(t, s.point(uu, vv + h)) - poly_implicit(t, s.point(uu, vv - h))) / (2 * h)
            slack = 1e-6 * size
            assert np.all(gu >= enc[1][0] - slack) and np.all(gu <= enc[1][1] + slack)
            assert np.all(gv >= enc[2][0] - slack) and np.all(gv <= enc[2][1] + slack)


def test_outward_rounding_on_trigonometry():
    """cos and sin enclosures contain the extreme values inside the box and the endpoint values."""
    rng = np.random.default_rng(5)
    for _ in range(2000):
        lo = rng.uniform(-10, 10)
        hi = lo + 10 ** rng.uniform(-12, 1)
        x = np.linspace(lo, hi, 50)
        for f, fi in ((np.cos, ki.icos), (np.sin, ki.isin)):
            r = fi((lo, hi))
            assert r[0] <= f(x).min() and f(x).max() <= r[1]
    assert ki.icos((-1e-3, 1e-3))[1] == 1.0 and ki.isin((math.pi / 2 - 1e-9, math.pi / 2 + 1e-9))[1] == 1.0


def test_line_roots_of_a_sphere_cut_by_planes():
    """On the meridian u = 0 of the unit sphere, g = sin v - z0 for the plane z = z0: one verified root at
    v = asin z0 per plane, its box holding the closed form."""
    sphere = sk.Sphere(1.0)
    for z0 in (-0.9, -0.3, 0.0, 0.3, 0.999999):
        plane = sk.Plane(sk.Frame((0, 0, z0)))
        m, c = np.empty((3, 3)), np.empty(3)
        ki.relative_placement(sphere.data, plane.data, m, c)
        out, kinds = np.empty((64, 2)), np.empty(64, dtype=np.int64)
        n, status, _ = kt.line_roots(sphere.data, plane.data, m, c, 1e-15, 1e-15, 0, 0.0, -math.pi / 2,
                                     math.pi / 2, 1e-14, 1e-7, 100_000, out, kinds)
        assert status == kt.DONE and n == 1 and kinds[0] == kt.VERIFIED
        assert out[0, 0] <= math.asin(z0) <= out[0, 1]


def test_extremal_points_of_a_tilted_circle():
    """A plane cutting a torus in one small loop: the system g = 0, d x grad g = 0 has exactly two roots (the
    extremes of d . (u, v) round the loop), each verified in its box; refined, each is on both surfaces and
    grad g is parallel to d there."""
    torus = sk.Torus(3.0, 1.0)
    plane = sk.Plane(sk.Frame((0.0, 0.0, 0.98)))            # a small loop round the top of the tube at u = 0?
    # the plane z = 0.98 cuts the torus in two circles (round the axis): rotate it to make one small loop
    plane = sk.Plane(sk.Frame((4.0 - 0.02, 0.0, 0.0), sk.rotation_about((0, 1, 0), math.pi / 2)))
    m, c = np.empty((3, 3)), np.empty(3)
    ki.relative_placement(torus.data, plane.data, m, c)
    du, dv = math.cos(0.3), math.sin(0.3)
    out, kinds = np.empty((64, 4)), np.empty(64, dtype=np.int64)
    box = np.array([-math.pi + 1.0, math.pi + 1.0, -math.pi + 1.0, math.pi + 1.0])
    n, status, _ = kt.extremal_points(torus.data, plane.data, m, c, 1e-15, 1e-15, du, dv, box,
                                      np.array([1e-13, 1e-13]), 1e6, 100_000, out, kinds)
    assert status == kt.DONE and n == 2 and np.all(kinds[:n] == kt.VERIFIED)
    uv = np.empty(2)
    for rec in out[:n]:
        kt.refine_extremal(torus.data, plane.data, m, c, du, dv, rec, uv)
        p = torus.point(*uv)
        assert plane.distance(p) < 1e-14 and torus.distance(p) < 1e-14
        g = np.empty((1, 6))
        kt.point_values(torus.data, plane.data, m, c, uv.reshape(1, 2), g)
        assert abs(dv * g[0, 1] - du * g[0, 2]) < 1e-12 * np.hypot(g[0, 1], g[0, 2])


@pytest.mark.parametrize("seed", range(3))
def test_second_order_form_encloses_g_and_is_tighter_on_small_boxes(seed):
    """The 2-D search's second-order Taylor form (kernels.topology._second_order) contains g at points inside
    random boxes (the numpy oracle, to its round-off), and on boxes 1e-3 wide its overestimate (width less the
    range of the samples, corners included) is at most half the centred form's, g(m) + grad g(X) . (X - m), and
    0.3 of it in the median, wherever g bends (both fall with the square of the width; the Taylor form's constant
    is smaller), and never larger where g is linear to round-off."""
    rng = np.random.default_rng(100 + seed)
    ratios = []
    for s in surfaces(rng):
        for t in surfaces(rng):
            m, c = np.empty((3, 3)), np.empty(3)
            mag = ki.relative_placement(s.data, t.data, m, c)
            pad, cpad = ki.PLACEMENT_ULPS * ki.EPS, ki.PLACEMENT_ULPS * ki.EPS * mag
            for width in (1.0, 1e-1, 1e-3):
                u0, v0 = rng.uniform(-3, 3, 2)
                U, V = (u0, u0 + width), (v0, v0 + 0.7 * width)
                g, gu, gv, guu, guv, gvv = ki.jet(s.data, t.data, m, c, pad, cpad, U, V)
                mu, mv = 0.5 * (U[0] + U[1]), 0.5 * (V[0] + V[1])
                gm, gum, gvm = ki.jet(s.data, t.data, m, c, pad, cpad, (mu, mu), (mv, mv))[:3]
                dU, dV = ki.isub(U, (mu, mu)), ki.isub(V, (mv, mv))
                form = kt._second_order(gm, gum, gvm, guu, guv, gvv, dU, dV)
                uu = U[0] + (U[1] - U[0]) * np.append(rng.uniform(0, 1, SAMPLES), [0.0, 0.0, 1.0, 1.0])
                vv = V[0] + (V[1] - V[0]) * np.append(rng.uniform(0, 1, SAMPLES), [0.0, 1.0, 0.0, 1.0])
                values = poly_implicit(t, s.point(uu, vv))
                slack = 1e-12 * (np.max(np.abs(values)) + 1.0)
                assert np.all(values >= form[0] - slack) and np.all(values <= form[1] + slack)
                if width == 1e-3:
                    centred = ki.iadd(gm, ki.iadd(ki.imul(gu, dU), ki.imul(gv, dV)))
                    spread = np.ptp(values)
                    over, centred_over = form[1] - form[0] - spread, centred[1] - centred[0] - spread
                    assert over <= centred_over * (1 + 1e-9)
                    if centred_over > 1e-9 * (np.max(np.abs(values)) + 1.0):
                        ratios.append(over / centred_over)
    assert len(ratios) >= 10 and max(ratios) <= 0.5 and np.median(ratios) <= 0.3
