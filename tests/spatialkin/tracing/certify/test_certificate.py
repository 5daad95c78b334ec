"""certify=True: each claim proven or said not to be, never a wrong answer marked proven.

Oracles: the number of components known in closed form (a sphere and a cylinder inside it meet in two loops, in
one when the cylinder reaches beyond it, in a figure-eight when internally tangent), the distances to both surfaces
(a lower bound of the distance to their intersection, which a proven distance bound must not undercut), and
answers tampered with on purpose (merged, dropped or moved curves), which no proof may pass.
"""
import dataclasses
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.certify.certificate import CLAIMS, CertificationError, certify


def looper_pair():
    return sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))


def sphere_cylinder(eps, shift=0.0, scale=1.0, swap=False):
    """A unit sphere (times scale) and a cylinder of radius 1/2 at distance (1/2)(1 + eps) from its centre, along
    z: two loops for eps < 0, one for eps > 0 (internally tangent at eps = 0); moved by shift."""
    o = np.array([shift, 0.3 * shift, -0.7 * shift])
    sphere = sk.Sphere(scale, sk.Frame(o))
    cylinder = sk.Cylinder(0.5 * scale, sk.Frame(o + np.array([0.5 * (1 + eps) * scale, 0.0, 0.0])),
                           v_range=(-3.0 * scale, 3.0 * scale))
    return (cylinder, sphere) if swap else (sphere, cylinder)


def test_looper_pair_is_proven_claim_by_claim():
    """Every claim of the looper pair's answer proven; the proven distance bound is at least each stored point's
    distance to the farther surface (a lower bound of its distance to the curve) and below 1e-12."""
    a, b = looper_pair()
    curves = sk.intersect(a, b, certify=True)
    cert = curves.certificate
    assert len(curves) == 2 and cert.proven and set(cert.claims) == set(CLAIMS)
    assert all(c.certificate.answer is cert for c in curves)
    for curve in curves:
        gap = np.maximum(a.distance(curve.points), b.distance(curve.points))
        assert np.all(gap <= curve.certificate.distance_bound)
        assert curve.certificate.distance_bound < 1e-12
        assert curve.certificate.tube.proven and len(curve.certificate.tube.pieces) >= len(curve.points) - 1


def test_empty_answer_carries_a_proven_certificate():
    """Disjoint surfaces: an empty list whose certificate proves that nothing was missed: a general placement, two
    spheres (exactly symmetric about the line through their centres), a sphere on a turned torus's axis (read as
    coaxial within a tolerance, so proven by a general search), and on the axis of a torus placed by the identity
    (coaxial exactly: proven in rational arithmetic)."""
    for pair in ((sk.Torus(1.0, 0.4), sk.Sphere(0.3, sk.Frame((0.5, 0.7, 2.0)))),
                 (sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((3.0, 0.0, 0.0))))):
        curves = sk.intersect(*pair, certify=True)
        assert curves == [] and curves.certificate.proven
        assert curves.certificate.claims["complete"].proven
    turn = sk.rotation_about((1.0, 2.0, 0.5), 0.7)
    coaxial = sk.intersect(sk.Torus(1.0, 0.4, sk.Frame((0.0, 0.0, 0.0), turn)),
                           sk.Sphere(0.3, sk.Frame(2.0 * turn[:, 2])), certify=True)
    assert coaxial == [] and coaxial.certificate.mode == "coaxial" and coaxial.certificate.proven
    exact = sk.intersect(sk.Torus(1.0, 0.4), sk.Sphere(0.3, sk.Frame((0.0, 0.0, 2.0))), certify=True)
    assert exact == [] and exact.certificate.mode == "exact (coaxial)" and exact.certificate.proven


def test_merged_curves_fail():
    """The two loops joined into one closed curve: the chain cannot cross from one loop to the other, so the arcs,
    and with them the rest, are not proven."""
    a, b = looper_pair()
    curves = sk.intersect(a, b)
    first, second = curves[0].result, curves[1].result
    joined_points = np.concatenate([first.points[:-1], second.points])
    s = np.concatenate([first.s[:-1], first.s[-2] + 0.1 + second.s])
    merged = dataclasses.replace(first, points=joined_points, s=s, closed=False, length=float(s[-1]))
    cert = certify(a, b, [merged], curves[0].topology, 1.4)
    assert not cert.proven
    assert not cert.claims["arcs"].proven or not cert.claims["points"].proven


