"""Quadric pairs whose intersection splits into two conics: the pencil A - lambda B of their 4 x 4 matrices holds a
pair of real crossing planes, and the quartic curve is the two conics those planes cut from either quadric, crossing
at the nodes where the planes' common line meets it.

Two cylinders of equal radii whose axes cross (the Steinmetz curves: two ellipses through two nodes, a pipe tee),
and cylinders and cones that share an inscribed sphere (Monge), are such pairs. Their nodes are where the tracer
must jump between branches (near-parallel normals, a hand-over to the fine DOP853 events), which makes tracing them
slow; in closed form it is the plane–cylinder case twice. spatialkin.tracing.closed.forms clips the conics
and makes the components; this module finds the planes and the nodes, and declines (None) everything else.

Only a member whose two smallest eigenvalues are round-off (RANK_TOL) counts, and closed.split_conics then checks
the ellipses on both surfaces (closed.SPLIT_FIT): a pair 1e-12 (relative) from splitting meets in loops passing a
waist, left to the general path. Parallel planes (coaxial surfaces: their
parallels) are left to the topology stage's placements.

References
----------
R. Goldman, J. Miller, Combining algebraic rigor with geometric robustness for the detection and calculation of
conic sections in the intersection of two natural quadric surfaces, ACM SPM (1991).
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(singular points of intersection curves: nodes and branch crossings).
"""
import math

import numpy as np
import scipy.linalg

from ...geometry.vectors import cross

#: A member of the pencil is a pair of planes when its two smallest eigenvalues (in magnitude) are at most this
#: fraction of its largest: round-off of the matrices, in coordinates scaled by the scene (the splitting pairs of
#: the stress cases: below 1e-15; a pair of cylinders whose radii differ by 1e-9: 2e-9).
RANK_TOL = 1e-12
#: An eigenvalue of the pencil is real when its imaginary part is at most this fraction of its size.
REAL_TOL = 1e-9
#: The axes of a pair that may split cross within this (relative to the scale), and the spheres inscribed about
#: their crossing have radii equal within it (may_split: a loose necessary condition; the pencil decides).
AXES_GAP = 1e-6
#: The planes must cross: the sine of their angle above this (parallel planes are coaxial surfaces' parallels).
CROSSING_SIN = 1e-6
#: The planes' common line meets the quadric in two points farther apart than this (relative to the scale), two
#: nodes; closer, it touches the quadric and the conics touch there: one node (a cone touching a cylinder along a
#: ruling meets it in that ruling and an ellipse touching it; the point is then known to about sqrt(round-off)).
NODE_SEPARATION = 1e-6


def may_split(quadrics, scale):
    """A necessary condition for a split, cheap to test first: both quadrics are cylinders or cones (a sphere's
    pencil with them holds no pair of crossing planes), their axes cross (within AXES_GAP x scale), and a sphere
    about the crossing is inscribed in both (a cylinder's radius; a cone's distance from its apex times the sine
    of its half angle; equal within AXES_GAP x scale). quadrics: (name, origin (3 floats), axis (3 floats),
    (mu, rho)) each, the cone's origin its apex."""
    (n1, o1, z1, f1), (n2, o2, z2, f2) = quadrics
    if "sphere" in (n1, n2):
        return False
    n = cross(z1, z2)
    sin = math.sqrt(float(n @ n))
    if sin <= CROSSING_SIN:
        return False
    d = np.subtract(o2, o1)
    if abs(float(d @ n)) > AXES_GAP * scale * sin:
        return False
    # the crossing: o1 + s z1 = o2 + t z2 (least squares on the two lines)
    c = float(np.dot(z1, z2))
    s1 = (float(d @ z1) - c * float(d @ z2)) / (sin * sin)
    cross_point = np.add(o1, s1 * np.asarray(z1))
    radii = [math.sqrt(rho) if name == "cylinder" else
             float(np.linalg.norm(cross_point - np.asarray(o))) * math.sqrt(-mu / (1.0 - mu))
             for name, o, (mu, rho) in ((n1, o1, f1), (n2, o2, f2))]
    return abs(radii[0] - radii[1]) <= AXES_GAP * scale


