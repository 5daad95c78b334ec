"""Certificates proven exactly for two surfaces along one coordinate axis, in rational arithmetic on the floats:
cylinders whose axes are parallel, and a plane parallel to a cylinder's axis.

A cylinder and a plane placed by frames whose rotations are signed permutations (exactly orthogonal) are exactly
invariant along their frame's z axis (the cylinder) or along an in-plane axis (the plane). Where both run along the
same coordinate axis e_k, a point lies on both exactly when its other two coordinates lie on both cross-sections:
a circle (x - a)^2 + (y - b)^2 = r^2 or a line x = p, with rational coefficients, met where a quadratic vanishes,
solved exactly as in spatialkin.tracing.search.exact (crossings: roots p + q sqrt(D), signs decided exactly; a
double root, D = 0, is a tangency of the sections, so of the surfaces along a line). Each common point of the
sections is a line along e_k, cut by the trims along e_k (a cylinder's v, the plane's range along it) into one
segment, kept where it lies strictly inside the plane's range across it.

The intersection is then exactly those segments: every claim holds in exact arithmetic, and each returned segment (a
segment of tangency or a line of the closed forms, its dense output affine in s) is bounded against its true
segment, ends enclosed in intervals (spatialkin.kernels.certify.closed.segment_bound). An answer with another number
of curves than the exact one is said to be wrong (spatialkin.tracing.certify.coaxial.exact_certificate). An answer
traced by the tracer (its dense output is not affine), a segment ending on a trim in a single point, a half-open
trim, and any other placement get no certificate here (None).

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (outward rounding).
"""
import math
from fractions import Fraction

import numpy as np

from ...geometry.surfaces import Cylinder, Plane
from ...kernels.certify import closed as kc
from ..curve.status import BOUNDARY, TANGENT
from .closed import SMALL, faithful, is_segment
from ..search.exact import Meridian, crossings, enclose, signed_axis
from .coaxial import NO_SINGULAR, exact_certificate

#: Mode of the certificates made here.
MODE = "exact (parallel)"


def _range(surface, col, k, sign):
    """The surface's trim of parameter col (0: u, 1: v) as a range of coordinate k (Fractions, sorted), None when
    untrimmed, False when half-open."""
    lo, hi = surface.bounds[col]
    if math.isinf(lo) and math.isinf(hi):
        return None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return False
    o = Fraction(surface.frame.origin[k])
    return tuple(sorted((o + sign * Fraction(lo), o + sign * Fraction(hi))))


def section(surface, k, others):
    """(its cross-section normal to e_k as a Meridian in the coordinates others, its range along e_k, its range
    across (coordinate index among others, range) or None), or None where the surface does not run along e_k
    exactly or is trimmed otherwise."""
    rot = np.asarray(surface.frame.rotation, dtype=float)
    if signed_axis(rot) is None or surface.region:
        return None
    origin = [Fraction(surface.frame.origin[j]) for j in range(3)]
    axes = [int(np.flatnonzero(rot[:, col])[0]) for col in range(3)]
    signs = [int(rot[axes[col], col]) for col in range(3)]
    if isinstance(surface, Cylinder):
        if axes[2] != k or not all(math.isinf(x) for x in surface.bounds[0]):
            return None
        a, b, r = origin[others[0]], origin[others[1]], Fraction(surface.radius)
        along = _range(surface, 1, k, signs[2])
        return None if along is False else (Meridian(1, -2 * a, -2 * b, a * a + b * b - r * r), along, None)
    if not isinstance(surface, Plane) or k not in axes[:2]:
        return None
    normal = others.index(axes[2])
    p = origin[axes[2]]
    line = Meridian(0, 1, 0, -p) if normal == 0 else Meridian(0, 0, 1, -p)
    col_along = axes.index(k)
    col_across = 1 - col_along
    along = _range(surface, col_along, k, signs[col_along])
    across = _range(surface, col_across, axes[col_across], signs[col_across])
    if along is False or across is False:
        return None
    return line, along, None if across is None else (others.index(axes[col_across]), across)


