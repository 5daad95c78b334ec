"""Certified intersection points: the Krawczyk test on each point's normal-plane system, in interval arithmetic.

For a stored point p near the intersection curve of surfaces a and b, with unit tangent t, the 3 x 3 system

    G(x) = (F_a(x), F_b(x), t . (x - p))

has as zeros the points of a ∩ b in the plane through p normal to t. ``certify_points`` proves, with outward-rounded
interval arithmetic (compiled: spatialkin.kernels.certify.points), that the box B = p + [-r, r]^3 holds exactly one
zero of G, and returns the smallest r it found (from a short geometric sequence). A returned r is a proof that a
true point of the two untrimmed surfaces lies in the box: its Euclidean distance from p is at most r * sqrt(3).
"""
import numpy as np

from ...geometry.traits import check_surface
from ...kernels.certify import points as kp
from ..._lib.validation import check_points, check_positive

__all__ = ["certify_points"]

#: Largest half-width tried, as a fraction of the smaller characteristic size of the two surfaces
#: (``Surface.size``; 1 for an unbounded plane or cone).
RADIUS_CAP_FRACTION = 1e-3


def certify_points(a, b, points, tangents, radius0=None, *, max_radius=None):
    """Prove, point by point, that a true intersection point of a and b lies in a small box around each point.

    For each point p and tangent t, the Krawczyk operator [1]_, [2]_ of the normal-plane system
    G(x) = (F_a(x), F_b(x), t . (x - p)) (F the surfaces' polynomial implicit functions) on the box
    B = p + [-r, r]^3 is

        K(B) = c - Y G(c) + (I - Y J(B)) (B - c),   c = p (exact),

    with Y the float64 inverse of the float Jacobian at p and J(B) an interval enclosure of the Jacobian over B,
    all evaluated in interval arithmetic with outward rounding (compiled: spatialkin.kernels.certify.points). If
    K(B) lies strictly inside B, B contains exactly one zero x* of G [1]_, [2]_: F_a(x*) = F_b(x*) = 0 and
    t . (x* - p) = 0. The half-width r starts at twice the max-norm of the Newton step Y G(p) (or ``radius0``)
    and doubles until the test succeeds or r exceeds the cap.

    What a finite radius r proves: a point x* lying on both untrimmed surfaces (their implicit zero sets) with
    max_i |x*_i - p_i| <= r, hence Euclidean distance |x* - p| <= r * sqrt(3); x* lies in the plane through p
    normal to t and is the only such point in the box. What it does not prove: that x* lies inside trims
    (u_range, v_range), which component of the intersection x* belongs to, or anything about the curve between
    stored points. ``inf`` proves nothing: it is returned where no tried box passed, in particular at a tangency
    (contact) point or a singular point of the curve (parallel normals, a node, the apex of a cone), where the
    Jacobian of G is singular and no box can pass, and for points farther from the curve than about the cap.

    Parameters
    ----------
    a, b : Plane, Sphere, Cylinder, Cone or Torus
        The two placed surfaces.
    points : array_like (N, 3)
        Points near the intersection curve (global coordinates, float64, length unit).
    tangents : array_like (N, 3)
        Tangent of the curve at each point (need not be exactly unit, nor exactly tangent: it fixes the plane
        through p in which the true point is sought).
    radius0 : float, optional
        First half-width tried (length unit), instead of the one from the Newton step.
    max_radius : float, optional
        Largest half-width tried (length unit); default ``RADIUS_CAP_FRACTION`` times the smaller ``size`` of the
        two surfaces (and at least ``radius0``).

    Returns
    -------
    radii : ndarray (N,) float64
        Certified box half-width r of each point (length unit: the box that passed, rounded up), or ``inf`` where
        certification failed.

    Raises
    ------
    ValueError
        If points or tangents are not finite arrays of shape (N, 3) with the same N.
    TypeError
        If a or b is not a spatialkin surface.

    Notes
    -----
    The surfaces certified are the zero sets of their implicit functions in local coordinates R^T (x - origin), with
    R and origin the surface's own float data (exactly orthogonal R assumed: a float64 rotation is orthogonal to
    ~1e-16, so the certified surface differs from ``origin + R q_local`` by ~1e-16 times the local coordinates).
    The constants (R^2, r^2, tan^2 of the cone) are enclosed as intervals. Typical radii: a few times the float64
    spacing of the coordinates (~1e-11 at 1e5 from the origin, ~1e-15 near it) when the points are float-accurate.

    References
    ----------
    .. [1] R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing 4
       (1969) 187-201.
    .. [2] R. E. Moore, R. B. Kearfott, M. J. Cloud, *Introduction to Interval Analysis*, SIAM, 2009, sec. 8.2
       (the Krawczyk method) and sec. 8.4 (existence and uniqueness tests).
    """
    check_surface("a", a)
    check_surface("b", b)
    pts = check_points("points", points, allow_empty=True)
    tans = check_points("tangents", tangents, allow_empty=True)
    if tans.shape[0] != pts.shape[0]:
        raise ValueError(f"tangents must have the same number of rows as points: {tans.shape[0]} != {pts.shape[0]}")
    check_positive("radius0", radius0, allow_none=True)
    size = min(a.size, b.size)
    cap = RADIUS_CAP_FRACTION * size if max_radius is None else float(max_radius)
    if radius0 is not None:
        cap = max(cap, float(radius0))
    radii = np.empty(pts.shape[0])
    kp.point_radii(a.data, b.data, np.ascontiguousarray(pts), np.ascontiguousarray(tans), cap, size,
                   0.0 if radius0 is None else float(radius0), radii)
    return radii