def test_dropped_curve_fails_completeness():
    """One of the two loops dropped: the roots of the search on it lie in no tube."""
    a, b = looper_pair()
    curves = sk.intersect(a, b)
    cert = certify(a, b, [curves[0].result], curves[0].topology, 1.4)
    assert not cert.proven and not cert.claims["complete"].proven
    assert cert.claims["arcs"].proven                  # what is there is proven; what is missing is said
    assert len(cert.claims["complete"].where) >= 1
    far = np.min(np.linalg.norm(cert.claims["complete"].where[:, None] - curves[0].points[None], axis=2), axis=1)
    assert np.all(far > 0.1)                           # the failure is located on the dropped loop


def test_a_curve_given_twice_is_not_distinct():
    """The same loop returned twice: the tubes overlap, so distinctness is not proven."""
    a, b = looper_pair()
    curves = sk.intersect(a, b)
    cert = certify(a, b, [curves[0].result, curves[0].result, curves[1].result], curves[0].topology, 1.4)
    assert not cert.proven and not cert.claims["distinct"].proven


@pytest.mark.parametrize("factor", [10.0, 1e6])
def test_moved_point_is_not_vouched_for(factor):
    """A stored point moved off the curve by factor times its proven radius: its new radius (or the distance
    bound) must cover the move, or the claim is not proven; never the old radius."""
    a, b = looper_pair()
    curves = sk.intersect(a, b, certify=True)
    result = curves[0].result
    k = len(result.points) // 3
    radius = curves[0].certificate.radii[k]
    normal = np.cross(result.sol.tangent(result.s[k:k + 1])[0], [0.0, 0.0, 1.0])
    normal /= np.linalg.norm(normal)
    move = factor * max(radius, 1e-15)
    points = result.points.copy()
    points[k] += move * normal
    cert = certify(a, b, [dataclasses.replace(result, points=points), curves[1].result], curves[0].topology, 1.4)
    true_gap = max(float(a.distance(points[k])), float(b.distance(points[k])))
    assert not cert.claims["points"].proven or cert.radii[0][k] * math.sqrt(3) >= true_gap
    assert not cert.claims["arcs"].proven or cert.distance_bounds[0] >= true_gap


def test_strict_raises_with_the_failed_claims():
    """certify='strict' raises CertificationError naming the claims it could not prove (a sphere in a cylinder of
    its radius, both turned by one rotation that is not a signed permutation, touches it along a circle: a singular
    curve, not proven: the turned floats are not exactly coaxial); True returns them, said not proven."""
    turn = sk.rotation_about((1.0, 2.0, 0.5), 0.7)
    pair = (sk.Sphere(1.0, sk.Frame((0.0, 0.0, 0.0), turn)),
            sk.Cylinder(1.0, sk.Frame((0.0, 0.0, 0.0), turn), v_range=(-2.0, 2.0)))
    loose = sk.intersect(*pair, certify=True)
    assert len(loose) == 1 and loose[0].status == "tangent" and not loose.certificate.proven
    assert not loose.certificate.claims["singular"].proven
    assert "tangency" in loose.certificate.claims["singular"].detail
    with pytest.raises(sk.CertificationError) as err:
        sk.intersect(*pair, certify="strict")
    assert isinstance(err.value, CertificationError)
    assert not err.value.certificate.proven
    assert all(c.name in str(err.value) for c in err.value.certificate.failed)
    with pytest.raises(ValueError, match="certify"):
        sk.intersect(*pair, certify="yes")


@pytest.mark.slow
def test_near_tangent_loops_are_never_certified_wrong():
    """A sphere and a cylinder 1e-7 to 1e-10 (relative) from internal tangency, on both sides, in both argument
    orders, moved up to 1e9 from the origin and scaled 1e-6 to 1e6: every answer certified proven has the right
    number of components (2 inside, 1 beyond); the rest say they are not proven (or the search refuses)."""
    proven = 0
    for eps in (1e-7, 1e-8, 1e-9, 1e-10):
        for sign, truth in ((-1.0, 2), (1.0, 1)):
            for shift in (0.0, 1e5, 1e9):
                for scale in (1e-6, 1.0, 1e6):
                    for swap in (False, True):
                        try:
                            curves = sk.intersect(*sphere_cylinder(sign * eps, shift, scale, swap), certify=True)
                        except sk.TopologyError:
                            continue
                        if curves.certificate.proven:
                            proven += 1
                            assert len(curves) == truth, (eps, sign, shift, scale, swap)
    assert proven >= 1


