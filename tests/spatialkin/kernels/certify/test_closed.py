"""The ellipse of a plane and a quadric (a sphere, a cylinder, a double cone), and the circle of two spheres,
enclosed in intervals (spatialkin.kernels.certify.closed), against the conic's centre and matrix computed in
60-digit decimal arithmetic from the floats given (exact rationals), in the enclosed basis of the plane."""
from decimal import Decimal, getcontext

import numpy as np
import pytest

from spatialkin.kernels.certify import closed as kc

getcontext().prec = 60


def dec(v):
    return [Decimal(float(x)) for x in v]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def unit(v):
    length = dot(v, v).sqrt()
    return [x / length for x in v]


def conic_truth(p, n, o, axis, g, k, f1, f2):
    """(centre (3 Decimal), A11, A12, A22) of the plane through p (normal n) and the quadric (o, axis, g, k) in the
    basis f1, f2 (3 Decimal each, the kernel's enclosures' midpoints: any orthonormal basis normal to n gives the
    same centre, and A in that basis)."""
    a = unit(axis)

    def form(x, y):
        return dot(x, y) - g * dot(a, x) * dot(a, y)
    d = [x - y for x, y in zip(p, o)]
    a11, a12, a22 = form(f1, f1), form(f1, f2), form(f2, f2)
    b1, b2 = form(f1, d), form(f2, d)
    det = a11 * a22 - a12 * a12
    z1, z2 = (a12 * b2 - a22 * b1) / det, (a12 * b1 - a11 * b2) / det
    c1 = form(d, d) - k + b1 * z1 + b2 * z2
    centre = [pi + z1 * x + z2 * y for pi, x, y in zip(p, f1, f2)]
    return centre, a11 / -c1, a12 / -c1, a22 / -c1


def basis(truth):
    """The kernel's f1, f2 as Decimal (midpoints), orthonormalised exactly against the Decimal normal n."""
    return [[Decimal(0.5 * (truth[r + i, 0] + truth[r + i, 1])) for i in range(3)] for r in (kc.F1, kc.F2)]


def holds(truth, centre, a11, a12, a22, rel, tight=True):
    for i in range(3):
        assert Decimal(truth[kc.Z0 + i, 0]) - rel <= centre[i] <= Decimal(truth[kc.Z0 + i, 1]) + rel
    for row, value in ((kc.A11, a11), (kc.A12, a12), (kc.A22, a22)):
        assert Decimal(truth[row, 0]) - rel <= value <= Decimal(truth[row, 1]) + rel
    if tight:                                   # (a well-conditioned conic's enclosures are narrow)
        assert np.all(np.diff(truth, axis=1) < 1e-8 * (1.0 + np.abs(truth[:, :1])))


def exact_basis(n, truth):
    """An exactly orthonormal basis normal to n (Decimal) nearest the kernel's."""
    nu = unit(n)
    f1, f2 = basis(truth)
    f1 = unit([x - dot(f1, nu) * y for x, y in zip(f1, nu)])
    f2 = [nu[1] * f1[2] - nu[2] * f1[1], nu[2] * f1[0] - nu[0] * f1[2], nu[0] * f1[1] - nu[1] * f1[0]]
    return f1, f2


@pytest.mark.parametrize("kind", ["sphere", "cylinder", "cone"])
@pytest.mark.parametrize("shift", [0.0, 1e5])
def test_plane_quadric_encloses_the_true_conic(kind, shift):
    rng = np.random.default_rng(3)
    proven = 0
    for _ in range(40):
        p, o = shift + rng.normal(size=3), shift + rng.normal(size=3) * 0.3
        n, axis = rng.normal(size=3), rng.normal(size=3)
        radius, tangent = rng.uniform(0.5, 2.0), rng.uniform(0.2, 1.5)
        truth = np.empty((kc.ROWS, 2))
        if kind == "cone":
            outcome = kc.cone_quadric(p, n, o, axis, tangent, truth)
            g, k = 1 + Decimal(tangent) ** 2, Decimal(0)
        else:
            outcome = kc.plane_quadric(p, n, o, axis, 0.0 if kind == "sphere" else 1.0, radius, truth)
            g, k = Decimal(0 if kind == "sphere" else 1), Decimal(radius) ** 2
        if outcome != kc.CURVE:
            continue
        proven += 1
        f1, f2 = exact_basis(dec(n), truth)
        centre, a11, a12, a22 = conic_truth(dec(p), dec(n), dec(o), dec(axis), g, k, f1, f2)
        far = max(abs(float(c) - x) for c, x in zip(centre, p))     # the conic's centre far off: ill-conditioned
        holds(truth, centre, a11, a12, a22, Decimal(1e-13) * (1 + abs(Decimal(shift))), tight=far < 10)
    assert proven >= 10


def test_two_spheres_meet_in_their_circle():
    rng = np.random.default_rng(7)
    for _ in range(20):
        oa = rng.normal(size=3)
        ob = oa + rng.normal(size=3) * 0.5
        ra, rb = rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5)
        truth = np.empty((kc.ROWS, 2))
        outcome = kc.spheres(oa, ra, ob, rb, truth)
        d = [y - x for x, y in zip(dec(oa), dec(ob))]
        dd = dot(d, d)
        kk = (dd + Decimal(ra) ** 2 - Decimal(rb) ** 2) / (2 * dd)
        rho2 = Decimal(ra) ** 2 - kk * kk * dd
        assert outcome == (kc.CURVE if rho2 > 0 else kc.EMPTY)
        if outcome == kc.CURVE:
            centre = [x + kk * y for x, y in zip(dec(oa), d)]
            holds(truth, centre, 1 / rho2, Decimal(0), 1 / rho2, Decimal(1e-13))


