"""Hard cases (ssi-notes): near tangency, crossing branches, parametrisation singularities, scale."""
import functools
import math

import numpy as np
import pytest
from tests.oracles.closed_forms import (HAIR_INSIDE, random_rotation, sphere_distance, torus_distance,
                                       torus_sphere_closed_form, torus_sphere_critical_radii)

import spatialkin as sk

BIG, SMALL, CENTRE = 3.0, 1.0, np.array([1.0, 0.5, 0.7])
RADII = torus_sphere_critical_radii(BIG, SMALL, CENTRE)


def on_both(curve, centre, rho, big=BIG, small=SMALL, origin=np.zeros(3), rot=np.eye(3)):
    """Largest exact distance of the points and of 2000 dense evaluations to torus and sphere."""
    pts = curve.points if curve.length == 0 else np.vstack([curve.points, curve(np.linspace(0, curve.length, 2000))])
    return max(torus_distance((pts - origin) @ rot, big, small).max(), sphere_distance(pts, centre, rho).max())


def test_tiny_loop_just_above_the_first_critical_radius():
    """rho = r1 + 1e-6: a loop of size about 2 sqrt(eps) ~ 2e-3 around the nearest foot point, found and
    traced to 1e-10; its extent matches the closed form per torus angle."""
    rho = RADII[0] + 1e-6
    curves = sk.intersect(sk.Torus(BIG, SMALL), sk.Sphere(rho, sk.Frame(CENTRE)))
    assert len(curves) == 1 and curves[0].closed
    c = curves[0]
    assert 1e-3 < np.ptp(c.points, axis=0).max() < 1e-2
    assert on_both(c, CENTRE, rho) <= 1e-10 * rho
    phi = np.linspace(-np.pi, np.pi, 200001)
    exact, ok = torus_sphere_closed_form(BIG, SMALL, CENTRE, rho, phi)
    assert len(exact) > 0
    assert np.max(c.closest(exact.reshape(-1, 3))[1]) < 1e-9


@pytest.mark.parametrize("which", [0, 3])
def test_contact_point_at_a_critical_radius(which):
    """rho exactly the smallest or largest critical radius: a single point of contact, status 'contact'."""
    rho = RADII[which]
    curves = sk.intersect(sk.Torus(BIG, SMALL), sk.Sphere(rho, sk.Frame(CENTRE)))
    assert len(curves) == 1
    c = curves[0]
    assert c.status == "contact" and c.length == 0 and len(c.points) == 1
    assert on_both(c, CENTRE, rho) < 1e-12


@pytest.mark.parametrize("k", [1, 2])
@pytest.mark.parametrize("delta", [-1e-7, 0.0, 1e-7])
def test_around_a_saddle_radius(k, delta):
    """At a saddle radius the curve is a figure-eight, traced as one closed curve straight through its node
    (passed twice); 1e-7 to one side two loops, to the other one loop; no branch jump (every point and
    dense evaluation on both surfaces, the closed form covered)."""
    rho = RADII[k] + delta
    curves = sk.intersect(sk.Torus(BIG, SMALL), sk.Sphere(rho, sk.Frame(CENTRE)))
    two_loops = (k == 1 and delta > 0) or (k == 2 and delta < 0)
    assert len(curves) == (2 if two_loops else 1)
    for c in curves:
        assert c.closed
        assert on_both(c, CENTRE, rho) <= 1e-10 * BIG
    if delta == 0.0:
        assert len(curves[0].nodes) == 2
        node = curves[0].nodes[0]
        np.testing.assert_allclose(curves[0].nodes[1], node, atol=1e-5)
    exact, _ = torus_sphere_closed_form(BIG, SMALL, CENTRE, rho, np.linspace(-np.pi, np.pi, 721))
    gaps = np.min(np.stack([c.closest(exact.reshape(-1, 3))[1] for c in curves]), axis=0)
    assert gaps.max() < 1e-6       # beside the node the closed form itself is ill-conditioned


def test_sphere_poles_on_the_curve():
    """A plane through the sphere's pole axis: a great circle through both poles, to 1e-12; and a torus-sphere
    loop through the sphere's pole (the sphere's frame turned so)."""
    curves = sk.intersect(sk.Sphere(2.0), sk.Plane(sk.Frame.from_z_axis((0, 0, 0), (1, 0, 0))))
    assert len(curves) == 1 and curves[0].closed
    c = curves[0]
    assert np.abs(c.points[:, 2]).max() > 1.98
    assert abs(c.length - 4 * np.pi) < 1e-9
    pts = c(np.linspace(0, c.length, 4001))
    assert np.abs(np.linalg.norm(pts, axis=1) - 2.0).max() < 1e-12 and np.abs(pts[:, 0]).max() < 1e-12
    loop = sk.intersect(sk.Torus(BIG, SMALL), sk.Sphere(2.5, sk.Frame(CENTRE)))[0]
    pole = loop.points[5]
    turned = sk.Sphere(2.5, sk.Frame.from_z_axis(CENTRE, pole - CENTRE))
    again = sk.intersect(sk.Torus(BIG, SMALL), turned)
    assert len(again) == 1 and abs(again[0].length - loop.length) < 1e-9
    assert on_both(again[0], CENTRE, 2.5) < 1e-12
    assert np.min(np.abs(np.cos(again[0].params[:, 3]))) < 1e-3     # the pole is on the curve