def test_clearly_separated_loops_are_proven():
    """Away from tangency (eps = -1e-2: two loops; +1e-2: one) the whole answer is proven."""
    for eps, truth in ((-1e-2, 2), (1e-2, 1)):
        curves = sk.intersect(*sphere_cylinder(eps), certify=True)
        assert len(curves) == truth and curves.certificate.proven, curves.certificate


def strip_pair():
    """A unit sphere and the plane z = 0.3 trimmed to the strip |x| <= 0.5: two arcs of the circle of radius
    sqrt(0.91), ending on the strip's edges."""
    return sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.3)), u_range=(-0.5, 0.5), v_range=(-2.0, 2.0))


def test_arcs_cut_by_a_strip_are_proven_whole():
    """Both arcs proven, each ending on an edge of the strip (x = +-0.5 to 1e-12), their lengths the closed form
    rho (pi - 2 acos(0.5 / rho)) each (1e-9)."""
    curves = sk.intersect(*strip_pair(), certify=True)
    assert len(curves) == 2 and curves.certificate.proven, curves.certificate
    rho = math.sqrt(0.91)
    for curve in curves:
        ends = curve.points[[0, -1]]
        assert np.allclose(np.abs(ends[:, 0]), 0.5, atol=1e-12, rtol=0)
        assert abs(curve.length - rho * (math.pi - 2 * math.acos(0.5 / rho))) < 1e-9


def test_a_cut_short_arc_is_not_whole():
    """One arc cut short (its last third dropped): its end is on no trim edge, so it is not one whole component,
    and the roots of the search on that edge are not all accounted for."""
    a, b = strip_pair()
    curves = sk.intersect(a, b, certify=True)
    result = curves[0].result
    keep = len(result.points) * 2 // 3
    short = dataclasses.replace(result, points=result.points[:keep], s=result.s[:keep], params=result.params[:keep],
                                length=float(result.s[keep - 1]))
    cert = certify(a, b, [short, curves[1].result], curves[0].topology, 1.0)
    assert not cert.proven and not cert.claims["one_component"].proven


def test_a_closed_form_answer_is_not_complete():
    """The answer of the closed-form path comes with no search: certifying it proves no completeness."""
    a, b = strip_pair()
    curves = sk.intersect(a, b)
    cert = certify(a, b, [c.result for c in curves], curves[0].topology, 1.0)
    assert not cert.proven and not cert.claims["complete"].proven


def test_a_dropped_arc_leaves_roots_unaccounted():
    """One of the two arcs dropped: the roots of the search on it are neither in a tube nor outside the trims."""
    a, b = strip_pair()
    curves = sk.intersect(a, b, certify=True)
    cert = certify(a, b, [curves[0].result], curves[0].topology, 1.0)
    assert not cert.proven and not cert.claims["complete"].proven


def test_trimmed_cylinder_rims_against_brute_force():
    """A sphere and a cylinder off its centre trimmed below the sphere's top, in both argument orders: the curves
    end on the cylinder's rim; proven, with the brute-force oracle's number of components."""
    from tests.oracles.ssi import brute_force, curve_components, dense_points
    sphere = sk.Sphere(1.0, sk.Frame((0.1, -0.2, 0.05)))
    cylinder = sk.Cylinder(0.45, sk.Frame((0.35, 0.0, 0.0), sk.rotation_about((1.0, 0.0, 0.0), 0.3)),
                           v_range=(-0.6, 0.7))
    truth = brute_force(sphere, cylinder)["count"]
    for pair in ((sphere, cylinder), (cylinder, sphere)):
        curves = sk.intersect(*pair, certify=True)
        assert curves.certificate.proven, curves.certificate.failed
        count, _ = curve_components(curves, 1.0, 2e-6, [dense_points(c, 1.0) for c in curves])
        assert count == truth