def test_undecided_and_empty():
    truth = np.empty((kc.ROWS, 2))
    z, x, y = np.zeros(3), np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    assert kc.spheres(z, 1.0, np.array([2.0, 0.0, 0.0]), 1.0, truth) == kc.UNDECIDED      # touching
    assert kc.spheres(z, 1.0, z, 1.0, truth) == kc.UNDECIDED                               # concentric
    assert kc.spheres(z, 1.0, np.array([0.1, 0.0, 0.0]), 0.5, truth) == kc.EMPTY          # nested
    assert kc.plane_quadric(z, x, z, y, 1.0, 1.0, truth) == kc.UNDECIDED                   # plane along the axis
    assert kc.plane_quadric(x, x, z, y, 0.0, 1.0, truth) == kc.UNDECIDED                   # plane touching a sphere
    assert kc.plane_quadric(2 * x, x, z, y, 0.0, 1.0, truth) == kc.EMPTY
    assert kc.cone_quadric(z, y, z, y, 1.0, truth) == kc.UNDECIDED                          # through the apex
    assert kc.cone_quadric(z, x, z, y, 1.0, truth) == kc.UNDECIDED                          # a hyperbola


def segment_truth(o1, n1, o2, n2, bands):
    """The segment's ends (A, B) of two planes inside the bands, in Decimal (None when empty)."""
    o1, n1, o2, n2 = dec(o1), dec(n1), dec(o2), dec(n2)
    d = [n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2], n1[0] * n2[1] - n1[1] * n2[0]]
    dd = dot(d, d)
    h1, h2 = dot(n1, o1), dot(n2, o2)
    k1 = (h1 * dot(n2, n2) - h2 * dot(n1, n2)) / dd
    k2 = (h2 * dot(n1, n1) - h1 * dot(n1, n2)) / dd
    p0 = [k1 * x + k2 * y for x, y in zip(n1, n2)]
    lo, hi = Decimal("-1e400"), Decimal("1e400")
    for band in bands:
        o, e = dec(band[:3]), dec(band[3:6])
        a, b = dot([x - y for x, y in zip(p0, o)], e), dot(d, e)
        ends = sorted([(Decimal(float(band[6])) - a) / b, (Decimal(float(band[7])) - a) / b])
        lo, hi = max(lo, ends[0]), min(hi, ends[1])
    if lo > hi:
        return None
    return [x + lo * y for x, y in zip(p0, d)], [x + hi * y for x, y in zip(p0, d)]


def test_two_planes_meet_in_the_true_segment():
    rng = np.random.default_rng(13)
    proven = 0
    for _ in range(40):
        o1, o2 = 0.2 * rng.normal(size=3), 0.2 * rng.normal(size=3)
        n1, n2 = rng.normal(size=3), rng.normal(size=3)
        e = [rng.normal(size=3) for _ in range(4)]
        bands = np.array([np.concatenate([o1 if k < 2 else o2, e[k], [-rng.uniform(0.5, 3), rng.uniform(0.5, 3)]])
                          for k in range(4)])
        ends = np.empty((6, 2))
        outcome = kc.plane_plane(o1, n1, o2, n2, bands, ends)
        truth = segment_truth(o1, n1, o2, n2, bands)
        if truth is None:
            assert outcome in (kc.EMPTY, kc.UNDECIDED)
            continue
        assert outcome in (kc.CURVE, kc.UNDECIDED)
        if outcome == kc.CURVE:
            proven += 1
            for i in range(3):
                assert Decimal(ends[i, 0]) <= truth[0][i] <= Decimal(ends[i, 1])
                assert Decimal(ends[3 + i, 0]) <= truth[1][i] <= Decimal(ends[3 + i, 1])
    assert proven >= 20
    parallel = np.empty((6, 2))
    z = np.array([0.0, 0.0, 1.0])
    assert kc.plane_plane(np.zeros(3), z, z, z, np.zeros((0, 8)), parallel) == kc.UNDECIDED


def test_nearly_degenerate_ellipses_are_never_proven_inside_too_narrow_a_band():
    """Planes 3e-8 to 3e-6 from parallel to a cylinder's axis: ellipses about 1 / eps long, whose matrix's
    determinant may hold 0 in intervals; a band a tenth of that long is never proven to hold one (out of 3000)."""
    rng = np.random.default_rng(2)
    curves = 0
    for _ in range(3000):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        w = rng.normal(size=3)
        w -= w.dot(axis) * axis
        w /= np.linalg.norm(w)
        eps = 10 ** rng.uniform(-7.5, -5.5)
        p = rng.uniform(-0.3, 0.3, 3)
        truth = np.empty((kc.ROWS, 2))
        if kc.plane_quadric(p, w + eps * axis, np.zeros(3), axis, 1.0, 1.0, truth) != kc.CURVE:
            continue
        curves += 1
        cz = np.mean(truth[kc.Z0:kc.Z0 + 3], axis=1).dot(axis)
        assert not kc.within_band(truth, np.zeros(3), axis, cz - 0.1 / eps, cz + 0.1 / eps)
    assert curves > 30
