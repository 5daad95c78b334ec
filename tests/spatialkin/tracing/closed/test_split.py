"""Quadric pairs whose intersection splits into two ellipses through nodes, in closed form
(spatialkin.tracing.closed.split): against the general path (the topology stage and the tracer, closed forms off) as the
oracle, and against the Steinmetz curves' own closed form (nodes, ellipse lengths)."""
import math

import numpy as np
import pytest
from tests.oracles.closed_forms import random_rotation
from scipy.special import ellipe

import spatialkin as sk
from spatialkin.tracing import components as intersect_module

SCALE_TOL = 1e-14        # points on both surfaces, relative to the scale
LENGTH_RTOL = 1e-9       # lengths against the traced oracle (its arc length is integrated at rtol 1e-10)


def scenes():
    """(name, a, b): equal cylinders with crossing axes (perpendicular and oblique, trims cutting through one
    ellipse), a cylinder and a cone sharing an inscribed sphere, two cones sharing one."""
    rng = np.random.default_rng(7)
    out = []
    for k, angle in enumerate((math.pi / 2, 0.9)):
        rot = random_rotation(rng)
        o = rng.uniform(-2, 2, 3)
        tilt = sk.rotation_about(rot[:, 1], angle) @ rot
        a = sk.Cylinder(0.7, sk.Frame(o, rot), v_range=(-3.0, 3.0))
        b = sk.Cylinder(0.7, sk.Frame(o, tilt), v_range=(-0.5, 3.0) if k else (-3.0, 3.0))
        out.append((f"steinmetz-{k}", a, b))
    rot = random_rotation(rng)
    o = rng.uniform(-2, 2, 3)
    r, d = 0.8, 2.0
    axis = rot[:, 0]
    cone_rot = np.column_stack([rot[:, 1], rot[:, 2], axis])
    out.append(("monge-cylinder-cone", sk.Cylinder(r, sk.Frame(o, rot), v_range=(-3.0, 3.0)),
                sk.Cone(math.asin(r / d), sk.Frame(o - d * axis, cone_rot), v_range=(0.5, 4.0))))
    other = sk.rotation_about(rot[:, 1], 1.1) @ cone_rot
    out.append(("monge-cone-cone", sk.Cone(math.asin(r / d), sk.Frame(o - d * axis, cone_rot), v_range=(0.5, 4.0)),
                sk.Cone(math.asin(r / 2.5), sk.Frame(o - 2.5 * other[:, 2], other), v_range=(0.5, 5.0))))
    return out


def traced(a, b, monkeypatch):
    with monkeypatch.context() as m:
        m.setattr(intersect_module, "CLOSED_FORMS", False)
        return sk.intersect(a, b)


@pytest.mark.parametrize("name, a, b", scenes(), ids=[s[0] for s in scenes()])
def test_split_pairs_match_the_general_path(name, a, b, monkeypatch):
    """Each order: in closed form (no right-hand-side evaluations), the same curves as the general path: count,
    statuses, lengths (1e-9), nodes per curve (the same points, 1e-9 x scale); every point on both surfaces."""
    scale = 0.7 if name.startswith("steinmetz") else 0.8
    for first, second in ((a, b), (b, a)):
        fast, oracle = sk.intersect(first, second), traced(first, second, monkeypatch)
        assert len(fast) == len(oracle) >= 2
        assert all(c.nfev == 0 for c in fast) and all(c.nfev > 0 for c in oracle)
        for c, o in zip(sorted(fast, key=lambda c: c.length), sorted(oracle, key=lambda c: c.length)):
            assert c.status == o.status and c.closed == o.closed
            assert abs(c.length - o.length) <= LENGTH_RTOL * o.length
            assert c.max_distance <= SCALE_TOL * scale
            assert len(c.nodes) == len(o.nodes)
            for node in o.nodes:
                assert np.min(np.linalg.norm(c.nodes - node, axis=1)) <= 1e-9 * scale
            # the dense output passes through its nodes
            s = np.linspace(0.0, c.length, 4001)
            for node in c.nodes:
                assert np.min(np.linalg.norm(c(s) - node, axis=1)) <= 2e-3 * scale