@pytest.mark.parametrize("gap", [2e-3, 2e-5])
def test_loops_just_inside_a_rim_are_proven_whole(gap):
    """A sphere of radius 1.5 off a unit cylinder's axis by d = 0.05 meets it in two loops, z = +-sqrt(2.25 - (1 +
    d^2 - 2 d cos theta)); the rims gap below the lower loop's lowest point and above the upper's highest: two closed
    curves, proven (their arcs inside the rims, though the tube's pieces reach past them), each point on the closed
    form's z within 1e-12."""
    d = 0.05
    top = math.sqrt(2.25 - (1 - d) ** 2)
    cylinder = sk.Cylinder(1.0, v_range=(-top - gap, top + gap))
    sphere = sk.Sphere(1.5, sk.Frame((d, 0.0, 0.0)))
    for pair in ((cylinder, sphere), (sphere, cylinder)):
        curves = sk.intersect(*pair, certify=True)
        assert curves.certificate.proven, curves.certificate.failed
        assert len(curves) == 2 and all(c.closed for c in curves)
        for curve in curves:
            x, y, z = curve.points.T
            theta = np.arctan2(y, x)
            exact = np.sign(z) * np.sqrt(2.25 - (1 + d * d - 2 * d * np.cos(theta)))
            assert np.max(np.abs(z - exact)) < 1e-12


@pytest.mark.parametrize("radius", [0.7, 1.1, 1.4])
def test_coaxial_circles_are_proven_by_a_general_search(radius):
    """A sphere centred on a torus's axis cuts it in two parallels (the meridian circles meet twice): turned by a
    rotation that is not a signed permutation (so coaxial only within a tolerance), read as coaxial, proven by a
    general search; each curve a circle about the axis (constant distance from it, length 2 pi times it, 1e-9)."""
    turn = sk.rotation_about((1.0, 2.0, 0.5), 0.7)
    curves = sk.intersect(sk.Torus(1.0, 0.4, sk.Frame((0.0, 0.0, 0.0), turn)),
                          sk.Sphere(radius, sk.Frame(0.1 * turn[:, 2])), certify=True)
    assert len(curves) == 2 and curves.certificate.mode == "coaxial" and curves.certificate.proven
    for curve in curves:
        local = curve.points @ turn
        rho = np.hypot(local[:, 0], local[:, 1])
        assert np.ptp(rho) < 1e-12 and np.ptp(local[:, 2]) < 1e-12
        assert abs(curve.length - 2 * math.pi * rho.mean()) < 1e-9


def test_a_contact_gets_a_proven_ball():
    """A sphere touching a torus's outer equator at (1.4, 0, 0): the contact is not proven (tangency is an
    equality), but its ball is: within it the intersection lies within a radius below 1e-5 of the true contact
    point, and the search's unresolved boxes there are accounted for by it (complete proven)."""
    curves = sk.intersect(sk.Torus(1.0, 0.4), sk.Sphere(0.5, sk.Frame((1.9, 0.0, 0.0))), certify=True)
    cert = curves.certificate
    assert [c.status for c in curves] == ["contact"] and not cert.proven
    singular = cert.claims["singular"]
    assert not singular.proven and len(singular.where) == 1 and singular.radius[0] < 1e-5
    assert np.linalg.norm(singular.where[0] - [1.4, 0.0, 0.0]) <= singular.radius[0]
    assert cert.claims["complete"].proven and "singular" in cert.claims["complete"].detail


def test_a_node_is_a_proven_saddle_and_not_proven():
    """Viviani's figure-eight (a sphere and a cylinder of half its radius through its centre): a box around the node
    at (1, 0, 0) is proven to hold one critical point of the level, a saddle, and four branches leaving it through
    the curve's proven tubes. The arcs and completeness are proven; the curve is not proven one component (which
    branches join at the node is an equality), so the answer is not proven."""
    curves = sk.intersect(sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.5, 0.0, 0.0)), v_range=(-2.0, 2.0)),
                          certify=True)
    cert = curves.certificate
    singular = cert.claims["singular"]
    assert len(curves) == 1 and not cert.proven and not singular.proven
    assert "saddle" in singular.detail and "four branches" in singular.detail
    assert np.allclose(singular.where[0], [1.0, 0.0, 0.0], atol=1e-9) and singular.radius[0] < 0.1
    assert cert.claims["arcs"].proven and cert.claims["complete"].proven and cert.claims["points"].proven
    assert not cert.claims["one_component"].proven and "node" in cert.claims["one_component"].detail
    assert cert.distance_bounds[0] < 1e-6                # (samples near the node: their proven boxes grow)


def test_a_point_moved_near_a_node_is_in_the_distance_bound():
    """Viviani's stored point nearest the node moved by 2e-3: its proven radius covers the move, and so does the
    curve's distance bound (a point near the node is not left out of it)."""
    a, b = sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.5, 0.0, 0.0)), v_range=(-2.0, 2.0))
    curves = sk.intersect(a, b, certify=True)
    c = curves[0].result
    k = int(np.argmin(np.linalg.norm(c.points - [1.0, 0.0, 0.0], axis=1)))
    points = c.points.copy()
    points[k, 0] -= 2e-3
    cert = certify(a, b, [dataclasses.replace(c, points=points)], curves[0].topology, 1.0)
    assert cert.radii[0][k] * math.sqrt(3.0) >= 1e-3 and cert.distance_bounds[0] >= 1e-3


