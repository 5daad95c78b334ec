"""Interval kernels: every enclosure holds the exact values it encloses, and the certified searches isolate the
roots they claim. Oracles: float evaluation of the surfaces and the polynomial implicit functions written here
(numpy, apart from the kernels), and closed-form roots."""
import math

import numpy as np
import pytest
from tests.oracles.closed_forms import random_rotation

import spatialkin as sk
from spatialkin.kernels.geometry import interval as ki
from spatialkin.kernels.search import topology as kt

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


def test_placement_pad_covers_the_rounding_of_the_translation():
    """c = R_T^T (o_S - o_T) as relative_placement rounds it lies within 2 ulps of its returned magnitude of the
    exact value (rational arithmetic on the same floats), so the pad of PLACEMENT_ULPS ulps covers it: for surfaces
    near the origin, 1e9 away from it and near each other, and far apart."""
    from fractions import Fraction
    rng = np.random.default_rng(21)
    worst = 0.0
    for _ in range(3000):
        base = rng.normal(size=3) * 10.0 ** rng.integers(-3, 10)
        spread = 10.0 ** rng.integers(-8, 10)
        s = sk.Sphere(1.0, sk.Frame(base + rng.normal(size=3) * spread, random_rotation(rng)))
        t = sk.Torus(2.0, 0.5, sk.Frame(base + rng.normal(size=3) * spread, random_rotation(rng)))
        m, c = np.empty((3, 3)), np.empty(3)
        mag = ki.relative_placement(s.data, t.data, m, c)
        rot, o_s, o_t = t.frame.rotation, s.frame.origin, t.frame.origin
        for i in range(3):
            exact = sum(Fraction(rot[k, i]) * (Fraction(o_s[k]) - Fraction(o_t[k])) for k in range(3))
            error = abs(Fraction(c[i]) - exact)
            assert error <= Fraction(2.0 * ki.EPS * mag), (i, float(error), mag)
            worst = max(worst, float(error) / (ki.EPS * mag)) if mag > 0 else worst
    assert worst > 0.0                   # (the test meets real round-off, not only exact cases)


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


def _subnormal(x):
    return x != 0.0 and abs(x) < np.finfo(float).tiny


def test_pads_of_exact_zeros_stay_normal():
    """An exact zero padded outward (a cylinder's zero slope, a zero tangent component) and its products with
    numbers of order one are normal numbers, not subnormal ones (each operation on a subnormal costs a microcode
    assist on Intel CPUs): no bound of the jets of a cylinder and a cone over boxes of the search, against each
    other and a sphere, is subnormal. The pad itself still covers round-off below the normal range (2^-1075)."""
    assert ki.TINY >= 2.0 ** -1074 and not _subnormal(ki.down(0.0)) and not _subnormal(ki.up(0.0))
    fuzzy = (ki.down(0.0), ki.up(0.0))
    assert not any(_subnormal(x) for x in ki.imul(fuzzy, (0.3, 0.8)) + ki.iscale(fuzzy, 1e-3))
    rng = np.random.default_rng(11)
    frame = sk.Frame(rng.uniform(-1, 1, 3), random_rotation(rng))
    cases = [sk.Cylinder(0.8, frame), sk.Cone(0.5, frame), sk.Sphere(1.0, sk.Frame((0.3, -0.2, 0.1)))]
    for s in cases[:2]:
        for t in cases:
            m, c = np.empty((3, 3)), np.empty(3)
            mag = ki.relative_placement(s.data, t.data, m, c)
            pad, cpad = ki.PLACEMENT_ULPS * ki.EPS, ki.PLACEMENT_ULPS * ki.EPS * mag
            for _ in range(50):
                u0, v0 = rng.uniform(-3, 3, 2)
                w = 10 ** rng.uniform(-12, 0, 2)
                enc = ki.jet(s.data, t.data, m, c, pad, cpad, (u0, u0 + w[0]), (v0, v0 + w[1]))
                bounds = np.array(enc, dtype=float).ravel()
                assert not np.any((bounds != 0) & (np.abs(bounds) < np.finfo(float).tiny))


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



