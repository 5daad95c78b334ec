"""B-splines of curves with a measured tolerance: quintic Hermite data (point, first and second derivative at each
knot, all exact) turned into a C2 B-spline with triple interior knots, the knots refined until the spline's
distance from exact points of the curve, measured between every two knots, is below the tolerance.

Used by ``Curve.to_bspline`` (intersection curves by arc length; the derivatives are the unit tangent and the
curvature vector from the two surfaces' implicit functions) and by mechanism trajectories (by crank angle).

References
----------
L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer 1997: blossoms and control points (ch. 2, 5).
"""
import math

import numpy as np
from scipy.interpolate import BSpline

#: Degree of the B-spline: a quintic matches the point, the first and the second derivative at both ends of
#: every span (C2 everywhere).
DEGREE = 5
#: Spline points compared with exact curve points inside every span, at (k + 1) / (CHECKS_PER_SPAN + 1): the
#: middle of the span (where a quintic Hermite error u^3 (1 - u)^3 peaks) among them.
CHECKS_PER_SPAN = 9
#: A span passes when its measured deviation is below this fraction of the tolerance (the samples may miss
#: the peak by a few per cent).
SAFETY = 0.9
#: Spans at the start, before refinement.
INITIAL_SPANS = 8
#: Rounds of refinement (each halves every span still above the tolerance).
MAX_ROUNDS = 40
#: Halving the spans cuts a quintic's error about 64-fold once they are short beside the curve's radius of
#: curvature. Two rounds in a row that do not halve the largest deviation, while it is below STALL_FLOOR times
#: the curve's extent or below STALL_CHORD times the chord of the span where it sits, have met the error of the
#: curve's exact points (their round-off, or the conditioning of a near-tangent intersection): the tolerance
#: cannot be reached. Above both, a span is still long beside a sharp bend, where halving may not yet halve the
#: error: a near-tangent loop's deviation goes 0.197, 0.291, 0.189, 0.069 in its first rounds. A quintic
#: Hermite span of chord h bends away from a circle of radius R by about h (h / R)^5 / 46080, so a deviation
#: below 1e-3 h that does not fall 64-fold when h halves is not truncation.
STALL = 0.5
STALL_FLOOR = 1e-6
STALL_CHORD = 1e-3
#: Most knots of one spline.
MAX_KNOTS = 100_000


class SplineToleranceError(RuntimeError):
    """The tolerance asked of a B-spline could not be reached (below the round-off of the curve's points)."""


def bezier_spans(x, points, d1, d2):
    """Bezier control points (n, 6, dim) of the quintic Hermite interpolant on each span [x_j, x_j+1]."""
    h = np.diff(x)[:, None]
    p0, p1 = points[:-1], points[1:]
    a0, a1 = d1[:-1], d1[1:]
    c0, c1 = d2[:-1], d2[1:]
    return np.stack([p0, p0 + h / 5 * a0, p0 + 2 * h / 5 * a0 + h * h / 20 * c0,
                     p1 - 2 * h / 5 * a1 + h * h / 20 * c1, p1 - h / 5 * a1, p1], axis=1)


def blossom(bezier, a, b, args):
    """The blossom of the quintic with Bezier points bezier (6, dim) on [a, b] at args (5,) (de Casteljau with
    one parameter per level)."""
    pts = bezier.copy()
    for level, x in enumerate(args):
        u = (x - a) / (b - a)
        pts = (1 - u) * pts[:-1] + u * pts[1:]
    return pts[0]


def hermite_bspline(x, points, d1, d2, periodic=False):
    """The C2 quintic B-spline through points (n+1, dim) at increasing parameters x (n+1,) with first and
    second derivatives d1, d2 there: knots x[0] and x[-1] six times, the others three times, control points the
    blossoms of the Hermite pieces (exact: the same polynomials, 3 (n+1) control points)."""
    x = np.asarray(x, dtype=float)
    bez = bezier_spans(x, np.asarray(points, float), np.asarray(d1, float), np.asarray(d2, float))
    knots = np.concatenate([[x[0]] * 6, np.repeat(x[1:-1], 3), [x[-1]] * 6])
    m = len(knots) - DEGREE - 1
    coef = np.empty((m, bez.shape[2]))
    span_of_knot = np.searchsorted(x, knots, side="right") - 1
    for l in range(m):
        # a span [knots[i], knots[i + 1]] with l in [i - DEGREE, i]: the last non-empty one at or before l + 5
        i = l + DEGREE
        while knots[i + 1] <= knots[i]:
            i -= 1
        j = min(span_of_knot[i], len(bez) - 1)
        coef[l] = blossom(bez[j], x[j], x[j + 1], knots[l + 1:l + DEGREE + 1])
    return BSpline(knots, coef, DEGREE, extrapolate="periodic" if periodic else False)