def hair_inside(swap=False):
    """A cylinder 7e-10 (relative) inside a sphere's tangent cylinder, 8.6e4 from the origin: two loops passing 1e-4
    apart where the cylinder comes nearest the sphere, within the tolerance of a node there, which the search
    reports."""
    from tests.oracles.closed_forms import HAIR_INSIDE
    (r, origin, axes), (big, centre) = HAIR_INSIDE["7e-10 at 8.6e4"]
    pair = sk.Cylinder(r, sk.Frame(origin, axes)), sk.Sphere(big, sk.Frame(centre))
    return pair[::-1] if swap else pair


@pytest.mark.parametrize("swap", [False, True])
def test_loops_passing_close_at_a_saddle_are_proven_two(swap):
    """The loops of hair_inside: the saddle of the level between them is proven off the level (g keeps one sign
    along a segment across its box), so the arcs there join the branches two by two, each loop passes by one of
    them and the two are distinct: every claim proven. Oracle: the gap R - r - d > 0 (two loops) and their length by
    quadrature in 30-digit arithmetic (tests.oracles.closed_forms.cylinder_sphere_loops), within 1e-6 relative."""
    from tests.oracles.closed_forms import cylinder_sphere_loops
    a, b = hair_inside(swap)
    gap, exact = cylinder_sphere_loops(*(b, a) if swap else (a, b))
    assert 0.0 < gap < 1e-8
    curves = sk.intersect(a, b, certify=True)
    cert = curves.certificate
    assert cert.proven, cert
    assert len(curves) == 2 and all(abs(c.length - exact) <= 1e-6 * exact for c in curves)
    assert cert.claims["singular"].proven and cert.claims["distinct"].proven
    assert all(len(t.passes) == 1 for t in cert.tubes)        # (both pass the reported node)


def test_loops_passing_close_at_a_saddle_tampered_with_are_not_proven(monkeypatch):
    """hair_inside's answer with one loop given twice (not distinct: both pass the saddle by one arc), with one
    dropped (the other arc's branches lie in no tube), and with the saddle's arcs said to join the branches the
    other way (each loop would cross from one arc to the other: not one component)."""
    from spatialkin.tracing.certify import nodes
    a, b = hair_inside()
    curves = sk.intersect(a, b)
    first, second = curves[0].result, curves[1].result
    twice = certify(a, b, [first, first, second], curves[0].topology, 3.0)
    assert not twice.proven and not twice.claims["distinct"].proven
    dropped = certify(a, b, [first], curves[0].topology, 3.0)
    assert not dropped.proven and not (dropped.claims["complete"].proven and dropped.claims["arcs"].proven)
    joined = nodes.joined

    def other_way(chart, node):
        pairs = joined(chart, node)
        return None if pairs is None else (frozenset((min(pairs[0]), min(pairs[1]))),
                                           frozenset((max(pairs[0]), max(pairs[1]))))

    monkeypatch.setattr(nodes, "joined", other_way)
    swapped = certify(a, b, [first, second], curves[0].topology, 3.0)
    assert not swapped.proven and not swapped.claims["one_component"].proven
    assert "arcs that join" in swapped.claims["one_component"].detail


def villarceau():
    """A ring torus (R = 1, r = 0.5) and its bitangent plane through the centre (turned about x by asin(r / R)):
    the two Villarceau circles of radius R about (+-r, 0, 0), crossing at two nodes."""
    tilt = math.asin(0.5)
    return sk.Torus(1.0, 0.5), sk.Plane(sk.Frame((0.0, 0.0, 0.0), sk.rotation_about((1.0, 0.0, 0.0), tilt)),
                                        u_range=(-3.0, 3.0), v_range=(-3.0, 3.0))