def test_bisection_follows_the_smear():
    """_cut_u cuts the parameter whose enclosed derivative times width spreads g or phi most (the maximal smear),
    whatever the widths alone say, and never one already at its smallest width (ratio <= 1). Oracle: the shares
    by hand."""
    flat, steep = (0.0, 0.0), (-2.0, 2.0)
    # g spreads along u only (|g_u| wu = 0.2, |g_v| wv = 0): u, though v is ten times wider relative to its floor
    assert kt._cut_u(10.0, 100.0, (-1.0, 2.0), flat, flat, flat, 0.1, 1.0)
    # phi spreads along v only: v
    assert not kt._cut_u(100.0, 10.0, flat, flat, flat, steep, 1.0, 0.1)
    # shares g: u 2/3 (|g_u| wu = 1, |g_v| wv = 0.5), phi: v 3/4 (0.25 against 0.75): v has the larger share
    assert not kt._cut_u(5.0, 5.0, (-1.0, 0.5), (0.0, 0.5), (0.25, 0.25), (-0.75, 0.0), 1.0, 1.0)
    # nothing spreads (both shares 1/2): u, as ties go
    assert kt._cut_u(5.0, 5.0, flat, flat, flat, flat, 1.0, 1.0)
    # at its smallest width a side is never cut
    assert not kt._cut_u(1.0, 5.0, steep, flat, steep, flat, 1.0, 1.0)
    assert kt._cut_u(5.0, 0.5, flat, steep, flat, steep, 1.0, 1.0)

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


def _icos_single(a):
    """kernels.interval.icos with the cosine taken at both ends even for a point (two cos calls), the oracle below."""
    lo, hi = a
    if hi - lo >= ki.TWO_PI:
        return (-1.0, 1.0)
    c0, c1 = math.cos(lo), math.cos(hi)
    r0, r1 = min(c0, c1), max(c0, c1)
    r0 -= ki.TRIG_ULPS * ki.EPS * abs(r0) + ki.TINY
    r1 += ki.TRIG_ULPS * ki.EPS * abs(r1) + ki.TINY
    if ki._has_multiple(lo, hi, 0.0):
        r1 = 1.0
    if ki._has_multiple(lo, hi, math.pi):
        r0 = -1.0
    return (max(r0, -1.0), min(r1, 1.0))


def _jet_single(s_data, t_data, m, c, pad, cpad, U, V):
    """kernels.interval.jet as one function (local_jet and jet not split in stages), in Python on the same interval
    primitives: the oracle of the staged jets, to the bit."""
    geometry = int(s_data[ki.GEOMETRY])
    z, one = (0.0, 0.0), (1.0, 1.0)
    zero3 = (z, z, z)
    if geometry == ki.PLANE:
        local = (U, V, z), (one, z, z), (z, one, z), zero3, zero3, zero3
    else:
        cu = _icos_single(U)
        su = _icos_single(ki.widen((U[0] - ki.HALF_PI, U[1] - ki.HALF_PI), ki.HALF_PI_ERROR))
        if geometry in (ki.SPHERE, ki.TORUS):
            big = 0.0 if geometry == ki.SPHERE else s_data[ki.P0]
            small = s_data[ki.P0] if geometry == ki.SPHERE else s_data[ki.P1]
            cv = _icos_single(V)
            sv = _icos_single(ki.widen((V[0] - ki.HALF_PI, V[1] - ki.HALF_PI), ki.HALF_PI_ERROR))
            w = ki.ishift(ki.iscale(cv, small), big)
            ssv, scv = ki.iscale(sv, small), ki.iscale(cv, small)
            wcu, wsu = ki.imul(w, cu), ki.imul(w, su)
            local = ((wcu, wsu, ssv), (ki.ineg(wsu), wcu, z),
                     (ki.ineg(ki.imul(ssv, cu)), ki.ineg(ki.imul(ssv, su)), scv),
                     (ki.ineg(wcu), ki.ineg(wsu), z), (ki.imul(ssv, su), ki.ineg(ki.imul(ssv, cu)), z),
                     (ki.ineg(ki.imul(scv, cu)), ki.ineg(ki.imul(scv, su)), ki.ineg(ssv)))
        else:
            b = s_data[ki.P1]
            rho = ki.ishift(ki.iscale(V, b), s_data[ki.P0])
            rcu, rsu = ki.imul(rho, cu), ki.imul(rho, su)
            bcu, bsu = ki.iscale(cu, b), ki.iscale(su, b)
            local = ((rcu, rsu, V), (ki.ineg(rsu), rcu, z), (bcu, bsu, one), (ki.ineg(rcu), ki.ineg(rsu), z),
                     (ki.ineg(bsu), bcu, z), zero3)
    x, xu, xv, xuu, xuv, xvv = local
    q0 = ki.transform(m, x, pad)
    r = cpad + pad * (abs(c[0]) + abs(c[1]) + abs(c[2]))
    q = tuple(ki.widen(ki.ishift(q0[i], c[i]), r) for i in range(3))
    qu, qv = ki.transform(m, xu, pad), ki.transform(m, xv, pad)
    quu, quv, qvv = ki.transform(m, xuu, pad), ki.transform(m, xuv, pad), ki.transform(m, xvv, pad)
    f, grad, s = ki.implicit_jet(t_data, q)
    return (f, ki.idot(grad, qu), ki.idot(grad, qv),
            ki.iadd(ki.hessian_form(t_data, q, s, qu, qu), ki.idot(grad, quu)),
            ki.iadd(ki.hessian_form(t_data, q, s, qu, qv), ki.idot(grad, quv)),
            ki.iadd(ki.hessian_form(t_data, q, s, qv, qv), ki.idot(grad, qvv)))