def test_spindle_torus_apex_on_the_curve():
    """A sphere through the upper axis point of a spindle torus (R = 1, r = 2): the curve passes the apex
    (a cone point of the surface), straight through, and stays on both surfaces to 1e-12."""
    apex = np.array([0.0, 0.0, np.sqrt(3.0)])
    centre = np.array([0.4, 1.0, 2.5])
    rho = np.linalg.norm(centre - apex)
    curves = sk.intersect(sk.Torus(1.0, 2.0), sk.Sphere(rho, sk.Frame(centre)))
    through = [c for c in curves if len(c.nodes)]
    assert len(through) == 1 and through[0].closed
    c = through[0]
    assert np.min(np.linalg.norm(c.nodes - apex, axis=1)) < 1e-4
    assert c.closest(apex)[1] < 1e-9
    assert on_both(c, centre, rho, 1.0, 2.0) < 1e-12


def test_horn_torus_cusp():
    """A horn torus (R = r = 1) with a sphere through its cusp (the origin): when the sphere's tangent
    plane there holds the axis and its radius exceeds R the curve runs through the cusp; otherwise the cusp
    is an isolated point of contact. Positions stay on both surfaces to 1e-12.

    The first sphere (centre (1.5, 0, 0), radius 1.5) meets the torus in two tube circles of radius 1 touching at
    the cusp (x^2 + y^2 + z^2 = 3x and = 2 rho give x = 2 rho / 3: two meridian half-planes), 4 pi in all. The
    cusp is an apex proven by the topology stage: the tracer must jump across it (snapped onto it) rather than
    integrate through it. Integrated through, the path turned onto whichever circle the machine's last bits chose: a
    figure-eight passing 4.2e-8 from the cusp on one machine, on another (AMD EPYC with AVX-512) one circle run
    twice, 6 pi in all. The length over each jump is the curve's (Gauss-Legendre), not the chord's (short by 3e-4
    over a jump of 0.19): the total is 4 pi to 1e-9 (4e-11 measured on each circle)."""
    torus = sk.Torus(1.0, 1.0)
    centre = np.array([1.5, 0.0, 0.0])
    curves = sk.intersect(torus, sk.Sphere(1.5, sk.Frame(centre)))
    assert curves and all(c.closed for c in curves)
    assert min(c.closest(np.zeros(3))[1] for c in curves) < 1e-12
    assert abs(sum(c.length for c in curves) - 4 * np.pi) < 1e-9
    for c in curves:        # dense points by arc length across the jump too: chords of 3e-5 match their s to 1e-7
        s = np.linspace(0.0, c.length, 200001)
        assert np.max(np.abs(np.linalg.norm(np.diff(c(s), axis=0), axis=1) / np.diff(s) - 1.0)) < 1e-7
    for c in curves:
        assert on_both(c, centre, 1.5, 1.0, 1.0) < 1e-12
    centre = np.array([0.5, 0.2, 0.3])
    curves = sk.intersect(torus, sk.Sphere(np.linalg.norm(centre), sk.Frame(centre)))
    contacts = [c for c in curves if c.status == "contact"]
    assert len(contacts) == 1 and np.linalg.norm(contacts[0].points[0]) < 1e-12


def test_horn_torus_centre_on_a_coaxial_surface_is_one_contact():
    """A horn torus (R = r = 1) and surfaces about its axis through its centre: the plane z = 0 meets it in the
    circle of radius 2 (4 pi) and the centre alone, the sphere of radius 1 centred at (0, 0, 1) in a circle and the
    centre. The centre is met at both ends of the periodic meridian (v = +-pi): one contact, not two."""
    torus = sk.Torus(1.0, 1.0)
    for other in (sk.Plane(sk.Frame(), (-3.0, 3.0), (-3.0, 3.0)), sk.Sphere(1.0, sk.Frame((0.0, 0.0, 1.0)))):
        for pair in ((torus, other), (other, torus)):
            curves = sk.intersect(*pair)
            contacts = [c for c in curves if c.status == "contact"]
            assert len(contacts) == 1 and np.linalg.norm(contacts[0].points[0]) < 1e-12
            assert [c.closed for c in curves if c.status != "contact"] == [True]
    plane_circle = [c for c in sk.intersect(torus, sk.Plane(sk.Frame(), (-3.0, 3.0), (-3.0, 3.0))) if c.closed]
    assert abs(plane_circle[0].length - 4 * np.pi) < 1e-10 * 4 * np.pi      # (tol 1e-10 of the scale)


