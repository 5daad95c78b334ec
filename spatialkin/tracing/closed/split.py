"""Quadric pairs whose intersection splits into two conics: two cylinders or cones tangent to one sphere (Monge's
case), whose quartic curve is the two ellipses that two crossing planes cut from either quadric, crossing at the
nodes where the planes' common line meets it.

Two cylinders of equal radii whose axes cross (the Steinmetz curves: two ellipses through two nodes, a pipe tee),
and cylinders and cones that share an inscribed sphere, are such pairs. Their nodes are where the tracer must jump
between branches (near-parallel normals, a hand-over to the fine DOP853 events), which makes tracing them slow; in
closed form it is the plane–cylinder case twice. spatialkin.tracing.closed.forms clips the conics and makes the
components; this module finds the planes and the nodes, and declines (None) everything else.

**The planes.** A quadric x^2 + y^2 + mu z^2 = rho (local coordinates; a cylinder mu = 0, rho = r^2; a cone
mu = -tan^2 of its half angle, rho = 0, its apex at the origin) whose axis z passes through a point O, with
c = z . (O - o) the height of O on its axis, reads, in x' = x - O,

    Q(x') = |x'|^2 - k (z . x' - d)^2 - s^2,   k = 1 - mu,  d = mu c / k,  s^2 = rho - mu c^2 / k,

the sphere |x'| = s about O less the square of a linear function: the quadric touches that sphere along the circle
z . x' = d. Two such quadrics with a common O and equal s differ by k2 L2^2 - k1 L1^2 (L = z . x' - d), a difference
of two squares: every common point lies on one of the planes sqrt(k2) L2 = +-sqrt(k1) L1, which cross (k >= 1 and
the axes are not parallel), and each plane cuts an ellipse from either quadric. O is where the axes cross (within
AXES_GAP x scale; the least-squares point on the first axis) and the two radii s must agree within AXES_GAP x scale:
a pair only nearly so is declined by closed.split_conics, which checks the ellipses on both surfaces
(closed.SPLIT_FIT): a pair 1e-12 (relative) from splitting meets in loops passing a waist, left to the general
path. Parallel axes (coaxial surfaces: their parallels) are left to the topology stage's placements.

References
----------
R. Goldman, J. Miller, Combining algebraic rigor with geometric robustness for the detection and calculation of
conic sections in the intersection of two natural quadric surfaces, ACM SPM (1991).
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(singular points of intersection curves: nodes and branch crossings).
"""
import math

from ...geometry.vectors import cross_list, dot_list

#: The axes of a pair that may split cross within this (relative to the scale), and the spheres inscribed about
#: their crossing have radii equal within it.
AXES_GAP = 1e-6
#: The axes must cross at an angle whose sine is above this (parallel axes: coaxial surfaces' parallels).
CROSSING_SIN = 1e-6
#: The planes' common line meets the quadric in two points farther apart than this (relative to the scale), two
#: nodes; closer, it touches the quadric and the conics touch there: one node (a cone touching a cylinder along a
#: ruling meets it in that ruling and an ellipse touching it; the point is then known to about sqrt(round-off)).
NODE_SEPARATION = 1e-6


def inscribed(quadrics, scale):
    """(O, forms): the crossing O (3 floats) of the axes of two cylinders or cones and each one's (k, z, d) (see the
    module docstring) when a sphere about O is inscribed in both (radii s equal within AXES_GAP x scale); None
    otherwise (a sphere among them, axes parallel or apart). quadrics: (name, origin, rot (9 floats, row by row),
    (mu, rho)) each, a cone's origin its apex."""
    (n1, o1, r1, _), (n2, o2, r2, _) = quadrics
    if "sphere" in (n1, n2):
        return None
    z1, z2 = r1[2::3], r2[2::3]
    n = cross_list(z1, z2)
    sin = math.sqrt(dot_list(n, n))
    if sin <= CROSSING_SIN:
        return None
    d = [o2[0] - o1[0], o2[1] - o1[1], o2[2] - o1[2]]
    if abs(dot_list(d, n)) > AXES_GAP * scale * sin:
        return None
    # the crossing: o1 + s z1 = o2 + t z2 (least squares on the two lines)
    c = dot_list(z1, z2)
    s1 = (dot_list(d, z1) - c * dot_list(d, z2)) / (sin * sin)
    centre = [o1[0] + s1 * z1[0], o1[1] + s1 * z1[1], o1[2] + s1 * z1[2]]
    forms, radii = [], []
    for (_, o, rot, (mu, rho)) in quadrics:
        z = rot[2::3]
        height = z[0] * (centre[0] - o[0]) + z[1] * (centre[1] - o[1]) + z[2] * (centre[2] - o[2])
        k = 1.0 - mu
        forms.append((k, z, mu * height / k))
        radii.append(math.sqrt(max(rho - mu * height * height / k, 0.0)))
    if abs(radii[0] - radii[1]) > AXES_GAP * scale:
        return None
    return centre, forms


