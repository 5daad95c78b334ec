"""The circle of two spheres, and of a plane and a sphere, and the ellipse of a plane and a cylinder, enclosed in
intervals (spatialkin.kernels.certify.closed), against the same formulas evaluated in 60-digit decimal arithmetic on
the floats given (exact rationals)."""
from decimal import Decimal, getcontext

import numpy as np
import pytest

from spatialkin.kernels.certify import closed as kc

getcontext().prec = 60


def dec(v):
    return [Decimal(float(x)) for x in v]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def spheres_truth(oa, ra, ob, rb):
    oa, ob, ra, rb = dec(oa), dec(ob), Decimal(ra), Decimal(rb)
    d = [y - x for x, y in zip(oa, ob)]
    dd = dot(d, d)
    k = (dd + ra * ra - rb * rb) / (2 * dd)
    centre = [x + k * y for x, y in zip(oa, d)]
    axis = [y / dd.sqrt() for y in d]
    return centre, axis, ra * ra - k * k * dd


def plane_sphere_truth(o, n, c, r):
    o, n, c, r = dec(o), dec(n), dec(c), Decimal(r)
    length = dot(n, n).sqrt()
    delta = dot([x - y for x, y in zip(o, c)], n) / length
    axis = [x / length for x in n]
    return [x + delta * y for x, y in zip(c, axis)], axis, r * r - delta * delta


def plane_cylinder_truth(o, n, oc, axis):
    o, n, oc, axis = dec(o), dec(n), dec(oc), dec(axis)
    a = [x / dot(axis, axis).sqrt() for x in axis]
    nu = [x / dot(n, n).sqrt() for x in n]
    lam = dot([x - y for x, y in zip(o, oc)], nu) / dot(nu, a)
    return [x + lam * y for x, y in zip(oc, a)], a


def holds(truth, centre, axis, r2):
    for i in range(3):
        assert Decimal(truth[kc.M + i, 0]) <= centre[i] <= Decimal(truth[kc.M + i, 1])
        assert Decimal(truth[kc.A + i, 0]) <= axis[i] <= Decimal(truth[kc.A + i, 1])
    assert Decimal(truth[kc.R, 0]) ** 2 <= r2 <= Decimal(truth[kc.R, 1]) ** 2
    assert np.all(np.diff(truth, axis=1) < 1e-12 * (1.0 + np.abs(truth[:, :1])))     # and tight


@pytest.mark.parametrize("shift", [0.0, 1e3, 1e7])
@pytest.mark.parametrize("scale", [1e-4, 1.0, 1e4])
def test_spheres_enclose_the_true_circle(shift, scale):
    rng = np.random.default_rng(7)
    for _ in range(20):
        oa = shift + scale * rng.normal(size=3)
        ob = oa + scale * rng.normal(size=3) * 0.5
        ra, rb = scale * rng.uniform(0.5, 1.5), scale * rng.uniform(0.5, 1.5)
        out = np.empty((10, 2))
        centre, axis, rho2 = spheres_truth(oa, ra, ob, rb)
        outcome = kc.spheres(oa, ra, ob, rb, out)
        if rho2 > 0:
            assert outcome in (kc.CURVE, kc.UNDECIDED)
            if outcome == kc.CURVE:
                holds(out, centre, axis, rho2)
        else:
            assert outcome in (kc.EMPTY, kc.UNDECIDED)


@pytest.mark.parametrize("shift", [0.0, 1e5])
def test_plane_sphere_encloses_the_true_circle(shift):
    rng = np.random.default_rng(11)
    for _ in range(30):
        o, c = shift + rng.normal(size=3), shift + rng.normal(size=3) * 0.3
        n = rng.normal(size=3)
        r = rng.uniform(0.5, 2.0)
        out = np.empty((10, 2))
        centre, axis, rho2 = plane_sphere_truth(o, n, c, r)
        outcome = kc.plane_sphere(o, n, c, r, out)
        assert outcome == (kc.CURVE if rho2 > 0 else kc.EMPTY)
        if outcome == kc.CURVE:
            holds(out, centre, axis, rho2)


@pytest.mark.parametrize("shift", [0.0, 1e5])
def test_plane_cylinder_encloses_the_true_ellipse(shift):
    rng = np.random.default_rng(5)
    for _ in range(30):
        o, oc = shift + rng.normal(size=3), shift + rng.normal(size=3)
        n, axis = rng.normal(size=3), rng.normal(size=3)
        out = np.empty((10, 2))
        assert kc.plane_cylinder(o, n, oc, axis, 0.7, out) == kc.CURVE
        centre, a = plane_cylinder_truth(o, n, oc, axis)
        holds(out, centre, a, Decimal(0.7) ** 2)


def test_a_plane_along_the_axis_is_undecided():
    out = np.empty((10, 2))
    assert kc.plane_cylinder(np.zeros(3), np.array([1.0, 0.0, 0.0]), np.zeros(3), np.array([0.0, 0.0, 1.0]), 1.0,
                             out) == kc.UNDECIDED


def test_touching_spheres_are_undecided():
    out = np.empty((10, 2))
    assert kc.spheres(np.zeros(3), 1.0, np.array([2.0, 0.0, 0.0]), 1.0, out) == kc.UNDECIDED
    assert kc.spheres(np.zeros(3), 1.0, np.zeros(3), 1.0, out) == kc.UNDECIDED            # concentric
    assert kc.spheres(np.zeros(3), 1.0, np.array([0.1, 0.0, 0.0]), 0.5, out) == kc.EMPTY  # nested