def test_scales_from_1e_minus_3_to_1e3_in_one_scene():
    """A torus of major radius 1e3 and tube 1 with a sphere of radius 1e-3 on its tube, and a torus of size
    1e-3 cut by a sphere of radius 1e3: accuracy relative to the small scale (tol 1e-10), or the round-off
    floor of coordinates of size 1e3 (Curve.tolerance)."""
    rng = np.random.default_rng(3)
    rot = random_rotation(rng)
    origin = np.array([5.0, -2.0, 1.0])
    torus = sk.Torus(1e3, 1.0, sk.Frame(origin, rot))
    p, n = torus.point(0.3, 1.1), torus.normal(0.3, 1.1)
    for offset in (2e-4, 0.0):
        sphere = sk.Sphere(1e-3, sk.Frame(p + offset * n))
        curves = sk.intersect(torus, sphere)
        assert len(curves) == 1 and curves[0].closed
        c = curves[0]
        assert 1e-10 * 1e-3 <= c.tolerance <= 64 * np.finfo(float).eps * 1.1e3
        assert on_both(c, sphere.center, 1e-3, 1e3, 1.0, origin, rot) <= c.tolerance
        assert abs(c.length - 2 * np.pi * np.sqrt(1e-6 - offset ** 2)) < 1e-3 * c.length   # nearly a circle
    small = sk.Torus(2e-3, 1e-3, sk.Frame((0, 0, 0), rot))
    centre = rot @ np.array([0.0, 0.001, 1e3 + 0.0005])
    curves = sk.intersect(small, sk.Sphere(1e3, sk.Frame(centre)))
    assert len(curves) == 2
    for c in curves:
        assert c.closed and on_both(c, centre, 1e3, 2e-3, 1e-3, np.zeros(3), rot) <= c.tolerance


def test_no_intersection_and_bad_tolerance():
    torus = sk.Torus(BIG, SMALL)
    assert sk.intersect(torus, sk.Sphere(0.5 * RADII[0], sk.Frame(CENTRE))) == []
    assert sk.intersect(torus, sk.Sphere(1.0, sk.Frame((50.0, 0, 0)))) == []
    for tol in (0.0, -1e-10, np.inf, np.nan):
        with pytest.raises(ValueError, match="tol"):
            sk.intersect(torus, sk.Sphere(2.5, sk.Frame(CENTRE)), tol=tol)


@pytest.mark.parametrize("kind, size", [("horn", (1.0, 1.0)), ("spindle", (0.6, 1.0)), ("ring", (1.0, 0.97)),
                                        ("cone", 0.3), ("cone", 1.2)])
@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_area_element_is_1_lipschitz_in_its_parameter(kind, size, scale):
    """The compiled engine probes the area hand-over inside a step only where a step end is within the step's reach
    of it (kernels.rk.within_reach), which is sound for an event 1-Lipschitz in the state's components: the relative
    area element of a torus (in v, an angle) and of a cone (in v, a length), in its unit for a scene of this scale
    and weighted as the events weigh it (tracing.ivp.area_weight), against the oracle of sampled differences, to
    round-off; and a cone's is the same number for the same scene at every scale (the apex guard means the same
    distance from the apex, relative to the scene)."""
    from spatialkin.kernels.march import curve as kc
    from spatialkin.tracing.march.ivp import area_weight
    from spatialkin.tracing.march.segments import area_flag
    if kind == "cone":
        surface = sk.Cone(size, v_range=(-3.0 * scale, 3.0 * scale))
        v = np.linspace(-3.0, 3.0, 20001) * scale
    else:
        surface = sk.Torus(size[0] * scale, size[1] * scale)
        v = np.linspace(-np.pi, np.pi, 20001)
    unit = area_flag(surface, scale)
    assert unit == (scale if kind == "cone" else 1.0)
    weight = area_weight(unit, 0.0)
    values = np.empty(len(v))
    for i, vi in enumerate(v):
        d = surface.derivatives(0.3, vi)
        values[i] = kc.relative_area(d[1].copy(), d[2].copy(), unit)
    assert np.max(np.abs(np.diff(values * weight)) / np.diff(v)) <= 1.0 + 1e-9
    if kind == "cone":                      # against the scene at scale 1 (written apart: the numpy formula)
        rho = np.abs(v / scale) * math.tan(size)
        cos = math.cos(size)
        expected = np.minimum(rho * cos, 1.0 / np.maximum(rho * cos, 1e-300))
        np.testing.assert_allclose(values, expected, rtol=1e-12, atol=1e-15)


def test_viviani_trimmed_at_its_node():
    """Viviani's curve (a sphere of radius 2r through the axis of a cylinder of radius r) with the cylinder trimmed
    at the height of its node: the upper lobe, from the node to the node. A jump across the node that ignored the
    trim would land beyond it (7.1e-4 r outside); the curve ends at the edge: in either order it lies inside the
    trim to round-off, and its length is the lobe's, 2 r int_0^pi sqrt(1 + cos^2 u) du (scipy.quad), to 1e-9."""
    from scipy.integrate import quad
    r = 0.7
    rot = sk.rotation_about((0.3, 0.5, 1.0), 0.6)
    o = np.array([0.2, -0.1, 0.4])
    sphere = sk.Sphere(2 * r, sk.Frame(o, rot))
    cylinder = sk.Cylinder(r, sk.Frame(o + r * rot[:, 0], rot), v_range=(0.0, 3 * r))
    lobe = 2 * r * quad(lambda u: math.sqrt(1 + math.cos(u) ** 2), 0, math.pi, epsabs=1e-13, epsrel=1e-13)[0]
    for a, b in ((sphere, cylinder), (cylinder, sphere)):
        curves = sk.intersect(a, b)
        assert len(curves) == 1 and curves[0].status == "boundary"
        c = curves[0]
        height = (c(np.linspace(0.0, c.length, 4001)) - cylinder.frame.origin) @ rot[:, 2]
        assert height.min() >= -1e-15 * r
        assert abs(c.length - lobe) <= 1e-9 * lobe
        assert c.max_distance <= 1e-14 * r