def exact_segments(a, b):
    """(k, others, [(x0, x1, lo, hi, double)]): the segments along e_k where the surfaces meet, each at the common
    point (x0, x1) (Surds) of their sections, from lo to hi (Fractions) along e_k; or None where the pair is not one
    this module decides."""
    if not (isinstance(a, Cylinder) or isinstance(b, Cylinder)):
        return None
    cylinder = a if isinstance(a, Cylinder) else b
    own = signed_axis(cylinder.frame.rotation)
    if own is None:
        return None
    k = own[0]
    others = [j for j in range(3) if j != k]
    sections = [section(s, k, others) for s in (a, b)]
    if sections[0] is None or sections[1] is None:
        return None
    points = crossings(sections[0][0], sections[1][0])
    if points is None:
        return None
    lows = [s[1][0] for s in sections if s[1] is not None]
    highs = [s[1][1] for s in sections if s[1] is not None]
    if not lows:
        return None                                             # (unbounded along e_k)
    lo, hi = max(lows), min(highs)
    out = []
    for x0, x1, double in points:
        inside = True
        for _, _, across in sections:
            if across is None:
                continue
            index, (near, far) = across
            x = (x0, x1)[index]
            signs = ((x - near).sign(), (x - far).sign())
            if 0 in signs:
                return None                                     # (on the plane's edge across)
            inside = inside and signs[0] > 0 > signs[1]
        if not inside or lo > hi:
            continue
        if lo == hi:
            return None                                         # (a single point of the trims' edges)
        out.append((x0, x1, lo, hi, double))
    return k, others, out


def _ends(k, others, x0, x1, lo, hi):
    """The true segment's ends as intervals (6, 2): rows 0-2 the end at lo, 3-5 at hi."""
    ends = np.empty((6, 2))
    for row, h in ((0, lo), (3, hi)):
        ends[row + others[0]] = x0.enclosure()
        ends[row + others[1]] = x1.enclosure()
        ends[row + k] = enclose(h)
    return ends


def _bound(curve, k, others, x0, x1, lo, hi, double):
    """The proven bound between the returned curve and the true segment, or None when the curve is not of its kind
    (a segment of tangency for a double point, an open line ending on the trims else) or lies far from it."""
    if curve.closed or curve.status != (TANGENT if double else BOUNDARY) or not is_segment(curve.sol):
        return None
    off = faithful(curve, None)
    if off is None:
        return None
    a, b = (np.ascontiguousarray(p, dtype=float) for p in curve.sol(np.array([0.0, curve.length])))
    bound = kc.segment_bound(_ends(k, others, x0, x1, lo, hi), a, b)
    if not bound < SMALL * float(hi - lo):
        return None
    return math.nextafter(bound + off, math.inf)


def parallel_certificate(a, b, curves):
    """The Certificate of the answer curves (CurveResults) of two surfaces running along one coordinate axis
    exactly, every claim proven in exact arithmetic, or None when the pair is not one this module decides or the
    answer is not the exact one."""
    found = exact_segments(a, b)
    if found is None:
        return None
    k, others, segments = found
    how = ("the surfaces run along one coordinate axis exactly (their frames are signed permutations): they meet in "
           "the lines through the common points of their cross-sections, found in rational arithmetic, cut by the "
           "trims")
    touching = sum(1 for *_, double in segments if double)
    singular = (f"{touching} segment(s) of tangency, each through a double common point of the cross-sections, "
                "exact in rational arithmetic" if touching else NO_SINGULAR)
    crossed = len(segments) - touching
    exact = "the surfaces meet in " + (", ".join(f"{n} {kind}" for kind, n in (("segment(s) of tangency", touching),
                                                                               ("segment(s) crossed", crossed)) if n)
                                       or "no point")
    return exact_certificate(curves, [lambda curve, s=s: _bound(curve, k, others, *s) for s in segments], how,
                             singular, "true segment", MODE, exact)
