"""Certified intersection points: a Krawczyk test in arb ball arithmetic on each point's normal-plane system.

For a stored point p near the intersection curve of surfaces a and b, with unit tangent t, the 3 x 3 system

    G(x) = (F_a(x), F_b(x), t . (x - p))

has as zeros the points of a ∩ b in the plane through p normal to t. ``certify_points`` proves, with python-flint's
arb ball arithmetic (outward-rounded, so every computed ball contains the exact value), that the box
B = p + [-r, r]^3 holds exactly one zero of G, and returns the smallest r it found (from a short geometric
sequence). A returned r is a proof that a true point of the two untrimmed surfaces lies in the box: its
Euclidean distance from p is at most r * sqrt(3) (its max-norm distance at most r).

``implicit_arb`` evaluates the polynomial implicit function of a placed surface and its gradient on arb balls.

Both are the certified path of ``sk.intersect(..., certify=True)``; nothing here is jitted, and nothing here is on
the fast path.
"""
import math

import flint
import numpy as np
from flint import arb, arb_mat

from ...geometry.traits import UnknownSurfaceKindError, check_surface, traits
from ..._lib.validation import check_points, check_positive

__all__ = ["implicit_arb", "certify_points", "PRECISION_BITS"]

#: Working precision (bits) of the arb arithmetic. At 53 bits the rounding radius of G(p) dominates the Newton
#: step and the radii come out 5-100x larger than the distance to the curve (quartic torus terms; surfaces of size
#: 1e4-1e5); from 64 bits on the radii are set by the float64 points alone (measured on torus, sphere, cylinder,
#: cone and plane pairs of size 1e-4..1e5 placed up to 1e5 from the origin: 64 and 128 bits give the same radii).
#: 128 leaves a margin and costs the same time (the cost is Python overhead per arb operation).
PRECISION_BITS = 128
#: The first box half-width is this many times the max-norm of the Newton step Y G(p) (with its rounding radius).
NEWTON_STEP_FACTOR = 4.0
#: Factor by which the half-width grows after a failed test.
INFLATION = 4.0
#: Largest half-width tried, as a fraction of the smaller characteristic size of the two surfaces
#: (``Surface.size``; 1 for an unbounded plane or cone).
RADIUS_CAP_FRACTION = 1e-3
#: Smallest half-width tried is max(|p|_inf, size) * 2**-prec: only reached when G(p) is exactly zero in arb (p
#: exactly on both surfaces); any box then passes whose Jacobian enclosure is not singular.


class _ArbSurface:
    """A surface's frame and its implicit function's constants (its traits' arb_coefficients) as exact arb balls,
    at the working precision of its creation."""

    __slots__ = ("traits", "rot", "origin", "coefficients")

    def __init__(self, surface):
        try:
            self.traits = traits(type(surface))
        except UnknownSurfaceKindError:
            raise TypeError(f"surface must be a spatialkin surface, got {type(surface).__name__}") from None
        rot = np.asarray(surface.frame.rotation, dtype=float)
        # float64 -> arb is exact; rot[i][j] is R_ij, column j = local axis j in global coordinates
        self.rot = [[arb(float(rot[i, j])) for j in range(3)] for i in range(3)]
        self.origin = [arb(float(v)) for v in surface.frame.origin]
        self.coefficients = self.traits.arb_coefficients(surface, arb)

    def evaluate(self, x, with_value=True):
        """(F, [dF/dx_i]) at the arb 3-vector x (global); F is None unless with_value."""
        rot, o = self.rot, self.origin
        d0, d1, d2 = x[0] - o[0], x[1] - o[1], x[2] - o[2]
        # q = R^T (x - origin)
        qx = rot[0][0] * d0 + rot[1][0] * d1 + rot[2][0] * d2
        qy = rot[0][1] * d0 + rot[1][1] * d1 + rot[2][1] * d2
        qz = rot[0][2] * d0 + rot[1][2] * d1 + rot[2][2] * d2
        value, local = self.traits.arb_local(self.coefficients, (qx, qy, qz), with_value)
        # gradient in global coordinates: R grad_q (the terms of identically vanishing derivatives left out)
        grad = []
        for i in range(3):
            acc = None
            for k, g in enumerate(local):
                if g is not None:
                    acc = rot[i][k] * g if acc is None else acc + rot[i][k] * g
            grad.append(acc)
        return value, grad


def implicit_arb(surface, x):
    """Polynomial implicit function of a placed surface and its gradient, in arb ball arithmetic.

    With q = R^T (x - origin) the local coordinates (R = ``surface.frame.rotation``, origin =
    ``surface.frame.origin``, both converted exactly from float64):

    ========  =====================================================
    Plane     F = q_z
    Sphere    F = |q|^2 - R^2                       (R = radius)
    Cylinder  F = q_x^2 + q_y^2 - r^2               (r = radius)
    Cone      F = q_x^2 + q_y^2 - tan(a)^2 q_z^2    (double cone, apex at the origin, a = half_angle)
    Torus     F = (|q|^2 + R^2 - r^2)^2 - 4 R^2 (q_x^2 + q_y^2)   (R = major_radius, r = minor_radius)
    ========  =====================================================

    The zero set of F is the untrimmed surface; ``u_range``/``v_range`` trims are ignored. The gradient is
    analytic, dF/dx = R dF/dq. Balls of the result contain the exact values for every x in the input balls (arb's
    outward rounding), at the current ``flint.ctx.prec``; tan(a) is computed as a ball from the float half angle.

    Parameters
    ----------
    surface : Plane, Sphere, Cylinder, Cone or Torus
        The placed surface.
    x : sequence of 3 flint.arb (or floats)
        Point or box in global coordinates (length unit of the surfaces).

    Returns
    -------
    value : flint.arb
        F(x) (unit: length to the power 1, 2, 2, 2 or 4 by kind).
    gradient : list of 3 flint.arb
        dF/dx_i in global coordinates.

    Notes
    -----
    q = R^T (x - origin) is the inverse placement exactly only when R is exactly orthogonal; a float64 rotation is
    orthogonal to ~1e-16, so the certified surface differs from ``origin + R q_local`` by ~1e-16 times the local
    coordinates (not times the distance from the global origin).
    """
    xs = [v if isinstance(v, arb) else arb(float(v)) for v in x]
    if len(xs) != 3:
        raise ValueError(f"x must have 3 components, got {len(xs)}")
    return _ArbSurface(surface).evaluate(xs)


