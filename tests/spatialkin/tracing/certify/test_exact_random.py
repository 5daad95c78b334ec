"""Random exactly coaxial pairs against an exact oracle written apart from the library: sympy solves the two
meridian equations (in the distance rho from the axis and the height h along it, the surfaces' stored floats read as
rationals), keeps the real solutions with rho >= 0 inside the trims, and calls one a tangency where the two
equations' gradients are parallel there (their Jacobian vanishes, decided exactly).

Every answer certified in an exact mode must then have the oracle's curves, one to one: a contact point for a
solution on the axis, a circle of tangency for a tangency, a crossed circle otherwise, each curve's stored points
within the proven bound of its true circle (measured in 40-digit mpmath); and every answer the certificate calls
wrong must have another number of curves than the oracle's. Half the pairs are built to touch exactly (a cylinder
or a sphere on a torus's equator, a plane on a torus's top, spheres inside each other, a sphere in a cone).
"""
import math

import mpmath as mp
import numpy as np
import pytest

import spatialkin as sk

sp = pytest.importorskip("sympy")
mp.mp.dps = 40
RHO, H = sp.symbols("rho h", real=True)
#: Exactly representable lengths the pairs are built from.
STEPS = (0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0)


def frame(rng, k, line, h):
    """A frame whose rotation is a signed permutation with local z along +-e_k, its origin on the line at h."""
    others = [j for j in range(3) if j != k]
    cols = [others[rng.integers(2)]]
    cols = [cols[0], [j for j in others if j != cols[0]][0], k]
    rot = np.zeros((3, 3))
    for col, j in enumerate(cols):
        rot[j, col] = rng.choice((-1.0, 1.0))
    if np.linalg.det(rot) < 0:
        rot[:, 0] *= -1.0
    origin = np.zeros(3)
    origin[others[0]], origin[others[1]], origin[k] = line[0], line[1], h
    return sk.Frame(origin, rot)


def meridian(surface, k):
    """(equation in RHO, H, trim along the axis (lo, hi) as Rationals or None) of the surface about axis k."""
    q = sp.Rational
    h0 = q(float(surface.frame.origin[k]))
    if isinstance(surface, sk.Sphere):
        return RHO ** 2 + (H - h0) ** 2 - q(surface.radius) ** 2, None
    if isinstance(surface, sk.Torus):
        return (RHO - q(surface.major_radius)) ** 2 + (H - h0) ** 2 - q(surface.minor_radius) ** 2, None
    if isinstance(surface, sk.Plane):
        return H - h0, None
    sign = int(surface.frame.rotation[k, 2])
    v0, v1 = surface.v_range
    trim = tuple(sorted((h0 + sign * q(v0), h0 + sign * q(v1))))
    if isinstance(surface, sk.Cylinder):
        return RHO - q(surface.radius), trim
    return RHO ** 2 - q(surface.slope) ** 2 * (H - h0) ** 2, trim


def truth(a, b, k):
    """[(rho, h, tangency)] of the exact intersection (sympy numbers), or None where a solution lies on a trim end
    (a case the certificate leaves to the search)."""
    (ea, ta), (eb, tb) = meridian(a, k), meridian(b, k)
    out = []
    for sol in sp.solve([ea, eb], [RHO, H], dict=True):
        rho, h = sp.nsimplify(sol[RHO]), sp.nsimplify(sol[H])
        if not (rho.is_real and h.is_real) or rho < 0:
            continue
        inside = True
        for trim in (ta, tb):
            if trim is None:
                continue
            if sp.simplify(h - trim[0]) == 0 or sp.simplify(h - trim[1]) == 0:
                return None
            inside = inside and trim[0] < h < trim[1]
        if not inside:
            continue
        jac = sp.Matrix([ea, eb]).jacobian([RHO, H]).subs({RHO: rho, H: h})
        out.append((rho, h, sp.simplify(jac.det()) == 0))
    return out