def test_a_near_tangent_tiny_loop_is_dense_to_its_closure():
    """A loop of 2.5e-6 where two tori nearly touch (normals 7e-7 apart, a re-measured segment whose closure lies
    past its last step): the dense output runs on through the closing stretch, at speed 1 in s (chords of 201
    evenly spaced samples, the wrap from the last to the first included, within 20% of their spacing: the
    positions are fixed by the doubles to about 4e-10 here; over the last stored step, the distance to the closing
    point is the arc length left), and the length agrees with the 40-digit oracle to the conditioning
    u |x| / sin(normals)."""
    from tests.oracles.mp import loop_length
    from tests.oracles.ssi_cases import all_cases
    case = next(c for c in all_cases() if c.name == "tiny/torus-torus/1e-06")
    curves = sk.intersect(case.a, case.b)
    assert len(curves) == 1 and curves[0].closed
    curve = curves[0]
    s = np.linspace(0.0, curve.length, 201)
    chords = np.linalg.norm(np.diff(curve(s), axis=0), axis=1) / (s[1] - s[0])
    assert np.all((chords > 0.8) & (chords < 1.2)), chords.min()
    # the last stored step: the distance to the closing point falls as the arc length left
    last = np.linspace(curve.s[-2], curve.length, 9)
    left = np.linalg.norm(curve(last) - curve.points[0], axis=1)
    assert np.max(np.abs(left - (curve.length - last))) < 0.1 * (curve.length - curve.s[-2])
    length, _, sine = loop_length(case.a, case.b, curve.points[:-1])
    size = np.max(np.abs(curve.points))
    assert abs(curve.length - length) < 50 * np.finfo(float).eps * size / sine


def cone_loop_length(cone, cylinder):
    """Length of the loop of a cone and a cylinder whose apex lies just outside the cylinder, in closed form: on
    the ruling at angle u the cone point o + v d(u) lies on the cylinder where A v^2 + 2 B v + C = 0 (A, B, C from
    the parts of d(u) and o - c across the cylinder's axis); over the angles where both roots are real and
    positive the larger root traces the loop's far arc and the smaller its turn round the apex; their speeds
    (v' from the implicit equation) integrated by scipy's quad between the zeros of the discriminant."""
    from scipy.integrate import quad
    from scipy.optimize import brentq
    o, e = cone.frame.origin, cone.frame.rotation
    w, k = cylinder.frame.rotation[:, 2], math.tan(cone.half_angle)
    perp = lambda x: x - (x @ w) * w
    r0 = perp(o - cylinder.frame.origin)
    c = r0 @ r0 - cylinder.radius ** 2
    assert c > 0

    def ruling(u):
        return k * (math.cos(u) * e[:, 0] + math.sin(u) * e[:, 1]) + e[:, 2], k * (-math.sin(u) * e[:, 0] +
                                                                                  math.cos(u) * e[:, 1])

    def disc(u):
        dp = perp(ruling(u)[0])
        return (r0 @ dp) ** 2 - (dp @ dp) * c

    def speed(u, sign):
        d, dd = ruling(u)
        dp, dq = perp(d), perp(dd)
        a, b = dp @ dp, r0 @ dp
        v = (-b + sign * math.sqrt(max(b * b - a * c, 0.0))) / a
        dv = -((dp @ dq) * v * v + (r0 @ dq) * v) / (a * v + b)
        return float(np.linalg.norm(dv * d + v * dd))

    u = np.linspace(0.0, 2 * math.pi, 200_001)
    b_sign = np.sign([r0 @ perp(ruling(x)[0]) for x in u])
    turns = u[np.flatnonzero(np.diff(b_sign))]          # where B = 0: the discriminant is negative round them
    lo = brentq(disc, turns[0], turns[0] + 1e-3, xtol=1e-16)
    hi = brentq(disc, turns[1] - 1e-3, turns[1], xtol=1e-16)
    return sum(quad(speed, lo, hi, args=(sign,), limit=2000, epsabs=1e-15, epsrel=1e-14)[0] for sign in (1, -1))


