"""Face trims in the certificate (spatialkin.tracing.certify.faces): answers cut by angular ranges, latitudes and a
plane's disc or annulus proven claim by claim, each checked against the brute-force oracle's components and the
faces' own inside test; answers made wrong on purpose (an arc dropped, cut short, run past its edge, or returned
uncut) are not proven."""
import dataclasses
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.geometry.trims import inside_region, limits
from spatialkin.tracing import components
from spatialkin.tracing.certify.certificate import certify
from spatialkin.tracing.curve.clip import window
from tests.oracles.ssi import brute_force, curve_components, dense_points

HALF = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, math.pi))
PAIRS = {
    "half cylinder, tilted plane": (HALF, sk.Plane(sk.Frame((0.0, 0.0, 2.0), sk.rotation_about((1, 0.3, 0), 0.4)))),
    "half cylinder, sphere": (HALF, sk.Sphere(1.2, sk.Frame((0.5, 0.2, 2.0)))),
    "three-quarter cylinder, sphere": (sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, 1.5 * math.pi)),
                                       sk.Sphere(1.2, sk.Frame((0.5, 0.2, 2.0)))),
    "quarter torus, sphere": (sk.Torus(8.0, 3.0, u_range=(0.0, math.pi / 2)),
                              sk.Sphere(4.0, sk.Frame((6.0, 6.0, 0.5)))),
    "disc, cylinder": (sk.Plane(sk.Frame((0.0, 0.0, 1.0)), radius=1.0),
                       sk.Cylinder(0.5, sk.Frame((0.8, 0, 0), sk.rotation_about((1, 0, 0), 0.3)), v_range=(-3, 3))),
    "annulus, sphere": (sk.Plane(sk.Frame((0.0, 0.0, 0.3)), radius=2.0, inner_radius=0.5),
                        sk.Sphere(1.0, sk.Frame((0.6, 0, 0)))),
    "torus outer band, sphere": (sk.Torus(8.0, 3.0, v_range=(-1.0, 1.0)), sk.Sphere(4.0, sk.Frame((8.0, 0.0, 0.0)))),
    "sphere band, cylinder": (sk.Sphere(2.0, v_range=(-0.3, 0.5)),
                              sk.Cylinder(0.8, sk.Frame((1.5, 0, 0), sk.rotation_about((0, 1, 0), 0.2)),
                                          v_range=(-5, 5))),
}


@pytest.mark.parametrize("name", sorted(PAIRS))
def test_face_trimmed_answers_are_proven_and_right(name):
    """Both argument orders proven; the brute-force oracle's number of components; every dense point inside both
    faces (their own limits, within 1e-9); the proven distance bound below 1e-9."""
    a, b = PAIRS[name]
    truth = brute_force(a, b)["count"]
    for pair in ((a, b), (b, a)):
        curves = sk.intersect(*pair, certify=True)
        assert curves.certificate.proven, curves.certificate.failed
        dense = [dense_points(c, 1.0) for c in curves]
        count, _ = curve_components(curves, 1.0, 2e-6, dense)
        assert count == truth
        for points in dense:
            assert inside_region(a, points, 1e-9).all() and inside_region(b, points, 1e-9).all()
        assert max(curves.certificate.distance_bounds) < 1e-9


def parts(monkeypatch, a, b):
    """(returned CurveResults, topology, scale, tolerance, components before the cut) of sk.intersect(a, b,
    certify=True), read where intersect hands them to the certificate."""
    seen = {}
    real = components.certified

    def spy(a, b, results, topo, scale, tolerance, mode, failure=None, proof=None, wholes=None, given=None):
        seen.update(results=results, topo=topo, scale=scale, tolerance=tolerance, wholes=wholes)
        return real(a, b, results, topo, scale, tolerance, mode, failure, proof, wholes, given)

    monkeypatch.setattr(components, "certified", spy)
    sk.intersect(a, b, certify=True)
    return seen["results"], seen["topo"], seen["scale"], seen["tolerance"], seen["wholes"]


def proven(a, b, answer, topo, scale, tolerance, wholes):
    return certify(a, b, answer, topo, scale, tolerance, wholes=wholes).proven


