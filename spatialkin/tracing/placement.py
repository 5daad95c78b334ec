"""How two placed surfaces sit relative to each other: bounding balls, coincidence, common axes, parallel rulings.

These decide the topology stage's special configurations (spatialkin.tracing.topology): coincident patches are
an error, coaxial surfaces of revolution meet in parallels (circles about the common axis), a cylinder and a
surface invariant along its axis meet in lines along it.
"""
import math

import numpy as np

from ..surfaces import Cone, Cylinder, Plane, Sphere, Torus

#: Two positions closer than this (relative to the scene scale), or two directions closer than this (radians),
#: are the same: the special configurations are recognised to round-off, not near it.
SAME = 1e-12


class CoincidentSurfacesError(ValueError):
    """The two patches overlap in a piece of surface (the same sphere twice, coaxial equal cylinders, coplanar
    planes ...): their intersection is two-dimensional, not a set of curves."""


def bounding_ball(surface):
    """(centre (3,), radius) of a ball holding the (trimmed) surface, or None when it is unbounded."""
    f = surface.frame
    if isinstance(surface, Sphere):
        return f.origin.copy(), surface.radius
    if isinstance(surface, Torus):
        return f.origin.copy(), surface.major_radius + surface.minor_radius
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    if isinstance(surface, Plane):
        if not np.all(np.isfinite([u0, u1, v0, v1])):
            return None
        return f.to_global([0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.0]), 0.5 * math.hypot(u1 - u0, v1 - v0)
    if not np.all(np.isfinite([v0, v1])):
        return None
    half = 0.5 * (v1 - v0)
    if isinstance(surface, Cylinder):
        return f.to_global([0.0, 0.0, 0.5 * (v0 + v1)]), math.hypot(surface.radius, half)
    t = math.tan(surface.half_angle)
    return f.to_global([0.0, 0.0, 0.5 * (v0 + v1)]), math.hypot(t * max(abs(v0), abs(v1)), half)


def revolution_axis(surface):
    """(point, unit direction) of the surface's axis of revolution; None for a sphere or a plane (any line
    through the centre, any normal line)."""
    if isinstance(surface, (Torus, Cylinder, Cone)):
        return surface.frame.origin, surface.frame.rotation[:, 2]
    return None


def _on_line(point, line_point, direction, tol):
    d = point - line_point
    return np.linalg.norm(d - (d @ direction) * direction) <= tol


def _parallel(d1, d2):
    return np.linalg.norm(np.cross(d1, d2)) <= SAME


def common_axis(a, b, scale):
    """(point, unit direction) of a line about which both surfaces are surfaces of revolution, or None.

    A sphere turns about any line through its centre and a plane about any line along its normal, so a sphere
    and a plane, or two spheres, always have one (two concentric spheres: any line through the centre).
    """
    tol = SAME * scale
    axes = [revolution_axis(s) for s in (a, b)]
    if axes[0] is None and axes[1] is None:
        kinds = {type(a), type(b)}
        if kinds == {Sphere}:
            d = b.frame.origin - a.frame.origin
            n = np.linalg.norm(d)
            return a.frame.origin, (d / n if n > tol else np.array([0.0, 0.0, 1.0]))
        if kinds == {Sphere, Plane}:
            sphere, plane = (a, b) if isinstance(a, Sphere) else (b, a)
            return sphere.frame.origin, plane.frame.rotation[:, 2]
        return None                                        # two planes: no axis of revolution in common
    if axes[0] is None:
        a, b, axes = b, a, axes[::-1]
    point, direction = axes[0]
    if axes[1] is not None:
        ok = _parallel(direction, axes[1][1]) and _on_line(axes[1][0], point, direction, tol)
    elif isinstance(b, Sphere):
        ok = _on_line(b.frame.origin, point, direction, tol)
    else:
        ok = _parallel(direction, b.frame.rotation[:, 2])
    return (point, direction) if ok else None


def ruled_along(a, b, scale=1.0):
    """The cylinder or cone (a or b) whose rulings the other surface respects, or None: a cylinder and a plane
    parallel to its axis or a cylinder with a parallel axis (invariant along the axis), a cone and a plane
    through its apex (invariant under scaling about it). Then the intersection is made of whole rulings."""
    for p, q in ((a, b), (b, a)):
        if isinstance(p, Cone) and isinstance(q, Plane):
            if abs((p.frame.origin - q.frame.origin) @ q.frame.rotation[:, 2]) <= SAME * scale:
                return p
            continue
        if not isinstance(p, Cylinder):
            continue
        axis = p.frame.rotation[:, 2]
        if isinstance(q, Plane) and abs(q.frame.rotation[:, 2] @ axis) <= SAME:
            return p
        if isinstance(q, Cylinder) and _parallel(axis, q.frame.rotation[:, 2]):
            return p
    return None