def test_a_loop_passing_a_cone_apex_at_1e_minus_8_closes():
    """A cone whose apex lies 1.4e-8 outside a cylinder: the loop turns round the apex within about 1e-4, and a
    start found beside the apex is carried clear of it first; one closed loop, traced once, its length within
    1e-10 of the closed form and its points within 1e-12 of both surfaces."""
    cone = sk.Cone(0.7637832434889373, sk.Frame(
        (0.3354280402615544, -0.29365620678491766, -0.9012881847000997),
        [(0.6274177514581923, -0.707192150460831, 0.32592365284178354),
         (0.014047707560017594, -0.40820987151491805, -0.9127800187942778),
         (0.7785561168390202, 0.5772728671298866, -0.24618369119051375)]), v_range=(0.0, 1.5))
    cylinder = sk.Cylinder(0.9873193540862184, sk.Frame((0.0, 0.0, 0.0), [
        (0.381845548384125, 0.18647473823977034, 0.9052188404897658),
        (-0.7998228735786244, -0.42410881983885207, 0.42475296330376294),
        (0.4631169917846446, -0.8862047624185423, -0.01279730389715561)]),
        v_range=(-1.3095615035525947, 1.6904384964474053))
    loop, = sk.intersect(cone, cylinder)
    assert loop.closed and loop.status == "closed"
    assert abs(loop.length - cone_loop_length(cone, cylinder)) <= 1e-10
    dense = np.vstack([loop.points, loop(np.linspace(0.0, loop.length, 4001))])
    assert max(cone.distance(dense).max(), cylinder.distance(dense).max()) <= 1e-12


def hair_tori():
    """Two tori (1, 0.4) whose surfaces come within about 1e-12 of touching at two points: there the branches of
    their one loop pass about 6e-6 apart, on either side of a saddle of the level."""
    a = sk.Torus(1.0, 0.4, sk.Frame((-0.04594095932053169, -0.6710148452364172, 0.00970803997920091), [
        (-0.5719573965110676, 0.8097848935702903, -0.1308172875488383),
        (0.44107185332479415, 0.16914805546370748, -0.8813878576072387),
        (-0.6916070826567011, -0.5618161278195922, -0.45391880522940076)]))
    b = sk.Torus(1.0, 0.4, sk.Frame((-0.6575998789053278, 0.02590662362426044, 0.9311213310894169), [
        (0.10053758774982796, -0.35424086878789346, 0.9297341557293914),
        (-0.7662401084873304, -0.6236396527827277, -0.1547568403088003),
        (0.634640283621179, -0.6968407209380333, -0.3341327880465971)]))
    return a, b


def test_tori_a_hair_from_touching_keep_each_branch_past_the_saddles():
    """hair_tori: one closed loop, the same length in both argument orders (within 1e-9), that passes each place
    where the surfaces nearly touch twice, once on each branch: each passage keeps to its own side of the plane
    through the saddle across the branches (oracle: the two passages' points of smallest sine, from 400,001 dense
    samples each refined by 200,001 more, span it; every dense point within 1e-3 of the saddle lies at least a
    third of their gap from it, on the passage's side). A march whose steps are longer than the gap crosses
    between the branches there. A max_length the user asks for is theirs: each direction is traced to it (3 + 3,
    the length re-measured on the curve within 1e-6)."""
    from spatialkin.tracing.curve.curvature import normal_sines
    a, b = hair_tori()
    curve, = sk.intersect(a, b)
    other, = sk.intersect(b, a)
    assert curve.closed and other.closed and abs(curve.length - other.length) <= 1e-9 * curve.length
    s = np.linspace(0.0, curve.length, 400001)
    sine = np.nan_to_num(normal_sines(a, b, np.asarray(curve(s))), nan=1.0)
    minima = [i for i in range(1, len(s) - 1) if sine[i] < 1e-3 and sine[i] <= min(sine[i - 1], sine[i + 1])]
    vertices = []
    for i in minima:
        near = np.linspace(s[i] - 1e-4, s[i] + 1e-4, 200001)
        points = np.asarray(curve(near))
        vertices.append((near, points[np.nanargmin(normal_sines(a, b, points))]))
    assert len(vertices) == 4                                    # two places, each passed twice
    for m, (s_m, p_m) in enumerate(vertices):
        n = min((k for k in range(4) if k != m), key=lambda k: np.linalg.norm(vertices[k][1] - p_m))
        saddle, across = 0.5 * (p_m + vertices[n][1]), p_m - vertices[n][1]
        gap = np.linalg.norm(across)
        assert gap < 1e-5
        side = np.asarray(curve(np.linspace(s_m[100000] - 2e-3, s_m[100000] + 2e-3, 40001)))
        close = np.linalg.norm(side - saddle, axis=1) < 1e-3
        assert close.sum() > 1000 and np.all((side[close] - saddle) @ across / gap >= gap / 3)
    curves = sk.intersect(a, b, max_length=3.0)         # a max_length asked for is the user's: traced to it
    assert curves and all(c.status == "max_length" and abs(c.length - 6.0) < 1e-6 for c in curves)


#: Planes just below a bitangent plane of a ring torus (R = scale, r = share * scale; tilt asin(share) - delta): two
#: nested loops passing 5e-7 to 2e-3 of the scale apart, moved up to 1.3e4 from the origin (seeded rotations).
BITANGENT = [(0.45, 4e-13, 0.85, 0.0, 1), (0.59, 3.5e-11, 351.0, 669.0, 2), (0.3, 1.5e-12, 83.0, 1.3e4, 3),
             (0.4, 5e-12, 97.0, 2.4, 4), (0.6, 1e-9, 1e-3, 0.0, 5), (0.5, 1e-7, 1.0, 0.0, 6)]