def split_planes(quadrics, scale):
    """The two crossing planes that split the intersection of two quadrics ((name, origin, rot, form) each, as
    inscribed reads them), as (unit normal, a point on it) (3 floats each) in global coordinates, and the nodes (K
    points, 3 floats each) where both planes meet the first quadric (K = 0, 1 where their common line touches it, or
    2); None when the pair is no such pair (inscribed)."""
    found = inscribed(quadrics, scale)
    if found is None:
        return None
    centre, ((k1, z1, d1), (k2, z2, d2)) = found
    a, b = math.sqrt(k1), math.sqrt(k2)
    units, offsets, out = [], [], []
    for sign in (1.0, -1.0):                   # sqrt(k2) L2 = sign sqrt(k1) L1
        n0, n1, n2 = b * z2[0] - sign * a * z1[0], b * z2[1] - sign * a * z1[1], b * z2[2] - sign * a * z1[2]
        size = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
        unit = [n0 / size, n1 / size, n2 / size]
        offset = (b * d2 - sign * a * d1) / size       # unit . x' on the plane
        units.append(unit)
        offsets.append(offset)
        out.append((unit, [centre[0] + offset * unit[0], centre[1] + offset * unit[1], centre[2] + offset * unit[2]]))
    # the planes' common line, O + f + t e, on the first quadric (its local form, exactly): a quadratic in t (scaled)
    (u0, u1), (w0, w1) = units, offsets
    g = dot_list(u0, u1)
    alpha, beta = (w0 - g * w1) / (1.0 - g * g), (w1 - g * w0) / (1.0 - g * g)
    e = cross_list(u0, u1)
    size = math.sqrt(dot_list(e, e))
    e0, e1, e2 = e[0] / size, e[1] / size, e[2] / size
    foot = [centre[0] + alpha * u0[0] + beta * u1[0], centre[1] + alpha * u0[1] + beta * u1[1],
            centre[2] + alpha * u0[2] + beta * u1[2]]
    _, origin, rot, (mu, rho) = quadrics[0]
    r0, r1, r2 = (foot[0] - origin[0]) / scale, (foot[1] - origin[1]) / scale, (foot[2] - origin[2]) / scale
    p = [rot[j] * r0 + rot[3 + j] * r1 + rot[6 + j] * r2 for j in range(3)]       # R^T (foot - o)
    q = [rot[j] * e0 + rot[3 + j] * e1 + rot[6 + j] * e2 for j in range(3)]       # R^T e
    qa = q[0] * q[0] + q[1] * q[1] + mu * q[2] * q[2]
    qb = 2.0 * (p[0] * q[0] + p[1] * q[1] + mu * p[2] * q[2])
    qc = p[0] * p[0] + p[1] * p[1] + mu * p[2] * p[2] - rho / (scale * scale)
    if qa == 0.0:
        return None
    disc = qb * qb - 4.0 * qa * qc
    root = math.sqrt(abs(disc))
    if root / abs(qa) <= NODE_SEPARATION:
        ts = (-qb / (2.0 * qa),)                  # the line touches the quadric: the conics touch there (one node)
    elif disc < 0.0:
        return out, []
    else:
        ts = ((-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa))
    return out, [[foot[0] + scale * t * e0, foot[1] + scale * t * e1, foot[2] + scale * t * e2] for t in ts]
