"""CAD-face trims of the surfaces: angular ranges (u of a cylinder, cone, sphere or torus; a torus's tube angle),
a sphere's zone, a plane's disc and annulus: the checks of their arguments, their round trips, and their limits
against an inside test written apart from them (the angles of the point by atan2, tests.oracles.ssi.face_margin)."""
import math
import pickle

import numpy as np
import pytest

from tests.oracles.ssi import face_margin, to_local

import spatialkin as sk
from spatialkin.geometry.trims import inside_region, limits

_Q = np.linalg.qr(np.random.default_rng(5).normal(size=(3, 3)))[0]
ROT = sk.Frame((0.3, -0.2, 0.5), _Q * np.sign(np.linalg.det(_Q)))        # a proper rotation

FACES = [
    sk.Cylinder(0.7, ROT, v_range=(-1.0, 2.0), u_range=(0.4, 2.0)),
    sk.Cylinder(0.7, ROT, u_range=(-3.0, 1.5)),                              # wider than a half turn
    sk.Cone(0.6, ROT, v_range=(-2.0, 2.0), u_range=(2.5, 4.0)),             # both nappes
    sk.Sphere(1.2, ROT, u_range=(5.0, 7.5), v_range=(-0.3, 1.1)),
    sk.Sphere(1.2, ROT, v_range=(-math.pi / 2, 0.2)),                       # a cap round the south pole
    sk.Torus(2.0, 0.5, ROT, u_range=(-1.0, 0.5), v_range=(1.0, 5.5)),
    sk.Torus(2.0, 0.5, ROT, v_range=(-0.5, 0.5)),
    sk.Plane(ROT, radius=1.5, inner_radius=0.4),
    sk.Plane(ROT, u_range=(-2.0, 0.5), v_range=(-1.0, 1.0), radius=1.2),
]


@pytest.mark.parametrize("call, match", [
    (lambda: sk.Cylinder(1.0, u_range=(0.0, 7.0)), "u_range must span at most a full turn"),
    (lambda: sk.Cylinder(1.0, u_range=(1.0, 0.0)), "u_range must satisfy min < max"),
    (lambda: sk.Cone(0.5, u_range=(math.nan, 1.0)), "u_range must be finite"),
    (lambda: sk.Cone(0.5, u_range=(-math.inf, 1.0)), "u_range must be finite"),
    (lambda: sk.Torus(1.0, 2.0, u_range=(0.0, 1.0)), "u_range trims only a ring torus"),
    (lambda: sk.Torus(1.0, 1.0, v_range=(0.0, 1.0)), "v_range trims only a ring torus"),
    (lambda: sk.Sphere(1.0, v_range=(-2.0, 0.0)), "v_range must be latitudes"),
    (lambda: sk.Sphere(1.0, u_range="ab"), "u_range must be a pair"),
    (lambda: sk.Plane(radius=-1.0), "radius must be a positive finite number"),
    (lambda: sk.Plane(radius=1.0, inner_radius=1.0), "inner_radius must be less than radius"),
    (lambda: sk.Plane(radius=1.0, inner_radius=-0.1), "inner_radius must be a finite number >= 0"),
    (lambda: sk.Plane(radius=1.0, u_range=(2.0, 3.0)), "u_range must meet the disc"),
])
def test_bad_trims_raise_naming_the_argument(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_a_full_turn_is_no_trim():
    assert sk.Cylinder(1.0, u_range=(1.0, 1.0 + 2 * math.pi)).region == ()
    assert sk.Sphere(1.0, v_range=(-math.pi / 2, math.pi / 2)).region == ()
    assert sk.Cylinder(1.0, u_range=(1.0, 1.0 + 2 * math.pi)).u_range == (-math.inf, math.inf)


@pytest.mark.parametrize("face", FACES, ids=lambda f: repr(f)[:40])
def test_round_trips_keep_the_trims(face):
    for copy in (pickle.loads(pickle.dumps(face)), face.with_frame(face.frame)):
        assert type(copy) is type(face)
        assert copy.region == face.region
        assert copy.u_range == face.u_range and copy.v_range == face.v_range
        assert repr(copy) == repr(face)


def surface_samples(face, n=4000, seed=7):
    """Points spread over the untrimmed surface (a plane's over a square of side 4 about its origin)."""
    rng = np.random.default_rng(seed)
    if isinstance(face, sk.Plane):
        return face.point(rng.uniform(-2.0, 2.0, n), rng.uniform(-2.0, 2.0, n))
    u = rng.uniform(-math.pi, math.pi, n)
    v = {sk.Cylinder: rng.uniform(-3.0, 3.0, n), sk.Cone: rng.uniform(-3.0, 3.0, n),
         sk.Sphere: rng.uniform(-math.pi / 2, math.pi / 2, n), sk.Torus: rng.uniform(-math.pi, math.pi, n)}[type(face)]
    return face.point(u, v)


@pytest.mark.parametrize("face", FACES, ids=lambda f: repr(f)[:40])
def test_inside_agrees_with_the_angles_of_the_point(face):
    """The half-plane limits say inside exactly where the atan2 angles (and radii) of the point lie in the trims,
    away from the edges (1e-9); the watched length trims are checked as the oracle reads them too."""
    pts = surface_samples(face)
    margin = face_margin(face, to_local(face, pts))
    clear = np.abs(margin) > 1e-9
    assert clear.sum() > 0.9 * len(pts)
    ours = inside_region(face, pts)
    assert np.array_equal(ours[clear], (margin >= 0)[clear])
    assert 0.05 < ours.mean() < 0.95                       # both sides are sampled


@pytest.mark.parametrize("face", FACES, ids=lambda f: repr(f)[:40])
def test_limits_are_1_lipschitz(face):
    """|limit(p + h e) - limit(p)| <= h for random directions e (the clipper's crossing bound rests on it)."""
    rng = np.random.default_rng(11)
    pts = surface_samples(face, 500)
    e = rng.normal(size=pts.shape)
    e /= np.linalg.norm(e, axis=1)[:, None]
    h = 1e-3
    for limit in limits(face):
        here = limit(face.frame.to_local(pts))
        there = limit(face.frame.to_local(pts + h * e))
        off_nappe = np.sign(face.frame.to_local(pts)[:, 2]) != np.sign(face.frame.to_local(pts + h * e)[:, 2])
        assert np.all(np.abs(there - here)[~off_nappe] <= h * (1 + 1e-9))