@pytest.mark.parametrize("share, delta, scale, far, seed", BITANGENT)
def test_a_plane_beside_a_bitangent_plane_of_a_torus_cuts_two_loops(share, delta, scale, far, seed):
    """A plane through a ring torus's centre tilted just below its bitangent plane meets it in two nested loops that
    pass close where the plane nearly touches the torus: the march follows each loop past there, not across to the
    other (which gave two circles through those places, loops 85% too long or short, or a march that never
    closed). Both argument orders: two closed curves, each of its loop's length within 1e-9 (relative) of the
    quadrature in 30-digit arithmetic (tests.oracles.closed_forms.bitangent_loops)."""
    from tests.oracles.bitangent_hunt import bitangent_pair
    from tests.oracles.closed_forms import bitangent_loops
    rng = np.random.default_rng(seed)
    rot = random_rotation(rng)
    origin = rng.normal(size=3)
    origin *= far / np.linalg.norm(origin)
    torus, plane = bitangent_pair(share, delta, scale, origin, rot)
    _, exact = bitangent_loops(torus, plane)
    for pair in ((torus, plane), (plane, torus)):
        curves = sk.intersect(*pair)
        assert [c.closed for c in curves] == [True, True]
        assert np.allclose(sorted(c.length for c in curves), exact, rtol=1e-9, atol=0.0)


def near_tangent_cylinders():
    """Two untrimmed cylinders 2.4e4 from the origin, 2.5e-9 (relative) from touching: one loop 3.4e-4 long whose
    normals' sine falls to 6e-6 at its tips, so that points within the gap tolerance of both surfaces lie up to 1e-5
    off it."""
    a = sk.Cylinder(0.1413875351916232, sk.Frame(
        (21412.986948007456, -813.6479107772784, -11997.63644131216),
        [[-0.8369333470956916, 0.3402774756925714, -0.42866515143581985],
         [-0.34985028612535285, 0.26970000542215644, 0.8971436252759631],
         [0.42088876180911694, 0.900818043009564, -0.10667475601663265]]))
    b = sk.Cylinder(0.034277285873440436, sk.Frame(
        (21413.19347888011, -813.7280635479508, -11997.709747417772),
        [[0.8918424115906136, 0.23349389560989187, 0.38742446180017487],
         [0.3736631825423068, 0.10242226565495177, -0.9218923502830799],
         [-0.25493712734827956, 0.9669489542943946, 0.004096448264493346]]))
    return a, b


def test_starts_off_a_near_tangent_loop_rejoin_it():
    """Where the surfaces nearly touch, a start within the gap tolerance of both may lie 1e-5 off the curve; the march
    from it goes round the loop without passing it. Both sk.intersect (whose search gives about a hundred such starts)
    and sk.trace from such a start return the one loop, closed, its length within the 40-digit oracle's (the trapezoid
    rule's error plus the loop's conditioning, 2 pi ulp(|x|) / smallest sine, tests.oracles.mp) of the truth."""
    from tests.oracles.mp import loop_length
    a, b = near_tangent_cylinders()
    off = np.asarray(a.point(3.14151741, 9.68063763e-05), dtype=float)
    answers = [sk.intersect(a, b), sk.intersect(b, a), [sk.trace(a, b, off)], [sk.trace(b, a, off)]]
    gap = answers[0][0].closest(off[None])[1]
    exact, error, sine = loop_length(a, b, answers[0][0].points[::5], n=1024)
    # (the start is within the gap tolerance of both surfaces, and 1e-6 or more from the curve: farther from the one
    # traced than its points' conditioning, 4 ulp(|x|) / smallest sine, plus 1e-6)
    places = 4 * np.finfo(float).eps * float(np.abs(off).max()) / sine
    assert float(b.distance(off)) < 3e-10 and gap[0] > 1e-6 + places
    bound = error + 2 * math.pi * np.finfo(float).eps * float(np.abs(off).max()) / sine
    for curves in answers:
        assert len(curves) == 1 and curves[0].status == "closed"
        assert abs(curves[0].length - exact) <= bound, (curves[0].length, exact, bound)