def fit(evaluate, x0, x1, tol, periodic=False, initial=None):
    """A C2 quintic B-spline of a curve x -> point on [x0, x1], within tol of it (measured).

    Parameters
    ----------
    evaluate : callable
        evaluate(x (M,)) -> (points (M, dim), first derivatives (M, dim), second derivatives (M, dim)), exact.
    x0, x1 : float
        Parameter range.
    tol : float
        Largest distance allowed between the spline and the curve, in the curve's length unit: measured at
        CHECKS_PER_SPAN points of every span as the distance to the curve point found by one Newton step from
        the same parameter (an upper bound of the distance to the curve).
    periodic : bool
        The curve is closed (its data at x0 and x1 agree): the spline extrapolates periodically.
    initial : array_like, optional
        Knots to start from (default: INITIAL_SPANS equal spans).

    Returns
    -------
    scipy.interpolate.BSpline
        With attributes ``deviation`` (the largest measured distance) and ``checked`` (how many exact points it
        was compared with).

    Raises
    ------
    SplineToleranceError
        If tol cannot be reached (the knots would crowd below the round-off of the parameter).
    """
    knots = np.linspace(x0, x1, INITIAL_SPANS + 1) if initial is None else np.unique(np.r_[x0, initial, x1])
    cache = {}

    def data(xs):
        todo = [v for v in xs if v not in cache]
        if todo:
            p, a, c = evaluate(np.array(todo))
            for k, v in enumerate(todo):
                cache[v] = (p[k], a[k], c[k])
        rows = [cache[v] for v in xs]
        return tuple(np.array([r[i] for r in rows]) for i in range(3))

    checked, stalled, previous = 0, 0, math.inf
    for _ in range(MAX_ROUNDS):
        p, a, c = data(knots)
        spline = hermite_bspline(knots, p, a, c, periodic)
        frac = (np.arange(CHECKS_PER_SPAN) + 1.0) / (CHECKS_PER_SPAN + 1)
        xs = (knots[:-1, None] + frac[None, :] * np.diff(knots)[:, None]).ravel()
        approx = spline(xs)
        exact, tangent, _ = evaluate(xs)
        # one Newton step to the foot point on the curve (its own parameter may drift from the spline's by the
        # integration's error in s): the distance to that curve point bounds the distance to the curve
        xs_foot = xs + np.einsum("ij,ij->i", approx - exact, tangent) / np.einsum("ij,ij->i", tangent, tangent)
        if not periodic:
            xs_foot = np.clip(xs_foot, x0, x1)
        exact, _, _ = evaluate(xs_foot)
        checked += 2 * len(xs)
        dev = np.linalg.norm(approx - exact, axis=1).reshape(-1, CHECKS_PER_SPAN).max(axis=1)
        bad = dev > SAFETY * tol
        if not bad.any():
            spline.deviation = float(dev.max())
            spline.checked = checked
            return spline
        worst = float(dev.max())
        at = int(np.argmax(dev))
        chord = float(np.linalg.norm(p[at + 1] - p[at]))
        noise = worst <= STALL_FLOOR * np.ptp(p, axis=0).max() or worst <= STALL_CHORD * chord
        stalled = stalled + 1 if worst > STALL * previous and noise else 0
        previous = worst
        mids = 0.5 * (knots[:-1] + knots[1:])[bad]
        if stalled >= 2 or len(knots) + len(mids) > MAX_KNOTS or np.min(np.diff(knots)[bad]) <= 1e-12 * (abs(x1) + abs(x0) + 1):
            break
        knots = np.sort(np.r_[knots, mids])
    raise SplineToleranceError(f"a B-spline within {tol:.3g} was not reached (measured {dev.max():.3g} with "
                               f"{len(knots)} knots): ask a tolerance above the round-off of the curve's points")