@pytest.mark.parametrize("seed", range(2))
def test_staged_jets_match_the_single_jet_to_the_bit(seed):
    """jet, jet_first, jet_second and level (compiled, their helpers inlined) give the same bits as the jet computed
    in one piece (_jet_single, in Python): over random boxes and at points (a box of zero
    width, padded or not), for every pair of kinds; the searches' point values (point_values) lie in that jet's
    enclosures at the point, and level_enclosure meets its first entry, as narrow."""
    rng = np.random.default_rng(200 + seed)
    for s in surfaces(rng):
        for t in surfaces(rng):
            m, c = np.empty((3, 3)), np.empty(3)
            mag = ki.relative_placement(s.data, t.data, m, c)
            pads = ((ki.PLACEMENT_ULPS * ki.EPS, ki.PLACEMENT_ULPS * ki.EPS * mag), (0.0, 0.0))
            for width in (2.0, 1e-3, 0.0):
                u0, v0 = rng.uniform(-3, 3, 2)
                U, V = (u0, u0 + width), (v0, v0 + 0.7 * width)
                for pad, cpad in pads:
                    want = _jet_single(s.data, t.data, m, c, pad, cpad, U, V)
                    first, state = ki.jet_first(s.data, t.data, m, c, pad, cpad, U, V, ki.box_trig(s.data, U, V))
                    assert ki.jet(s.data, t.data, m, c, pad, cpad, U, V) == want
                    assert first == want[:3]
                    assert ki.jet_second(s.data, t.data, m, pad, state) == want[3:]
                    assert ki.level(s.data, t.data, m, c, pad, cpad, U, V) == want[0]
            uv = rng.uniform(-3, 3, (4, 2))
            values = np.empty((4, 6))
            kt.point_values(s.data, t.data, m, c, uv, values)
            for (u, v), row in zip(uv, values):
                want = _jet_single(s.data, t.data, m, c, 0.0, 0.0, (u, u), (v, v))
                assert all(lo <= x <= hi for x, (lo, hi) in zip(row.tolist(), want))
                pad, cpad = pads[0]
                lo, hi = kt.level_enclosure(s.data, t.data, m, c, pad, cpad, u, v)
                wlo, whi = _jet_single(s.data, t.data, m, c, pad, cpad, (u, u), (v, v))[0]
                # two enclosures of one value (inlined, or through the helpers' own dispatchers): they meet, and
                # are as narrow within a few ulps
                assert lo <= whi and wlo <= hi
                assert hi - lo <= 2.0 * (whi - wlo) + 8 * np.spacing(max(abs(lo), abs(hi)))