@pytest.mark.parametrize("shift, edge", [(-1e-12, 1e-10), (-1e-12, 1e-8), (-1e-9, 1e-10)])
@pytest.mark.parametrize("placed", [False, True])
def test_a_lobe_beside_a_split_node_and_a_trim_edge_is_one_loop(shift, edge, placed):
    """A cylinder (radius 0.8) touching a torus (1, 0.4) at its inner equator, moved inwards by 1e-12 or 1e-9: the
    figure eight splits into two lobes; the cylinder trimmed to v >= 1e-10 or 1e-8 keeps the lobe y > 0 whole. Its
    seeds on the trim edge sit where the surfaces nearly touch: the march from them goes round the lobe both ways to
    the edge, its two branches running over each other, and the lobe is traced again from its steadiest point. Both
    argument orders, at the origin and placed (scale 216, turned, moved): one closed curve, its length within
    1e-8 (relative) of the closed form (tests.oracles.closed_forms.torus_cylinder_lobe_length)."""
    from tests.oracles.closed_forms import torus_cylinder_lobe_length
    scale, turn, move = (1.0, np.eye(3), np.zeros(3)) if not placed else (
        215.98166976261078, random_rotation(np.random.default_rng(1138)), np.array([-6.68, -8.24, 4.95]))
    axis_y = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])       # the cylinder's axis along y
    torus = sk.Torus(scale, 0.4 * scale, sk.Frame(move, turn))
    cylinder = sk.Cylinder(0.8 * scale, sk.Frame(move + scale * turn @ np.array([1.4 + shift, 0.0, 0.0]),
                                                 turn @ axis_y), v_range=(edge * scale, 2.0 * scale))
    exact = torus_cylinder_lobe_length(shift) * scale
    for a, b in ((torus, cylinder), (cylinder, torus)):
        curves = sk.intersect(a, b)
        assert len(curves) == 1 and curves[0].status == "closed", curves
        assert abs(curves[0].length - exact) <= 1e-8 * exact, (curves[0].length, exact)


def near_tangent_cylinder_cone():
    """A cylinder and a cone (both nappes, trimmed along the axis) 1e-8 (relative) from touching, 2e5 from the
    origin: they meet in a thin loop, 5.6e-3 long and 1.8e-4 wide, where the normals' sine falls to 5e-6, and in two
    curves across the cone's trim edges."""
    a = sk.Cylinder(0.6930632828650811, sk.Frame(
        (-30254.33187656742, -205781.4439664306, -34684.75333391829),
        [[-0.7115996767309053, 0.13168412641138566, 0.6901341832772384],
         [-0.6869378736400427, -0.33655550811329615, -0.6440859785133481],
         [0.14745256130487294, -0.9324106824837812, 0.32995160456461115]]))
    b = sk.Cone(1.0370627045961436, sk.Frame(
        (-30256.14671500991, -205779.83795546676, -34686.35921171851),
        [[0.4559015818496644, -0.5636174104775376, 0.6888317372722956],
         [-0.44932700052801344, -0.8138246116902531, -0.3685033894059966],
         [0.768283147194752, -0.14150942022990462, -0.6242724483130132]]),
        v_range=(-0.691409525651711, 2.476532259998504))
    return a, b


@functools.lru_cache(maxsize=None)
def thin_loop_truth():
    """(length, its error estimate, smallest sine of the normals' angle) of near_tangent_cylinder_cone's loop, in
    40-digit arithmetic (tests.oracles.mp), from samples of the loop sk.intersect returns."""
    from tests.oracles.mp import loop_length
    a, b = near_tangent_cylinder_cone()
    loop = next(c for c in sk.intersect(a, b) if c.closed)
    return loop_length(a, b, loop.points[::2], n=1024)


@pytest.mark.parametrize("swap", [False, True])
def test_a_thin_near_tangent_loop_is_traced_once(swap):
    """Each of the search's 1,450 starts on the thin loop is located within the gap tolerance of both surfaces, up to
    3e-4 off the loop (gap over sine); the tracer settles each onto the curve to round-off, and one loop traced from
    two starts (its places fixed only to an ulp over the sine) is one component. The oracles: the sign regions of
    the cone's implicit function on a grid of the cylinder's chart round the loop (one loop: one negative region
    inside one positive, no other loop there), and the loop's 40-digit length (tests.oracles.mp), within its
    conditioning, 2 pi ulp(|x|) / smallest sine."""
    from tests.oracles.ssi import window_regions
    a, b = near_tangent_cylinder_cone()
    curves = sk.intersect(b, a) if swap else sk.intersect(a, b)
    loops = [c for c in curves if c.closed]
    assert len(loops) == 1 and sorted(c.status for c in curves) == ["boundary", "boundary", "closed"]
    loop = loops[0]
    centre = loop.points.mean(axis=0)
    assert window_regions(a, b, centre, 0.01 / a.radius, 0.01) == (1, 1, False)
    assert all(c.max_distance <= c.tolerance for c in curves)
    exact, error, sine = thin_loop_truth()
    bound = error + 2 * math.pi * np.finfo(float).eps * float(np.abs(centre).max()) / sine
    assert abs(loop.length - exact) <= bound, (loop.length, exact, bound)


def test_thousands_of_starts_beside_two_loops_are_set_aside_in_a_few_queries(monkeypatch):
    """A cylinder 2e-9 inside a sphere's tangent cylinder, 1.8e6 from the origin (HAIR_INSIDE), the cylinder first: the
    search leaves about 30,000 starts in the band where the surfaces lie within its tolerance of each other, off the
    loops. Once the loops are traced, the starts still to be located are located together and tested against each
    loop in one query of the dense output, not one query per start. Oracle: the queries counted, and the loops'
    count and lengths (tests.oracles.closed_forms.cylinder_sphere_loops, within 1e-6 relative)."""
    from spatialkin.tracing import components
    from tests.oracles.closed_forms import cylinder_sphere_loops
    (r, origin, axes), (big, centre) = HAIR_INSIDE["2e-9 at 1.8e6"]
    a, b = sk.Cylinder(r, sk.Frame(origin, axes)), sk.Sphere(big, sk.Frame(centre))
    _, exact = cylinder_sphere_loops(a, b)
    queries = []
    near_curve = components.near_curve

    def counted(curve, points, radius):
        queries.append(len(np.atleast_2d(points)))
        return near_curve(curve, points, radius)

    monkeypatch.setattr(components, "near_curve", counted)
    curves = sk.intersect(a, b)
    assert len(curves) == 2 and all(abs(c.length - exact) <= 1e-6 * exact for c in curves)
    assert sum(queries) > 10_000 and len(queries) < 1_000, (sum(queries), len(queries))


