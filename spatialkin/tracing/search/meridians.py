"""A surface of revolution and a second surface that touch along a whole meridian of the first, with other curves
beside it: a meridian circle of a torus (two tori of equal tubes whose axes lie in one plane, a ball inscribed in
the tube), a generator of a cone or a cylinder (two cones holding one generator, their axes in one plane with it:
a polygon's edge revolved about two axes).

On P, with g(u, v) = F_Q(P(u, v)), the meridian is the line u = u0 where g and g_u vanish for every v:
g = (u - u0)^2 (g_uu / 2 + ...) near it. The interval search cannot exclude the boxes along it (g vanishes to
second order), so spatialkin.tracing.search.topology searches P's domain less a band |u - u0| < BAND (seeding the other
components on the band's edges), returns the meridian in closed form as a circle or a segment of tangency (the
segment clipped by both surfaces' trims), and gives the points
where another branch crosses it as nodes: there the second-order term changes sign, the roots of g_uu(u0, v)
(g = (u - u0)^2 g_uu / 2 + (u - u0)^3 g_uuu / 6 + ...: the branch g_uu / 2 + (u - u0) g_uuu / 6 = 0 meets
u = u0 where g_uu = 0).

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(tangential intersections of surfaces; intersection curves that branch).
"""
import math

import numpy as np
from scipy.optimize import brentq


#: The meridian is sought on a grid of this many angles u, g read at MERIDIAN_SAMPLES angles v round the tube.
U_GRID = 1440
MERIDIAN_SAMPLES = 16
#: g and g_u vanish along the meridian within this fraction of their largest on the grid (round-off).
FLAT = 1e-11
#: Half width (radians of u) of the band about the meridian left out of the search.
BAND = 1e-3
#: Unresolved boxes of the search within this many BANDs of the meridian are its second-order flatness, not
#: singular points of other branches (those cross the band's edges, where they are seeded, and the meridian at
#: the crossings below).
BESIDE = 10.0
#: The crossings of other branches are the sign changes of g_uu on this many angles v round the meridian.
NODE_GRID = 720


#: The kinds whose meridians are the lines u = const of their chart.
REVOLVED = ("torus", "cone", "cylinder")


def tangent_meridians(p, reader, v_range):
    """Angles u0 of the meridians of p (a torus, cone or cylinder) along which it touches the surface q of reader
    (topology.Reader(p, q): g = F_q o p), v in v_range (finite); [] when there is none or p has no such meridians."""
    if p.traits.name not in REVOLVED:
        return []
    u = np.linspace(-math.pi, math.pi, U_GRID, endpoint=False)
    v = np.linspace(*v_range, MERIDIAN_SAMPLES)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    values = reader.values(np.stack([uu.ravel(), vv.ravel()], axis=1)).reshape(U_GRID, MERIDIAN_SAMPLES, 6)
    g, g_u = values[..., 0], values[..., 1]
    big_g, big_gu = float(np.abs(g).max()), float(np.abs(g_u).max())
    if big_g == 0.0 or big_gu == 0.0:
        return []
    score = np.abs(g).max(axis=1) / big_g
    found = []
    for i in np.nonzero((score <= np.roll(score, 1)) & (score <= np.roll(score, -1)) & (score < 1e-3))[0]:
        k = int(np.argmax(np.abs(values[i, :, 3])))          # g_u has a simple root at u0 where g_uu is largest
        lo, hi = u[i] - 2 * math.pi / U_GRID, u[i] + 2 * math.pi / U_GRID
        slope = lambda x: float(reader.values([[x, v[k]]])[0, 1])          # noqa: E731
        if slope(lo) * slope(hi) > 0:
            continue
        u0 = brentq(slope, lo, hi, xtol=1e-15, rtol=1e-15)
        check = reader.values(np.stack([np.full(4 * MERIDIAN_SAMPLES, u0),
                                        np.linspace(*v_range, 4 * MERIDIAN_SAMPLES)], axis=1))
        if np.abs(check[:, 0]).max() <= FLAT * big_g and np.abs(check[:, 1]).max() <= FLAT * big_gu:
            if all(abs(math.remainder(u0 - w, 2 * math.pi)) > BAND for w in found):
                found.append(u0)
    return found


def meridian_circle(p, u0):
    """(centre (3,), axis (3,), radius) of the meridian u = u0 of the torus p."""
    c, s = math.cos(u0), math.sin(u0)
    centre = p.frame.global_of([p.major_radius * c, p.major_radius * s, 0.0])
    axis = p.frame.rotation @ np.array([-s, c, 0.0])
    return centre, axis, p.minor_radius


def meridian_segment(p, q, u0, v_range):
    """(p0, p1) of the generator u = u0 of the cone or cylinder p over v_range, clipped by the trims of q that
    are lengths along its local axes (exact: they are affine along the line); None where nothing is left."""
    ends = p.point(np.full(2, u0), np.asarray(v_range, dtype=float))
    local = q.frame.local_of(ends)
    lo, hi = 0.0, 1.0
    for axis, (a, b) in zip(q.traits.parameter_axes, q.bounds):
        if axis is None:
            continue
        x0, dx = local[0, axis], local[1, axis] - local[0, axis]
        if dx == 0.0:
            if not a <= x0 <= b:
                return None
            continue
        t0, t1 = sorted(((a - x0) / dx, (b - x0) / dx))
        lo, hi = max(lo, t0), min(hi, t1)
    if not lo < hi:
        return None
    return ends[0] + lo * (ends[1] - ends[0]), ends[0] + hi * (ends[1] - ends[0])


def meridian_nodes(p, reader, u0, v_range):
    """Points (K, 3) of the meridian u = u0 (v in v_range) where another branch of the intersection crosses it:
    the sign changes of g_uu(u0, v), solved by Brent's method."""
    v = np.linspace(*v_range, NODE_GRID + 1)
    second = reader.values(np.stack([np.full(len(v), u0), v], axis=1))[:, 3]
    curvature = lambda x: float(reader.values([[u0, x]])[0, 3])          # noqa: E731
    roots = [brentq(curvature, v[i], v[i + 1], xtol=1e-15, rtol=1e-15)
             for i in np.nonzero(np.sign(second[:-1]) * np.sign(second[1:]) < 0)[0]]
    roots += [float(v[i]) for i in np.nonzero(second[:-1] == 0.0)[0]]
    return p.point(np.full(len(roots), u0), np.array(roots)).reshape(-1, 3)