def test_steinmetz_closed_form():
    """Perpendicular equal cylinders (radius r, axes crossing): two ellipses of semi-axes r and r sqrt(2) (length
    4 r sqrt(2) E(1/2)), both through the two nodes at r along the common perpendicular, to round-off."""
    rot = random_rotation(np.random.default_rng(3))
    o, r = np.array([0.4, -1.0, 0.2]), 1.3
    a = sk.Cylinder(r, sk.Frame(o, rot))
    b = sk.Cylinder(r, sk.Frame(o, np.column_stack([rot[:, 1], rot[:, 2], rot[:, 0]])), v_range=(-5.0, 5.0))
    curves = sk.intersect(a, b)
    exact = 4.0 * r * math.sqrt(2.0) * ellipe(0.5)
    nodes = np.array([o + r * rot[:, 1], o - r * rot[:, 1]])
    assert len(curves) == 2
    for c in curves:
        assert c.closed and c.status == "closed" and c.nfev == 0
        assert abs(c.length - exact) <= 1e-14 * exact
        assert len(c.nodes) == 2
        assert max(np.min(np.linalg.norm(c.nodes - n, axis=1)) for n in nodes) <= 1e-14 * r


@pytest.mark.parametrize("offset", [1e-9, 1e-6])
def test_near_split_pairs_take_the_general_path(offset, monkeypatch):
    """Radii 1 and 1 - offset: the planes of the two cylinders' difference of squares cut ellipses lying about the
    offset off the other cylinder, beyond the split's fit (SPLIT_FIT = 1e-13 x scale), so the pair is traced: two
    loops passing a waist, as the general path finds them."""
    rot = random_rotation(np.random.default_rng(5))
    o = np.array([0.1, 0.2, -0.3])
    a = sk.Cylinder(1.0, sk.Frame(o, rot), v_range=(-3.0, 3.0))
    b = sk.Cylinder(1.0 - offset, sk.Frame(o, np.column_stack([rot[:, 1], rot[:, 2], rot[:, 0]])),
                    v_range=(-3.0, 3.0))
    curves = sk.intersect(a, b)
    assert len(curves) == 2 and all(c.nfev > 0 and len(c.nodes) == 0 for c in curves)


def test_axes_missing_by_1e_12_take_the_general_path():
    """Equal cylinders whose axes miss each other by 1.4e-12 of the radius: they pass the crossing test (within
    AXES_GAP), but the planes' ellipses lie about 1e-12 x scale off the surfaces, beyond the split's fit (SPLIT_FIT =
    1e-13 x scale): the pair is traced, one closed loop through a waist, not two ellipses."""
    a = sk.Cylinder(94.57052564861789, sk.Frame(
        [1353.2678431571949, -2387.5946620871246, -1600.3622979617073],
        [[0.7800252477520986, 0.4272470765078407, -0.4571876512820313],
         [0.21480940712346172, 0.5033990822167108, 0.8369266889248066],
         [0.5877223251506989, -0.751032156194977, 0.30088730262438745]]),
        v_range=(-782.7284790805767, 525.5265277088945))
    b = sk.Cylinder(94.57052564861789, sk.Frame(
        [1283.3316068619595, -2490.6013033854665, -1640.1609520825164],
        [[0.16042999218244255, -0.037761356225052826, -0.9863246410712784],
         [-0.9576422565524837, -0.24804617995757972, -0.14626825039467317],
         [-0.23913077190819307, 0.9680119692361745, -0.07595591709732102]]))
    curves = sk.intersect(a, b)
    assert len(curves) == 1 and curves[0].closed and curves[0].nfev > 0 and len(curves[0].nodes) == 0
    assert curves[0].max_distance <= 1e-14 * a.radius