def test_circles_crossing_at_nodes_are_proven_apart_from_the_nodes():
    """The Villarceau circles: the arcs proven, the two nodes (0, +-0.75, +-0.433) proven saddles with four branches
    each in proven tubes; the curves are not proven distinct (they meet at the nodes). (Completeness is not: each
    circle touches the torus chart's seam, the inner equator, where the search cannot resolve the double root.)
    Oracle: every point of the dense output lies on one of the two circles (1e-12), and each curve is 2 pi R long
    (1e-8; the tracer may turn from one circle to the other at a node)."""
    torus, plane = villarceau()
    curves = sk.intersect(torus, plane, certify=True)
    cert = curves.certificate
    assert len(curves) == 2
    for curve in curves:
        p = curve(np.linspace(0.0, curve.length, 400))
        off = np.minimum(*(np.abs(np.linalg.norm(p - c, axis=1) - 1.0) for c in ([0.5, 0, 0], [-0.5, 0, 0])))
        assert off.max() < 1e-12 and abs(curve.length - 2 * math.pi) < 1e-8
    assert cert.claims["arcs"].proven and cert.claims["points"].proven
    assert not cert.claims["distinct"].proven and "node" in cert.claims["distinct"].detail
    singular = cert.claims["singular"]
    assert "four branches" in singular.detail and len(singular.where) == 2 and np.all(singular.radius < 0.1)
    assert np.allclose(np.abs(singular.where), [0.0, 0.75, math.sqrt(0.1875)], atol=1e-9)


def test_a_circle_dropped_at_the_nodes_leaves_branches_unaccounted():
    """One Villarceau curve alone: the other's branches leave the node boxes through no proven tube, so the arcs
    around the nodes are not proven (nor, then, is anything inside the nodes' boxes)."""
    torus, plane = villarceau()
    curves = sk.intersect(torus, plane, certify=True)
    cert = certify(torus, plane, [curves[0].result], curves[0].topology, 1.0)
    arcs = cert.claims["arcs"]
    assert not cert.proven and not cert.claims["complete"].proven and not arcs.proven
    assert "no proven tube" in arcs.detail


@pytest.mark.slow
def test_stress_cases_certified_never_lie():
    """Every eighth case of the stress suite run with certify=True (tests.oracles.certified_stress): no answer
    proven with a number of components other than the oracle's; most are proven."""
    from tests.oracles.certified_stress import run
    from tests.oracles.ssi_cases import all_cases
    rows, _ = run(all_cases()[::8], echo=lambda line: None)
    assert sum(r["lies"] for r in rows.values()) == 0
    cases = sum(r["cases"] for r in rows.values())
    assert sum(r["proven"] for r in rows.values()) >= 0.5 * cases


def test_rulings_crossing_at_an_apex_are_proven_apart_from_the_apex():
    """A plane through a cone's apex along its axis: two rulings crossing at the apex. The cone's chart collapses
    there, so the certificate reads the pair in the plane's chart, where the apex is a node: the arcs on either side
    are proven (a chain of pieces into the node's box); completeness and the node are not (the searches leave the
    apex unresolved), nor which rulings join there. Oracle: every point of the dense output lies on one of the two
    rulings (closed form: the axis turned by the half angle in the plane, 1e-12), and the distance bound covers
    that."""
    half, apex = math.radians(30), np.array([0.2, -0.1, 0.3])
    cone = sk.Cone(half, sk.Frame(apex), v_range=(-2.0, 2.0))
    plane = sk.Plane(sk.Frame(apex, sk.rotation_about((1, 0, 0), math.radians(90))), u_range=(-3, 3), v_range=(-3, 3))
    rulings = [np.array([math.sin(half) * side, 0.0, math.cos(half)]) for side in (1.0, -1.0)]
    for pair in ((cone, plane), (plane, cone)):
        plain = sk.intersect(*pair)
        curves = sk.intersect(*pair, certify=True)
        cert = curves.certificate
        assert len(curves) == len(plain) == 2 and not cert.proven
        assert cert.claims["arcs"].proven and cert.claims["points"].proven
        for name in ("complete", "singular", "one_component"):
            assert not cert.claims[name].proven
        assert "node" in cert.claims["one_component"].detail
        for curve, bound in zip(curves, cert.distance_bounds):
            p = curve(np.linspace(0.0, curve.length, 200)) - apex
            off = np.min([np.linalg.norm(p - np.outer(p @ r, r), axis=1) for r in rulings], axis=0)
            assert off.max() < 1e-12 and off.max() <= bound < math.inf


def test_a_whole_circle_across_the_trims_is_not_one_component():
    """The untrimmed circle given as the answer for the strip: its closed tube leaves the strip, so it is not one
    component of the trimmed patches."""
    a, b = strip_pair()
    topology = sk.intersect(a, b, certify=True)[0].topology
    circle = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.3))), certify=True)[0].result
    cert = certify(a, b, [circle], topology, 1.0)
    assert not cert.proven and not cert.claims["one_component"].proven
    assert "inside a trim" in cert.claims["one_component"].detail