def pair(rng):
    """(a, b, k, line): a random pair turning about one coordinate axis, placed exactly; half built to touch."""
    k = int(rng.integers(3))
    line = tuple(float(rng.choice((-1.0, 0.0, 0.5, 2.0))) for _ in range(2))
    h = float(rng.choice((-1.0, 0.0, 0.5, 1.0)))
    big, small = 2.0, float(rng.choice((0.25, 0.5, 0.75)))
    torus = sk.Torus(big, small, frame(rng, k, line, h))
    trim = (-4.0, 4.0)
    build = int(rng.integers(8))
    if build == 0:
        other = sk.Cylinder(big + small * rng.choice((-1.0, 1.0)), frame(rng, k, line, h), v_range=trim)
    elif build == 1:
        other = sk.Sphere(big + small * rng.choice((-1.0, 1.0)), frame(rng, k, line, h))
    elif build == 2:
        other = sk.Plane(frame(rng, k, line, h + small * rng.choice((-1.0, 1.0))))
    elif build == 3:
        r = float(rng.choice(STEPS))
        return sk.Sphere(r, frame(rng, k, line, h)), sk.Sphere(r / 2, frame(rng, k, line, h + r / 2)), k, line
    elif build == 4:                    # a sphere of radius 3 five above the apex of the cone of slope 0.75
        cone = sk.Cone(math.atan(0.75), frame(rng, k, line, h), v_range=(-8.0, 8.0))
        if cone.slope != 0.75:
            pytest.skip("math.tan(math.atan(0.75)) is not 0.75 here")
        sign = float(cone.frame.rotation[k, 2])
        return cone, sk.Sphere(3.0, frame(rng, k, line, h + 5.0 * sign * rng.choice((-1.0, 1.0)))), k, line
    else:
        kind = rng.integers(4)
        f = frame(rng, k, line, h + float(rng.choice((-1.0, -0.25, 0.0, 0.5))))
        r = float(rng.choice(STEPS))
        other = (sk.Sphere(r, f), sk.Cylinder(r, f, v_range=trim), sk.Plane(f),
                 sk.Cone(math.atan(float(rng.choice((0.5, 1.0, 2.0)))), f, v_range=trim))[kind]
    return (torus, other, k, line) if rng.random() < 0.5 else (other, torus, k, line)


def _distance(points, k, line, rho, h):
    others = [j for j in range(3) if j != k]
    r, z = mp.mpf(sp.N(rho, 45)), mp.mpf(sp.N(h, 45))
    worst = 0.0
    for p in np.asarray(points, dtype=float).reshape(-1, 3):
        d = [mp.mpf(float(p[j])) - mp.mpf(c) for j, c in zip(others, line)]
        worst = max(worst, float(mp.sqrt((mp.sqrt(d[0] ** 2 + d[1] ** 2) - r) ** 2 + (mp.mpf(float(p[k])) - z) ** 2)))
    return worst


@pytest.mark.slow
def test_exact_certificates_agree_with_an_exact_oracle():
    """60 random exactly coaxial pairs: each answer proven in an exact mode is the oracle's, every curve within its
    bound; each answer said to be wrong has another number of curves than the oracle's; most are proven."""
    rng = np.random.default_rng(2026)
    proven = 0
    for _ in range(60):
        a, b, k, line = pair(rng)
        expected = truth(a, b, k)
        try:
            curves = sk.intersect(a, b, certify=True)
        except sk.TopologyError:
            continue
        cert = curves.certificate
        if not cert.mode.startswith("exact") or expected is None:
            continue
        if not cert.proven:
            if "not the exact one" in cert.claims["complete"].detail:
                assert len(curves) != len(expected), (a, b)
            continue
        proven += 1
        assert len(curves) == len(expected), (a, b, expected)
        left = list(expected)
        for curve, bound in zip(curves, cert.distance_bounds):
            near = [_distance(curve.points, k, line, rho, h) for rho, h, _ in left]
            rho, h, tangent = left.pop(int(np.argmin(near)))
            assert min(near) <= bound, (a, b, curve)
            kind = "contact" if rho == 0 else "tangent" if tangent else "closed"
            assert curve.status == kind, (a, b, curve.status, kind)
    assert proven >= 30
