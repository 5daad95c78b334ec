"""Face trims in the certificate (spatialkin.tracing.certify.faces): answers cut by angular ranges, latitudes and a
plane's disc or annulus proven claim by claim, each checked against the brute-force oracle's components and the
faces' own inside test; answers made wrong on purpose (an arc dropped, cut short, run past its edge, or returned
uncut) are not proven."""
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

    def spy(a, b, results, topo, scale, tolerance, mode, failure=None, proof=None, wholes=None):
        seen.update(results=results, topo=topo, scale=scale, tolerance=tolerance, wholes=wholes)
        return real(a, b, results, topo, scale, tolerance, mode, failure, proof, wholes)

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


def test_faces_of_a_re_framed_chart_are_said_not_proven():
    """A sphere's angular range where the search reads the sphere in a turned chart of its own: not proven, the
    claims say why, and strict raises."""
    pair = (sk.Sphere(1.0, u_range=(-1.0, 1.0)), sk.Plane(sk.Frame((0.0, 0.0, 0.3))))
    curves = sk.intersect(*pair, certify=True)
    assert len(curves) == 1 and not curves.certificate.proven
    assert "re-framed" in curves.certificate.claims["complete"].detail
    with pytest.raises(sk.CertificationError):
        sk.intersect(*pair, certify="strict")


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
