"""How two placed surfaces sit relative to each other: bounding balls, coincidence, common axes, parallel rulings.

These decide the topology stage's special configurations (spatialkin.tracing.search.topology): coincident patches are
an error, coaxial surfaces of revolution meet in parallels (circles about the common axis), a cylinder and a
surface invariant along its axis meet in lines along it.
"""
import math

import numpy as np

from .traits import AXIS, NORMAL, POINT, SCALING, TRANSLATION
from .trims import region_values

#: Two positions closer than this (relative to the scene scale), or two directions closer than this (radians),
#: are the same: the special configurations are recognised to round-off, not near it.
SAME = 1e-12


class CoincidentSurfacesError(ValueError):
    """The two patches overlap in a piece of surface.

    Their intersection is two-dimensional, not a set of curves: the same sphere twice, coaxial equal cylinders,
    coplanar planes whose rectangles overlap.

    Parameters
    ----------
    message : str
        Which surfaces coincide, and where.

    Examples
    --------
    >>> import spatialkin as sk
    >>> try:
    ...     sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0))
    ... except sk.CoincidentSurfacesError as error:
    ...     print(type(error).__name__, isinstance(error, ValueError))
    CoincidentSurfacesError True
    """


def bounding_ball(surface):
    """(centre (3,), radius) of a ball holding the (trimmed) surface, or None when it is unbounded (made once per
    surface; the centre read-only)."""
    return surface.memo("bounding_ball", _bounding_ball)


def _bounding_ball(surface):
    ball = surface.traits.bounding_ball(surface)
    if ball is None:
        return None
    centre = np.array(ball[0], dtype=float)
    centre.flags.writeable = False
    return centre, float(ball[1])


def on_line(point, line_point, direction, tol):
    """True when point lies within tol of the line through line_point along the unit direction."""
    d = point - line_point
    return np.linalg.norm(d - (d @ direction) * direction) <= tol


def parallel(d1, d2, same=SAME):
    """True when the unit directions d1 and d2 are parallel or opposite (|d1 x d2| <= same)."""
    (x1, y1, z1), (x2, y2, z2) = (float(x) for x in d1), (float(x) for x in d2)
    return math.hypot(y1 * z2 - z1 * y2, z1 * x2 - x1 * z2, x1 * y2 - y1 * x2) <= same


def common_axis(a, b, scale):
    """(point, unit direction) of a line about which both surfaces are surfaces of revolution, or None.

    A sphere turns about any line through its centre and a plane about any line along its normal, so a sphere
    and a plane, or two spheres, always have one (two concentric spheres: any line through the centre).
    """
    tol = SAME * scale
    sym = [s.traits.symmetry(s) for s in (a, b)]
    if sym[0] is None or sym[1] is None:
        return None                                        # a kind that is no surface of revolution
    if sym[0][0] != AXIS and sym[1][0] != AXIS:
        if sym[0][0] == sym[1][0] == POINT:
            d = sym[1][1] - sym[0][1]
            n = np.linalg.norm(d)
            return sym[0][1], (d / n if n > tol else np.array([0.0, 0.0, 1.0]))
        if sym[0][0] == NORMAL and sym[1][0] == NORMAL:
            return None                                    # two planes: no axis of revolution in common
        centre, normal = (sym[0], sym[1]) if sym[0][0] == POINT else (sym[1], sym[0])
        return centre[1], normal[1]
    if sym[0][0] != AXIS:
        sym = sym[::-1]
    _, point, direction = sym[0]
    other = sym[1]
    if other[0] == AXIS:
        ok = parallel(direction, other[2]) and on_line(other[1], point, direction, tol)
    elif other[0] == POINT:
        ok = on_line(other[1], point, direction, tol)
    else:
        ok = parallel(direction, other[1])
    return (point, direction) if ok else None


def ruled_along(a, b, scale=1.0):
    """The surface (a or b) whose rulings the other surface respects, or None: a cylinder and a plane parallel to
    its axis or a cylinder with a parallel axis (invariant along the axis), a cone and a plane through its apex
    (invariant under scaling about it). Then the intersection is made of whole rulings."""
    for p, q in ((a, b), (b, a)):
        ruling = p.traits.ruling(p)
        if ruling is None:
            continue
        kind, q_traits = ruling[0], q.traits
        if kind == SCALING and q_traits.keeps_scaling(q, ruling[1], SAME * scale):
            return p
        if kind == TRANSLATION and q_traits.keeps_translation(q, ruling[1], SAME):
            return p
    return None


def same_surface(a, b, scale):
    """True when a and b are the same untrimmed surface (the same set of points)."""
    kind = a.traits
    if kind is not b.traits:
        return False
    return kind.same_surface(a, b, SAME * scale, SAME)


def trims_overlap(a, b):
    """For the same surface given twice: True when the two trimmed patches share a piece of positive area
    (compared in a's parameters; b's trim is mapped into them)."""
    return a.traits.trims_overlap(a, b)


#: Same-surface patches with angular or circular trims are compared on a grid of this many samples per
#: parameter of a's patch (infinite length ranges cut at OVERLAP_REACH x its size).
REGION_SAMPLES = 97
OVERLAP_REACH = 1e3


def regions_overlap(a, b):
    """For the same surface given twice: True when a grid of a's patch has a point strictly inside b's patch (its
    length trims and its region) and a's region; True when neither has a region (trims_overlap decides)."""
    if not (a.region or b.region):
        return True
    own = getattr(a.traits, "regions_overlap", None)            # a kind that compares its patches itself
    if own is not None:
        return own(a, b)
    reach = OVERLAP_REACH * a.size
    (u0, u1), (v0, v1) = (np.clip(r, -reach, reach) for r in a.traits.natural_domain(a))
    u, v = np.meshgrid(np.linspace(u0, u1, REGION_SAMPLES)[1:-1], np.linspace(v0, v1, REGION_SAMPLES)[1:-1])
    points = a.point(u.ravel(), v.ravel())
    inside = np.all(region_values(a, points) > 0.0, axis=1) & np.all(region_values(b, points) > 0.0, axis=1)
    (bu0, bu1), (bv0, bv1) = b.bounds
    uv = b.parameters(points)
    inside &= (uv[:, 0] > bu0) & (uv[:, 0] < bu1) & (uv[:, 1] > bv0) & (uv[:, 1] < bv1)
    return bool(inside.any())


def check_not_coincident(a, b, scale):
    """Raise CoincidentSurfacesError when the patches overlap in a piece of surface, or when they are patches of
    one surface (not a plane) that do not overlap (they meet, if at all, along their edges)."""
    if not same_surface(a, b, scale):
        return
    apart = not trims_overlap(a, b)
    if apart and a.traits.name == "plane":
        return                              # (two planes' patches that share an edge or a corner: a closed form)
    if apart or (a.region or b.region) and not regions_overlap(a, b):
        raise CoincidentSurfacesError(
            f"a and b are patches of the same {type(a).__name__.lower()} that share no area: they meet, if at all, "
            "along their trim edges, which sk.intersect does not compute for one surface given twice")
    raise CoincidentSurfacesError(
        f"a and b are the same {type(a).__name__.lower()} and their patches overlap: the intersection is a "
        "piece of surface, not curves (compare them, or trim one so that the patches meet only along edges)")