def test_an_apex_on_the_other_surface_is_read_in_the_other_chart():
    """A cone whose apex lies on a sphere: in the cone's chart, which collapses at the apex, the search leaves a thin
    band round it out; the certificate reads the pair in the sphere's chart instead, where the apex is a point of the
    level: completeness, one component and distinctness are proven, and the apex is said as a contact with a ball
    (not decided: a point or a tiny loop). Oracle: the brute-force search of the test oracles finds as many
    components (the loop and the apex)."""
    from tests.oracles.ssi import brute_force, curve_components, dense_points
    apex = np.array([0.3, 0.7, 0.8])
    cone = sk.Cone(0.5, sk.Frame(apex, sk.rotation_about((1, 0, 0), 0.4)), v_range=(-2.0, 2.0))
    sphere = sk.Sphere(1.0, sk.Frame((0.3, 0.1, 0.0)))
    for pair in ((cone, sphere), (sphere, cone)):
        curves = sk.intersect(*pair, certify=True)
        claims = curves.certificate.claims
        assert all(claims[name].proven for name in ("complete", "one_component", "distinct", "arcs"))
        assert not claims["singular"].proven and any(np.allclose(w, apex, atol=1e-9) for w in claims["singular"].where)
        count, _ = curve_components(curves, 1.0, 2e-6, [dense_points(c, 1.0) for c in curves])
        assert count == brute_force(*pair)["count"] == 2


def test_a_contact_given_twice_is_not_distinct():
    """The contact point of a sphere touching a torus given twice: the two isolation boxes are the same, so the
    curves are not proven distinct (each contact's box stands for its tube)."""
    a, b = sk.Torus(1.0, 0.4), sk.Sphere(0.5, sk.Frame((1.9, 0.0, 0.0)))
    curves = sk.intersect(a, b, certify=True)
    cert = certify(a, b, [curves[0].result, curves[0].result], curves[0].topology, 0.5)
    assert not cert.claims["distinct"].proven and "overlap" in cert.claims["distinct"].detail


@pytest.mark.parametrize("axis_tilt, kind", [(0.2, "within"), (1.3, "saddle")])
def test_an_apex_on_the_other_surface_gets_a_proven_ball(axis_tilt, kind):
    """A cone's apex placed on a sphere: with the axis near the sphere's
    normal there, the tangent plane misses the cone and the apex is an isolated point of the intersection (a ball
    proven around it, holding all of the intersection nearby); tilted past the half angle, two branches cross there
    (a proven saddle; read in the sphere's chart, it is also a node whose box the tubes reach). Either way the claim
    is not proven, the apex has a ball smaller than 1e-6, and every ball said round it holds the true apex."""
    apex = np.array([0.6, 0.0, 0.8])                     # (off the sphere's poles, on it to round-off)
    axis = sk.rotation_about((0, 1, 0), axis_tilt) @ apex
    cone = sk.Cone(0.5, sk.Frame.from_z_axis(apex, axis), v_range=(-2.0, 2.0))
    for pair in ((cone, sk.Sphere(1.0)), (sk.Sphere(1.0), cone)):
        singular = sk.intersect(*pair, certify=True).certificate.claims["singular"]
        assert not singular.proven and kind in singular.detail
        near = [r for w, r in zip(singular.where, singular.radius) if np.linalg.norm(w - apex) < 1e-6]
        assert near and all(np.isfinite(r) for r in near) and min(near) < 1e-6
        assert all(np.linalg.norm(w - apex) <= r for w, r in zip(singular.where, singular.radius)
                   if np.linalg.norm(w - apex) < 1e-6)


#: Pair kinds whose 1e-6 tiny loop of the stress suite is proven: the closed forms' (the search's enclosures of the
#: level, padded for the placement's round-off, are too wide for the marching kinds' there).
PROVEN_AT_1E_6 = ("plane-sphere", "sphere-sphere", "plane-cone")