def test_a_trim_through_both_nodes():
    """Equal cylinders with crossing axes, b's trim passing exactly through both nodes: in either order two arcs,
    each listing both nodes (at its ends), inside b's trim to round-off: 8 ulps of the trim's bounds (the arc's ends
    are the edge's crossings of an ellipse whose plane is known to a few ulps of the coordinates)."""
    a = sk.Cylinder(0.0030864655572198463, sk.Frame(
        [-0.005240491689181651, -0.00326973829279299, -0.006688478077075634],
        [[0.2960055335119358, -0.3163746880178444, -0.9012700932084267],
         [-0.7968238493062175, 0.4385355061637703, -0.4156421092845478],
         [0.5267375791674034, 0.841185869243711, -0.12228596026349896]]))
    b = sk.Cylinder(0.0030864655572198463, sk.Frame(
        [-0.013145632202375291, -0.004178989381569043, -0.005467704828156544],
        [[0.15760193548415166, 0.2099763047935231, -0.9649205052007688],
         [-0.7453483893428486, 0.6662696958798612, 0.02324802908158952],
         [0.6477788267886427, 0.7155380100158305, 0.26151089420311896]]),
        v_range=(-0.005843944592629173, 0.006501917636250212))
    lo, hi = b.v_range
    roundoff = 8.0 * np.finfo(float).eps * max(abs(lo), abs(hi))
    for first, second in ((a, b), (b, a)):
        curves = sk.intersect(first, second)
        assert len(curves) == 2 and all(c.nfev == 0 for c in curves)
        assert [len(c.nodes) for c in curves] == [2, 2]
        for c in curves:
            v = (c(np.linspace(0.0, c.length, 2001)) - b.frame.origin) @ b.frame.rotation[:, 2]
            assert lo - v.min() <= roundoff and v.max() - hi <= roundoff


def test_split_planes_finds_every_splitting_scene_and_refuses_general_pairs():
    """split_planes (a sphere inscribed in both quadrics about their axes' crossing) finds the planes of every
    splitting scene above, in either order, and refuses the bench's general pairs of quadrics (which do not split:
    the general path finds single loops in them)."""
    from spatialkin.bench.kinds import pair_kind_cases
    from spatialkin.tracing.closed.forms import Placed
    from spatialkin.tracing.closed.split import split_planes

    def quadrics(a, b):
        return [(p.name, p.origin, p.rot, p.form) for p in (Placed(a), Placed(b))]

    for _, a, b in scenes():
        for first, second in ((a, b), (b, a)):
            cuts, nodes = split_planes(quadrics(first, second), 0.7)
            assert len(cuts) == 2 and len(nodes) in (1, 2)
    for name, a, b in pair_kind_cases():
        if "plane" in name or "torus" in name or name == "sphere-sphere":
            continue
        assert split_planes(quadrics(a, b), 1.0) is None