@pytest.mark.parametrize("swap", [False, True])
@pytest.mark.parametrize("placing", list(HAIR_INSIDE))
def test_a_cylinder_a_hair_inside_a_sphere_cuts_two_loops(placing, swap):
    """A cylinder 2e-9, 1e-9 or 7e-10 (relative) inside a sphere's tangent cylinder, far from the origin: the two
    loops pass 1e-4 apart where the cylinder comes nearest the sphere, within the tolerance of a node there, which
    the search reports. A march that crosses between them there runs round both: from each of the search's starts
    (those curves lie on the two loops within the error of their places, gap over sine), or once, jumping across
    the reported node as across a crossing (a lap beside a loop traced on its own, or a curve stopped when it comes
    back to the node), or it stops at the node from both sides; such curves are traced again from their points
    farthest from the node and the loops found, the node set aside. The answer is the two loops, closed, in both
    argument orders. The oracle: the gap R - r - d > 0 and the loops' length by quadrature in 30-digit arithmetic
    (tests.oracles.closed_forms.cylinder_sphere_loops), within 1e-6 relative (1e-4 where the loops pass: 2 pi
    ulp(|x|) over the smallest sine, 2e-5 of the length, bounds what doubles can fix)."""
    from tests.oracles.closed_forms import cylinder_sphere_loops
    (r, origin, axes), (big, centre) = HAIR_INSIDE[placing]
    a, b = sk.Cylinder(r, sk.Frame(origin, axes)), sk.Sphere(big, sk.Frame(centre))
    gap, exact = cylinder_sphere_loops(a, b)
    assert 0 < gap < 1e-8
    curves = sk.intersect(b, a) if swap else sk.intersect(a, b)
    assert len(curves) == 2
    for curve in curves:
        assert curve.status == "closed"
        assert curve.max_distance <= curve.tolerance
        assert abs(curve.length - exact) <= 1e-6 * exact, (curve.length, exact)
    distance = curves[0].closest(curves[1].points)[1].min()
    assert distance > 1e-6 * a.radius, distance           # (two loops, not one twice)


#: Points of the loop of a sphere of radius 1e-9 straddling a ring torus (R 1, r 0.3) 1.3 from its centre (a billion
#: scales from the origin) by the search of two placings: (placing seed, start (3,)).
TINY_LOOP_STARTS = [(1, (0.7321216490496261, -0.3358929690310265, 1.3096193857590643)),
                    (1, (0.732121649445173, -0.3358929703580412, 1.309619384718597)),
                    (2, (1.3218277670586613, 0.011144945845018406, -0.1414361903281336)),
                    (2, (1.3218277673617127, 0.011144945002327655, -0.14143619181070916))]


@pytest.mark.parametrize("seed, start", TINY_LOOP_STARTS)
def test_a_tiny_loop_a_billion_scales_out_closes_once_round(seed, start):
    """A loop of 5.4e-9 a billion of its scales from the origin (where an ulp of a coordinate is 2e-7 of the scale),
    traced from points on it that the search gives: the march's first point, the start projected onto the curve, may
    lie an ulp on either side of the start, so the closure plane lies behind the start by its round-off, not only by
    1e-8 of the scale (else the march closed at once, a loop of 1e-17, or kept no point). Both argument orders close
    once round the loop. Oracle: a circle of radius sqrt(r^2 - h^2), h the sphere centre's distance to the torus by
    the oracle's own distance function (the torus's curvature changes it by 1e-9 relative), within 1e-6 (the
    placement's round-off over h)."""
    from tests.oracles.ssi import distance
    rng = np.random.default_rng(seed)
    turn = sk.rotation_about(rng.normal(size=3), rng.uniform(0, 6))
    origin = rng.uniform(-1, 1, 3)
    torus = sk.Torus(1.0, 0.3, sk.Frame(origin, turn))
    sphere = sk.Sphere(1e-9, sk.Frame(origin + turn @ np.array([1.3 + 0.5e-9, 0.0, 0.0]), turn))
    h = float(distance(torus, np.asarray(sphere.frame.origin)[None])[0])
    exact = 2 * math.pi * math.sqrt(1e-18 - h * h)
    for a, b in ((torus, sphere), (sphere, torus)):
        curve = sk.trace(a, b, np.array(start))
        assert curve.closed and abs(curve.length - exact) <= 1e-6 * exact, (curve.status, curve.length, exact)
        curves = sk.intersect(a, b)
        assert len(curves) == 1 and curves[0].closed and abs(curves[0].length - exact) <= 1e-6 * exact