def test_the_answer_as_given_is_proven(monkeypatch):
    """The spy's parts, certified again as they are: proven (the tests below change one thing each)."""
    a, b = PAIRS["sphere band, cylinder"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    assert len(answer) == 2 and proven(a, b, answer, topo, scale, tolerance, wholes)


def test_a_dropped_arc_is_not_complete(monkeypatch):
    """Of two arcs cut by a sphere's latitudes, one dropped: the arcs inside the faces are not all returned."""
    a, b = PAIRS["sphere band, cylinder"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    cert = certify(a, b, answer[:1], topo, scale, tolerance, wholes=wholes)
    assert not cert.proven and not cert.claims["complete"].proven


#: Narrow faces (from the angle, its width) and the sphere radius that cuts them (centred off the axis).
NARROW = {"cylinder": (lambda lo, w: sk.Cylinder(1.0, v_range=(-2.0, 2.0), u_range=(lo, lo + w)), 1.5),
          "torus": (lambda lo, w: sk.Torus(2.0, 1.0, u_range=(lo, lo + w)), 2.5),
          "torus tube": (lambda lo, w: sk.Torus(2.0, 1.0, v_range=(1.25 + lo, 1.25 + lo + w)), 2.5)}


@pytest.mark.parametrize("width", [1e-4, 5e-3, 0.1])
@pytest.mark.parametrize("kind", sorted(NARROW))
def test_narrow_faces_are_proven_and_a_dropped_arc_is_not(monkeypatch, kind, width):
    """Faces 1e-4 to 0.1 rad wide, narrower than a chord of their components' tubes (a tube's pieces then held both
    crossings of one arc, and nothing was proven): each arc inside gets samples of its own, so the answer is
    proven; the answer less one arc is not (complete). The arcs lie inside the face by the oracle's atan2 margin."""
    face, radius = NARROW[kind]
    a, b = face(0.0 if kind == "torus tube" else 0.3, width), sk.Sphere(radius, sk.Frame((0.1, 0.05, 0.02)))
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    assert len(answer) >= 2 and proven(a, b, answer, topo, scale, tolerance, wholes)
    from tests.oracles.ssi import face_margin, to_local
    assert all(face_margin(a, to_local(a, c.points)).min() >= -1e-12 for c in answer)
    cert = certify(a, b, answer[1:], topo, scale, tolerance, wholes=wholes)
    assert not cert.proven and not cert.claims["complete"].proven


def test_an_uncut_component_is_not_proven(monkeypatch):
    """The component returned whole instead of its arc inside the half cylinder: not one arc between crossings."""
    a, b = PAIRS["half cylinder, sphere"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    assert len(answer) == 1 and len(wholes) == 1
    cert = certify(a, b, list(wholes), topo, scale, tolerance, wholes=wholes)
    assert not cert.proven and not cert.claims["one_component"].proven


@pytest.mark.parametrize("move", [-0.05, 0.05])
def test_an_arc_cut_off_its_edge_is_not_proven(monkeypatch, move):
    """The arc's start moved along its component by 0.05 (past the face's edge, or short of it): its end is no
    proven crossing of a face edge."""
    a, b = PAIRS["half cylinder, sphere"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    arc, whole = answer[0], wholes[0]
    start, end = arc.sol.start, arc.sol.start + arc.length
    edge = limits(a)[0]
    moved = window(whole, (start + move, edge, 0), (end, edge, 0))
    assert abs(moved.length - arc.length + move) < 1e-12
    cert = certify(a, b, [moved], topo, scale, tolerance, wholes=wholes)
    assert not cert.proven and not cert.claims["one_component"].proven


def test_faces_of_a_sphere_searched_in_a_turned_chart_are_proven():
    """A sphere's angular range |u| <= 1 where the search reads the sphere in a turned chart of its own (its limits
    read through the chart's placement in the sphere's frame): the arc of the circle of radius rho = sqrt(0.91) at
    z = 0.3, proven, of length 2 rho (1e-12), its ends at u = -1 and 1 (1e-12)."""
    sphere = sk.Sphere(1.0, u_range=(-1.0, 1.0))
    for pair in ((sphere, sk.Plane(sk.Frame((0.0, 0.0, 0.3)))), (sk.Plane(sk.Frame((0.0, 0.0, 0.3))), sphere)):
        curves = sk.intersect(*pair, certify=True)
        assert len(curves) == 1 and curves.certificate.proven, curves.certificate.failed
        rho = math.sqrt(0.91)
        assert abs(curves[0].length - 2.0 * rho) < 1e-12
        ends = curves[0].points[[0, -1]]
        assert np.allclose(np.sort(np.arctan2(ends[:, 1], ends[:, 0])), [-1.0, 1.0], atol=1e-12, rtol=0)


def test_a_loop_outside_a_face_leaves_a_proven_empty_answer():
    """A loop of the sphere and the cylinder lying wholly outside the half cylinder (y < 0): nothing returned,
    proven (the component is proven outside the face along its tube)."""
    a = sk.Cylinder(1.0, v_range=(0.0, 4.0), u_range=(0.0, math.pi))
    b = sk.Sphere(0.5, sk.Frame((0.0, -1.0, 2.0)))
    full = sk.intersect(sk.Cylinder(1.0, v_range=(0.0, 4.0)), b)
    assert len(full) == 1 and np.all(full[0].points[:, 1] < 0.0)
    curves = sk.intersect(a, b, certify=True)
    assert curves == [] and curves.certificate.proven, curves.certificate.failed


def test_an_arc_run_once_round_its_loop_more_is_not_proven(monkeypatch):
    """The arc inside the half cylinder run on for one more turn of its closed component, from the same crossing to
    the same crossing: longer than its component, not proven."""
    a, b = PAIRS["half cylinder, sphere"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    arc, whole = answer[0], wholes[0]
    assert whole.closed
    edge = limits(a)[0]
    longer = window(whole, (arc.sol.start, edge, 0), (arc.sol.start + arc.length + whole.length, edge, 0))
    cert = certify(a, b, [longer], topo, scale, tolerance, wholes=wholes)
    assert not cert.proven and not cert.claims["one_component"].proven


def test_an_arc_run_past_its_edges_is_not_proven_or_bounded(monkeypatch):
    """The arc inside the half cylinder run on past both face edges along its component: by 1e-5, not proven (its
    ends are not on the edges); by 1e-9, proven only with a distance bound at least the ends' distance from the
    crossings (the measured distance of the moved ends from the true ones)."""
    a, b = PAIRS["half cylinder, sphere"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    arc, whole = answer[0], wholes[0]
    edge = limits(a)[0]
    for move in (1e-5, 1e-9):
        moved = window(whole, (arc.sol.start - move, edge, 0), (arc.sol.start + arc.length + move, edge, 0))
        cert = certify(a, b, [moved], topo, scale, tolerance, wholes=wholes)
        if move > 1e-7:
            assert not cert.proven and not cert.claims["one_component"].proven
        else:
            shift = np.max(np.linalg.norm(moved.points[[0, -1]] - arc.points[[0, -1]], axis=1))
            assert not cert.proven or cert.distance_bounds[0] >= shift


def test_forged_stored_points_of_an_arc_are_not_proven(monkeypatch):
    """The arc's dense output kept, its stored points replaced by points of its component outside the face (its
    ends kept, or all of them with its tolerance raised to 1), or the arc flagged closed: not proven."""
    a, b = PAIRS["half cylinder, sphere"]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    arc, whole = answer[0], wholes[0]
    outside = np.linspace(arc.sol.start + arc.length + 0.3, arc.sol.start + whole.length - 0.3, len(arc.points))
    elsewhere = whole.sol(outside % whole.length)
    inner = arc.points.copy()
    inner[1:-1] = elsewhere[1:-1]
    assert not inside_region(a, elsewhere, 1e-9).any()
    for forged in (dataclasses.replace(arc, points=inner), dataclasses.replace(arc, points=elsewhere, tolerance=1.0),
                   dataclasses.replace(arc, closed=True)):
        cert = certify(a, b, [forged], topo, scale, tolerance, wholes=wholes)
        assert not cert.proven and not cert.claims["one_component"].proven


def test_an_arc_stopped_short_of_its_components_end_is_not_proven(monkeypatch):
    """A half cylinder of height 2 and the sphere: the component ends on the cylinder's rim; its arc inside the face
    stopped 9e-8 short of that end (less than the proven crossing's tolerance) is not proven."""
    a = sk.Cylinder(1.0, v_range=(0.0, 2.0), u_range=(0.0, math.pi))
    b = PAIRS["half cylinder, sphere"][1]
    answer, topo, scale, tolerance, wholes = parts(monkeypatch, a, b)
    assert proven(a, b, answer, topo, scale, tolerance, wholes)
    arc = next(c for c in answer if any(abs(c.sol.start + c.length - w.length) < 1e-12 or c.sol.start == 0.0
                                        for w in wholes if w.sol is c.sol.whole))
    whole = next(w for w in wholes if w.sol is arc.sol.whole)
    lo, hi = arc.sol.start, arc.sol.start + arc.length
    lo, hi = (lo + 9e-8, hi) if lo == 0.0 else (lo, hi - 9e-8)
    short = window(whole, (lo, None, None), (hi, None, None))
    rest = [c for c in answer if c is not arc]
    cert = certify(a, b, [short] + rest, topo, scale, tolerance, wholes=wholes)
    assert not cert.proven