def test_tiny_loops_are_proven_or_said_not_to_be():
    """The stress suite's tiny loops of 1e-6 to 1e-3 of the scene (every pair kind): every answer proven has the
    oracle's one loop; those of 1e-5 and more are all proven (the search's roots on them placed in their tubes by
    boxes shrunk around them), and at 1e-6 those of PROVEN_AT_1E_6."""
    from tests.oracles.ssi_cases import all_cases
    tiny = [c for c in all_cases() if c.family == "tiny"]
    assert len(tiny) == 40
    for case in tiny:
        curves = sk.intersect(case.a, case.b, certify=True)
        if curves.certificate.proven:
            assert len(curves) == case.count, case.name
        if not case.name.endswith("1e-06") or case.name.split("/")[1] in PROVEN_AT_1E_6:
            assert curves.certificate.proven, (case.name, curves.certificate.failed)


def test_arcs_crossing_a_trim_edge_at_a_shallow_angle_are_proven():
    """Stress cases whose arcs leave a cylinder's or cone's rim at a shallow angle in a long end piece (the edge's
    rate over the whole piece holds 0; over its stretches, with the arc's own enclosure, it does not): proven, with
    the oracle's number of curves, moved 1e5 away and scaled by 1e-4 too."""
    from tests.oracles.ssi import curve_components, dense_points
    from tests.oracles.ssi_cases import all_cases, truth_of
    names = ("random/sphere-cone/5", "random/cylinder-cone/0", "scaled/random/cylinder-cone/0/x1e-4",
             "scaled/random/cylinder-cone/0/+1e5")
    every = all_cases()
    by_name = {c.name: c for c in every}
    for name in names:
        case = by_name[name]
        truth = truth_of(case, by_name, {})["count"]
        curves = sk.intersect(case.a, case.b, certify=True)
        assert curves.certificate.proven, (name, curves.certificate.failed)
        count, _ = curve_components(curves, case.scale, 2e-6, [dense_points(c, case.scale) for c in curves])
        assert count == truth, name


def plane_along_a_ruling(gap):
    """A cone of half-angle 0.6 (trimmed to 0.2 <= v <= 1.5) and a plane parallel to its tangent plane along the
    ruling in the xz-plane, gap inside it: the plane meets the cone in a parabola whose two arms run beside that
    ruling, about sqrt(gap) apart, each cut by the trims to the ruling's length 1.3 / cos 0.6 (to O(gap))."""
    k = math.tan(0.6)
    n = np.array([1.0, 0.0, -k]) / math.hypot(1.0, k)
    x = np.array([k, 0.0, 1.0]) / math.hypot(1.0, k)
    plane = sk.Plane(sk.Frame(-gap * n, np.column_stack([x, (0.0, -1.0, 0.0), n])), u_range=(0.0, 2.0),
                     v_range=(-1.0, 1.0))
    return plane, sk.Cone(0.6, v_range=(0.2, 1.5))


@pytest.mark.parametrize("gap", [1e-10, 1e-12, 1e-14])
def test_arms_beside_a_ruling_are_proven_right_or_refused_within_the_work_budget(gap, monkeypatch):
    """Tubes along arms sqrt(gap) apart need pieces narrower than that, so their count grows as the gap closes:
    no chain takes more than its budget of pieces tried and samples (counted over all its attempts), and an answer
    certified proven has both arms at the ruling's length (1e-6)."""
    from spatialkin.tracing.certify import tubes
    work, chain = [], tubes.chain

    def counted(chart, x, closed, shift, per_chord=tubes.PIECES_PER_CHORD):
        out = chain(chart, x, closed, shift, per_chord)
        work.append(out[3] + len(x))
        return out

    monkeypatch.setattr(tubes, "chain", counted)
    curves = sk.intersect(*plane_along_a_ruling(gap), certify=True)
    assert sum(work) <= 2 * (tubes.MOST_WORK + tubes.MOST_PIECES + tubes.MOST_SAMPLES)
    if curves.certificate.proven:
        assert len(curves) == 2
        np.testing.assert_allclose([c.length for c in curves], 1.3 / math.cos(0.6), rtol=0, atol=1e-6)


def test_a_tube_out_of_its_work_budget_is_not_proven(monkeypatch):
    """Arms 1e-11 apart (relative) are proven with the whole budget; with a budget of 20 000 pieces and samples
    the arcs' claim fails and says the tube ran out of its work budget."""
    from spatialkin.tracing.certify import tubes
    assert sk.intersect(*plane_along_a_ruling(1e-11), certify=True).certificate.proven
    monkeypatch.setattr(tubes, "MOST_WORK", 20_000)
    certificate = sk.intersect(*plane_along_a_ruling(1e-11), certify=True).certificate
    assert not certificate.proven and not certificate.claims["arcs"].proven
    assert "work budget" in certificate.claims["arcs"].detail