def quadric_matrix(origin, rot, form, centre, scale):
    """The symmetric 4 x 4 matrix M of a quadric x^2 + y^2 + mu z^2 = rho (local; form = (mu, rho)) placed at origin
    with rotation rot (9 floats, row by row), in the coordinates X = ((p - centre) / scale, 1): X^T M X = 0."""
    r = np.array(rot, dtype=float).reshape(3, 3)
    mu, rho = form
    s = (r * np.array([1.0, 1.0, mu])) @ r.T
    o = (np.array(origin, dtype=float) - centre) / scale
    so = s @ o
    m = np.empty((4, 4))
    m[:3, :3] = s
    m[:3, 3] = m[3, :3] = -so
    m[3, 3] = o @ so - rho / (scale * scale)
    return m


def plane_pair(a, b):
    """The two planes (P+, P-) (4-vectors of the scaled coordinates: X . P = 0) of a member of the pencil of the
    matrices a, b that is a pair of real planes crossing each other; None when there is none."""
    with np.errstate(all="ignore"):
        values = scipy.linalg.eigvals(a, b)
    for lam in values:
        if not (np.isfinite(lam) and abs(lam.imag) <= REAL_TOL * max(1.0, abs(lam))):
            continue
        w, v = np.linalg.eigh(a - lam.real * b)
        order = np.argsort(np.abs(w))
        big = abs(w[order[3]])
        if big == 0.0 or abs(w[order[1]]) > RANK_TOL * big or w[order[2]] * w[order[3]] >= 0.0:
            continue                                       # not rank 2, or a real line (imaginary planes)
        i, j = (order[2], order[3]) if w[order[2]] > 0 else (order[3], order[2])
        p, q = math.sqrt(w[i]) * v[:, i], math.sqrt(-w[j]) * v[:, j]
        planes = (p + q, p - q)
        n0, n1 = planes[0][:3], planes[1][:3]
        size = np.linalg.norm(n0) * np.linalg.norm(n1)
        if size == 0.0 or np.linalg.norm(cross(n0, n1)) <= CROSSING_SIN * size:
            continue
        return planes
    return None


def split_planes(quadrics, centre, scale):
    """The two crossing planes that split the intersection of two quadrics ((origin, rot, form) each), as
    (unit normal (3,), a point on it (3,)) in global coordinates, and the nodes (K, 3) where both planes meet the
    first quadric (K = 0, 1 where the line touches it, or 2); None when the pair does not split (or splits only in
    parallel planes)."""
    a, b = (quadric_matrix(*q, centre, scale) for q in quadrics)
    planes = plane_pair(a, b)
    if planes is None:
        return None
    out = []
    for plane in planes:
        n, d = plane[:3], plane[3]
        norm2 = float(n @ n)
        out.append((n / math.sqrt(norm2), centre - scale * d / norm2 * n))
    (n0, p0), (n1, p1) = out
    # the planes' common line, p + t e (scaled coordinates), on the first quadric: a quadratic in t
    e = cross(n0, n1)
    e /= np.linalg.norm(e)
    rows = np.array([n0, n1, e])
    foot = np.linalg.solve(rows, [n0 @ (p0 - centre) / scale, n1 @ (p1 - centre) / scale, 0.0])
    x, y = np.append(foot, 1.0), np.append(e, 0.0)
    qa, qb, qc = y @ a @ y, 2.0 * (x @ a @ y), x @ a @ x
    disc = qb * qb - 4.0 * qa * qc
    if qa == 0.0:
        return None
    root = math.sqrt(abs(disc))
    if root / abs(qa) <= NODE_SEPARATION:
        ts = (-qb / (2.0 * qa),)                  # the line touches the quadric: the conics touch there (one node)
    elif disc < 0.0:
        return out, np.empty((0, 3))
    else:
        ts = ((-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa))
    return out, np.array([centre + scale * (foot + t * e) for t in ts])