def _refine_all_steps(step, x, keep_new):
    """Newton's iterates x_k+1 = step(x_k) (None: stop at x_k) for REFINE_ITER steps or until an iterate equals the
    one before (then the new one if keep_new, else the old), without looking for cycles as refine_extremal and
    refine_line do: (the last iterate, whether some iterate repeated an earlier one bit for bit)."""
    seen, repeated = [np.array(x).tobytes()], False
    for _ in range(kt.REFINE_ITER):
        new = step(x)
        if new is None:
            break
        if new == x:
            return (new if keep_new else x), repeated
        x = new
        repeated = repeated or np.array(x).tobytes() in seen
        seen.append(np.array(x).tobytes())
    return x, repeated


def test_refinement_ends_where_all_its_steps_end():
    """refine_extremal and refine_line, which stop when their iterates cycle, return the bits the full REFINE_ITER
    steps give (the plain loops of _refine_all_steps) on every verified box of searches over the bench pairs
    and random pairs, on many of which the iterates do cycle."""
    from spatialkin.bench.kinds import pair_kind_cases
    rng = np.random.default_rng(7)
    pairs = [(a, b) for kind, a, b in pair_kind_cases()] + [(s, t) for s in surfaces(rng) for t in surfaces(rng)]
    box = np.array([-math.pi, math.pi, -3.0, 3.0])
    du, dv = math.cos(0.3091), math.sin(0.3091)
    cycled = checked = 0
    for s, t in pairs:
        m, c = np.empty((3, 3)), np.empty(3)
        mag = ki.relative_placement(s.data, t.data, m, c)
        pad, cpad = ki.PLACEMENT_ULPS * ki.EPS, ki.PLACEMENT_ULPS * ki.EPS * mag
        out, kinds = np.empty((4096, 4)), np.empty(4096, dtype=np.int64)
        n, _, _ = kt.extremal_points(s.data, t.data, m, c, pad, cpad, du, dv, box, np.array([1e-13, 1e-13]), 1e6,
                                     100_000, out, kinds)
        for rec in out[:n][kinds[:n] == kt.VERIFIED]:
            def step(x, rec=rec):
                g, gu, gv, guu, guv, gvv = kt._point_jet(s.data, t.data, m, c, x[0], x[1])
                phi, a10, a11 = dv * gu - du * gv, dv * guu - du * guv, dv * guv - du * gvv
                det = gu * a11 - gv * a10
                if det == 0.0:
                    return None
                return (min(max(x[0] - (a11 * g - gv * phi) / det, rec[0]), rec[1]),
                        min(max(x[1] - (gu * phi - a10 * g) / det, rec[2]), rec[3]))
            want, repeated = _refine_all_steps(step, (0.5 * (rec[0] + rec[1]), 0.5 * (rec[2] + rec[3])), True)
            uv = np.empty(2)
            kt.refine_extremal(s.data, t.data, m, c, du, dv, rec, uv)
            assert uv.tobytes() == np.array(want).tobytes()
            cycled += repeated
            checked += 1
        records, kinds = np.empty((64, 2)), np.empty(64, dtype=np.int64)
        for fixed in (0, 1):
            n, _, _ = kt.line_roots(s.data, t.data, m, c, pad, cpad, fixed, 0.1, box[2 - 2 * fixed],
                                    box[3 - 2 * fixed], 1e-14, 1e-7, 100_000, records, kinds)
            for lo, hi in records[:n][kinds[:n] == kt.VERIFIED]:
                def step(x, lo=lo, hi=hi, fixed=fixed):
                    j = kt._point_jet(s.data, t.data, m, c, *((x[0], 0.1) if fixed == 1 else (0.1, x[0])))
                    d = j[1] if fixed == 1 else j[2]
                    return None if d == 0.0 else (min(max(x[0] - j[0] / d, lo), hi),)
                want, repeated = _refine_all_steps(step, (0.5 * (lo + hi),), False)
                got = kt.refine_line(s.data, t.data, m, c, fixed, 0.1, lo, hi)
                assert np.float64(got).tobytes() == np.float64(want[0]).tobytes()
                cycled += repeated
                checked += 1
    assert checked >= 40 and cycled >= 5