def tangent_ruling_scene(rng, alpha=0.6, r=0.9):
    """A cylinder (radius r) and a cone (half angle alpha) touching all along a ruling: the cone's apex on the
    cylinder, its axis through the cylinder's axis at r / sin(alpha) from the apex (so the ruling through the apex
    parallel to the cylinder's axis lies on both), in a random frame; and that ruling (point, direction)."""
    rot, o = random_rotation(rng), rng.uniform(-2, 2, 3)
    h = r / math.tan(alpha)
    apex_local = np.array([r, 0.0, h])
    axis_local = -apex_local / np.linalg.norm(apex_local)
    e1 = np.cross(axis_local, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    cone_rot = rot @ np.column_stack([e1, np.cross(axis_local, e1), axis_local])
    cylinder = sk.Cylinder(r, sk.Frame(o, rot), v_range=(-4.0 * r, 4.0 * r))
    cone = sk.Cone(alpha, sk.Frame(o + rot @ apex_local, cone_rot), v_range=(0.2 * r, 4.0 * r))
    return cylinder, cone, (o + rot @ apex_local, -rot[:, 2])


def test_cone_touching_a_cylinder_along_a_ruling():
    """A cone touching a cylinder all along a ruling (the general path's search cannot resolve a tangency along a
    line in this placement: it runs out of its box budget, TopologyError): in closed form, in either order, the
    ruling, clipped by both trims, as a segment of tangency, and an ellipse on both surfaces. Oracles: the ruling
    (through the apex, along the cylinder's axis) and its ends on the cone's trim (v = 0.2 r and 4 r, so
    t = v / cos(alpha)); the ellipse's length from its own plane's tilt (semi-axes r and r / cos of the tilt,
    4 a E(1 - b^2 / a^2)); the brute-force grid oracle's samples all near the curves."""
    from tests.oracles.ssi import brute_force
    from scipy.spatial import cKDTree
    alpha, r = 0.6, 0.9
    cylinder, cone, (apex, direction) = tangent_ruling_scene(np.random.default_rng(21), alpha, r)
    for a, b in ((cylinder, cone), (cone, cylinder)):
        curves = sk.intersect(a, b)
        assert sorted(c.status for c in curves) == ["closed", "tangent"]
        assert all(c.nfev == 0 and c.max_distance <= 1e-14 * r for c in curves)
        segment = next(c for c in curves if c.status == "tangent")
        ends = segment(np.array([0.0, segment.length]))
        along = (ends - apex) @ direction
        np.testing.assert_allclose(np.sort(along), np.array([0.2, 4.0]) * r / math.cos(alpha), rtol=1e-14)
        assert np.abs(ends - apex - np.outer(along, direction)).max() <= 1e-14 * r
        ellipse = next(c for c in curves if c.status == "closed")
        assert len(ellipse.nodes) == 1                  # where it touches the ruling
        node = ellipse.nodes[0]
        assert np.linalg.norm(node - apex - ((node - apex) @ direction) * direction) <= 1e-7 * r
        points = ellipse(np.linspace(0.0, ellipse.length, 400, endpoint=False))
        normal = np.linalg.svd(points - points.mean(axis=0))[2][2]
        cos_tilt = abs(normal @ cylinder.frame.rotation[:, 2])
        major = r / cos_tilt
        assert abs(ellipse.length - 4.0 * major * ellipe(1.0 - (r / major) ** 2)) <= 1e-12 * ellipse.length
    samples = brute_force(cylinder, cone)["samples"]
    dense = np.vstack([c(np.linspace(0.0, c.length, 4000)) for c in curves])
    assert cKDTree(dense).query(samples)[0].max() <= 5e-3 * r


def test_cone_nearly_touching_a_cylinder_along_a_ruling():
    """The cone of test_cone_touching_a_cylinder_along_a_ruling moved off the cylinder by 1e-8 and 1e-10 of the
    radius, out and in (the general path: the level is within that of zero all along the ruling, so a search that
    cut along it would run out of its budget; it bisects by the smear). The node splits and the
    ellipse and the two thin branches beside the ruling join into one open curve from the trim edge back to it:
    status 'boundary', on both surfaces to round-off. Oracle: as the offset goes to 0 the curve tends to the exact
    touching's ellipse plus the ruling from its node to a trim end, twice (closed form); one sign takes each end,
    and the length's distance to that limit shrinks with the offset (measured 1.2e-3 at 1e-8, 2.5e-4 at 1e-10)."""
    cylinder, cone, (apex, _) = tangent_ruling_scene(np.random.default_rng(0))
    touching = sk.intersect(cylinder, cone)
    ruling = next(c for c in touching if c.status == "tangent")
    ellipse = next(c for c in touching if c.status == "closed")
    limits = np.sort([ellipse.length + 2.0 * np.linalg.norm(end - ellipse.nodes[0])
                      for end in ruling(np.array([0.0, ruling.length]))])
    axis = cylinder.frame.rotation[:, 2]
    foot = cylinder.frame.origin + ((apex - cylinder.frame.origin) @ axis) * axis
    radial = (apex - foot) / np.linalg.norm(apex - foot)
    for sign in (1.0, -1.0):
        gaps = []
        for offset in (1e-8, 1e-10):
            moved = sk.Cone(cone.half_angle, sk.Frame(cone.frame.origin + sign * offset * radial,
                                                      cone.frame.rotation), cone.v_range)
            for a, b in ((cylinder, moved), (moved, cylinder)):
                curves = sk.intersect(a, b)
                assert [c.status for c in curves] == ["boundary"]
                points = np.vstack([curves[0].points, curves[0](np.linspace(0.0, curves[0].length, 2000))])
                assert max(cylinder.distance(points).max(), moved.distance(points).max()) <= 1e-14
                gaps.append(np.abs(curves[0].length - limits) / limits)
        side = np.argmin(gaps[0])
        assert side == (0 if sign > 0 else 1)
        assert all(np.argmin(g) == side for g in gaps)
        assert gaps[0][side] < 2e-3 and gaps[2][side] < 5e-4 and gaps[2][side] < gaps[0][side] / 3

def test_general_path_finds_both_arcs_beside_an_outside_node(monkeypatch):
    """Equal cylinders with crossing axes, a's trim passing just beside both nodes: both ellipses leave through that
    edge next to a node that lies outside the trim. The topology stage seeds a node's arms inside the trim even
    though the node itself lies outside (dropping them with the node would leave one arc without a start): the
    general path (closed forms off) finds both, their lengths the closed form's to 1e-7 (an end taken through the
    node, beside the edge), and the closed form itself both, exactly on the surfaces."""
    a = sk.Cylinder(0.0012617220940868451, sk.Frame(
        [-0.0020201759091821115, 0.003413274975558246, -0.0017599610186184796],
        [[0.4782520415715582, -0.30479982461043276, -0.8236334449559988],
         [-0.630693973089143, 0.5334332920280015, -0.563625793647878],
         [0.6111465430170312, 0.7890158362628843, 0.06288014857420104]]),
        v_range=(-0.0006467355906349223, 0.004400152694542784))
    b = sk.Cylinder(0.0012617220940868451, sk.Frame(
        [-0.0015430859494380176, 0.0037077011455990913, -0.0017272423646580394],
        [[-0.6721605985872134, 0.5634076663551795, -0.4803872721035495],
         [-0.21025951735873155, -0.7673538478988253, -0.605771415201262],
         [-0.7099232811134962, -0.3061696810709337, 0.6342468457359253]]))
    exact = sorted(c.length for c in sk.intersect(a, b))
    assert len(exact) == 2
    for first, second in ((a, b), (b, a)):
        found = sorted(c.length for c in traced(first, second, monkeypatch))
        assert len(found) == 2
        np.testing.assert_allclose(found, exact, rtol=1e-7)


def test_round_off_does_not_choose_a_closed_ellipses_direction():
    """A Steinmetz pair is symmetric: its ellipses' probes for the direction (NODE_PROBES points, the one with the
    largest angle between the normals) tie in pairs, on the two arcs between the nodes, where N_a x N_b points
    opposite ways along the curve. Moved by amounts that only change the round-off (1e-9 to 1e-7 of the scale),
    each ellipse runs the same way: its unit tangent at the point nearest a fixed point of it keeps its sign
    (oracle: the unmoved pair's tangents)."""
    a = sk.Cylinder(0.7, sk.Frame((0.0, 0.0, 0.0), sk.rotation_about((1.0, 2.0, 0.5), 0.4)), v_range=(-3.0, 3.0))
    b = sk.Cylinder(0.7, sk.Frame((0.0, 0.0, 0.0), sk.rotation_about(a.frame.rotation[:, 0], 1.2) @ a.frame.rotation),
                    v_range=(-3.0, 3.0))

    def tangents(shift):
        """The unit tangent, at each reference point (moved), of the curve through it."""
        moved = [type(s)(s.radius, sk.Frame(s.frame.origin + shift, s.frame.rotation), v_range=s.v_range)
                 for s in (a, b)]
        curves = sk.intersect(*moved)
        assert len(curves) == 2
        out = []
        for ref in references:
            nearest = [c.closest(ref + shift) for c in curves]
            k = int(np.argmin([dist for _, dist in nearest]))
            assert nearest[k][1] < 1e-9
            out.append(curves[k].derivatives(np.atleast_1d(nearest[k][0]))[1][0])
        return out

    curves = sk.intersect(a, b)
    references = [c.points[len(c.points) // 3] for c in curves]          # (away from the nodes)
    base = tangents(np.zeros(3))
    rng = np.random.default_rng(3)
    for _ in range(24):
        shift = rng.uniform(-1e-7, 1e-7, 3) * rng.choice([1.0, 1e-1, 1e-2])
        for t0, t1 in zip(base, tangents(shift)):
            assert t0 @ t1 > 0.99