def _upper(ball):
    """A float >= every |value| in the ball (rounded up)."""
    return math.nextafter(float(ball.abs_upper()), math.inf)


def certify_points(a, b, points, tangents, radius0=None, *, max_radius=None, prec=PRECISION_BITS):
    """Prove, point by point, that a true intersection point of a and b lies in a small box around each point.

    For each point p and tangent t, the Krawczyk operator [1]_, [2]_ of the normal-plane system
    G(x) = (F_a(x), F_b(x), t . (x - p)) (F the implicit functions of ``implicit_arb``) on the box
    B = p + [-r, r]^3 is

        K(B) = c - Y G(c) + (I - Y J(B)) (B - c),   c = p (exact),

    with Y the float64 inverse of the float Jacobian at p and J(B) an interval enclosure of the Jacobian over B,
    all evaluated in arb ball arithmetic (outward rounding). If K(B) lies strictly inside B, B contains exactly one
    zero x* of G [1]_, [2]_: F_a(x*) = F_b(x*) = 0 and t . (x* - p) = 0. The half-width r starts at
    ``NEWTON_STEP_FACTOR`` times the max-norm of the Newton step Y G(p) (or ``radius0``) and grows by ``INFLATION``
    until the test succeeds or r exceeds the cap.

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
    prec : int, optional
        arb working precision in bits (default ``PRECISION_BITS`` = 128); restored on return.

    Returns
    -------
    radii : ndarray (N,) float64
        Certified box half-width r of each point (length unit; exactly the radius of the arb box that passed, which
        is a float), or ``inf`` where certification failed.

    Raises
    ------
    ValueError
        If points or tangents are not finite arrays of shape (N, 3) with the same N.
    TypeError
        If a or b is not a spatialkin surface.

    Notes
    -----
    Cost is dominated by Python overhead per arb operation: one value-and-gradient evaluation at p and one gradient
    evaluation per box tried; measured 0.10-0.21 ms per point at 128 bits (the same at 53 and 64) on every pair
    kind. A failing point costs up to ~log4(cap / first radius) box evaluations, except where the contraction term
    alone fills the box (singular Jacobian), which stops at once.

    The surfaces certified are the zero sets of ``implicit_arb`` (local coordinates R^T (x - origin), see there).
    The precision is set through flint's global context (``flint.ctx.workprec``), so calls from several threads at
    once are not safe.

    Typical radii: a few times the float64 spacing of the coordinates (~1e-11 at 1e5 from the origin, ~1e-15 near
    it) when the points are float-accurate.

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
    radii = np.full(pts.shape[0], np.inf)
    with flint.ctx.workprec(int(prec)):
        sa, sb = _ArbSurface(a), _ArbSurface(b)
        eye = arb_mat([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
        floor_scale = 2.0 ** -int(prec)
        for k in range(pts.shape[0]):
            p, t = pts[k], tans[k]
            radii[k] = _certify_one(sa, sb, p, t, radius0, cap,
                                    floor_scale * max(float(np.max(np.abs(p))), size), eye)
    return radii


def _certify_one(sa, sb, p, t, radius0, cap, floor, eye):
    """Box half-width r that passes the Krawczyk test at p (see certify_points), or inf."""
    c = [arb(float(v)) for v in p]
    fa, ga = sa.evaluate(c)
    fb, gb = sb.evaluate(c)
    jac = np.array([[float(g.mid()) for g in ga], [float(g.mid()) for g in gb], [float(v) for v in t]])
    try:
        y = np.linalg.inv(jac)
    except np.linalg.LinAlgError:
        return math.inf
    if not np.all(np.isfinite(y)):
        return math.inf
    ya = arb_mat([[float(v) for v in row] for row in y])           # exact copy of the float preconditioner
    tb = [arb(float(v)) for v in t]
    # G(c) = (F_a(c), F_b(c), 0): the third row vanishes exactly at c = p
    step = ya * arb_mat([[fa], [fb], [arb(0)]])                   # Y G(c), a ball
    steps = step.entries()
    if radius0 is not None:
        r = float(radius0)
    else:
        r = max(NEWTON_STEP_FACTOR * max(_upper(s) for s in steps), floor)
    while r <= cap:
        half = arb(0, r)
        r_box = float(half.rad())              # the box arb actually holds (radius rounded up to 30 bits)
        box = [ci + half for ci in c]
        _, ja = sa.evaluate(box, with_value=False)
        _, jb = sb.evaluate(box, with_value=False)
        m = eye - ya * arb_mat([ja, jb, tb])                          # I - Y J(B)
        k = (m * arb_mat([[half], [half], [half]])).entries()        # (I - Y J(B)) (B - c)
        r_arb = arb(r_box)
        if all((k[i] - steps[i]).abs_upper() < r_arb for i in range(3)):
            return r_box
        # the contraction term alone already fills the box (|I - Y J(B)| >= 1 in a row): larger boxes only make
        # J(B) wider, so stop (inf is always an honest answer)
        if any(float(kk.rad()) >= r_box for kk in k):
            return math.inf
        r *= INFLATION
    return math.inf