def same_surface(a, b, scale):
    """True when a and b are the same untrimmed surface (the same set of points)."""
    if type(a) is not type(b):
        return False
    tol = SAME * scale
    za, zb = a.frame.rotation[:, 2], b.frame.rotation[:, 2]
    if isinstance(a, Plane):
        return _parallel(za, zb) and abs((b.frame.origin - a.frame.origin) @ za) <= tol
    if isinstance(a, Sphere):
        return np.linalg.norm(a.frame.origin - b.frame.origin) <= tol and abs(a.radius - b.radius) <= tol
    if isinstance(a, Cylinder):
        return (abs(a.radius - b.radius) <= tol and _parallel(za, zb)
                and _on_line(b.frame.origin, a.frame.origin, za, tol))
    if isinstance(a, Cone):
        return (abs(a.half_angle - b.half_angle) <= SAME and _parallel(za, zb)
                and np.linalg.norm(a.frame.origin - b.frame.origin) <= tol)
    return (abs(a.major_radius - b.major_radius) <= tol and abs(a.minor_radius - b.minor_radius) <= tol
            and _parallel(za, zb) and np.linalg.norm(a.frame.origin - b.frame.origin) <= tol)


def trims_overlap(a, b):
    """For the same surface given twice: True when the two trimmed patches share a piece of positive area
    (compared in a's parameters; b's trim is mapped into them)."""
    if isinstance(a, (Sphere, Torus)):
        return True
    if isinstance(a, Plane):
        corners = []
        (u0, u1), (v0, v1) = b.u_range, b.v_range
        big = 1e300
        for u in (max(u0, -big), min(u1, big)):
            for v in (max(v0, -big), min(v1, big)):
                corners.append(b.frame.to_global([u, v, 0.0]))
        local = a.frame.to_local(np.array(corners))[:, :2]
        lo, hi = local.min(axis=0), local.max(axis=0)
        # b's rectangle is turned in a's plane: compare its bounding box first, then sample its inside
        if (lo[0] >= a.u_range[1] or hi[0] <= a.u_range[0] or lo[1] >= a.v_range[1] or hi[1] <= a.v_range[0]):
            return False
        return _rectangles_overlap(a, b)
    # cylinder, cone: the axial coordinate of b's rim in a's frame
    flip = float(a.frame.rotation[:, 2] @ b.frame.rotation[:, 2]) < 0
    lo_b, hi_b = b.v_range
    shift = float(a.frame.to_local(b.frame.origin)[2])
    lo_b, hi_b = (shift - hi_b, shift - lo_b) if flip else (shift + lo_b, shift + hi_b)
    return max(lo_b, a.v_range[0]) < min(hi_b, a.v_range[1])


def _rectangles_overlap(a, b, samples=64):
    """Two coplanar trimmed rectangles share an area: a grid of b's rectangle has a point strictly inside a's."""
    (u0, u1), (v0, v1) = b.u_range, b.v_range
    big = 1e6 * max(1.0, *[abs(x) for x in (*a.u_range, *a.v_range) if np.isfinite(x)])
    u0, u1, v0, v1 = max(u0, -big), min(u1, big), max(v0, -big), min(v1, big)
    uu, vv = np.meshgrid(np.linspace(u0, u1, samples)[1:-1], np.linspace(v0, v1, samples)[1:-1])
    pts = b.frame.to_global(np.stack([uu.ravel(), vv.ravel(), np.zeros(uu.size)], axis=1))
    loc = a.frame.to_local(pts)
    inside = ((loc[:, 0] > a.u_range[0]) & (loc[:, 0] < a.u_range[1]) & (loc[:, 1] > a.v_range[0])
              & (loc[:, 1] < a.v_range[1]))
    return bool(inside.any())


def check_not_coincident(a, b, scale):
    """Raise CoincidentSurfacesError when the patches overlap in a piece of surface."""
    if same_surface(a, b, scale) and trims_overlap(a, b):
        raise CoincidentSurfacesError(
            f"a and b are the same {type(a).__name__.lower()} and their patches overlap: the intersection is a "
            "piece of surface, not curves (compare them, or trim one so that the patches meet only along edges)")
