"""Certificates proven exactly for two surfaces of revolution about one axis, in rational arithmetic on the floats.

Where spatialkin.tracing.search.exact decides a pair exactly (frames that are signed permutations, one common axis;
its common points of the meridians, tangencies included), the intersection is exactly one parallel circle per
common point with rho > 0 and one point per common point on the axis: every claim of the certificate (no component
missed, each curve one component, the curves distinct, the singular points) holds in exact arithmetic, and each
returned circle is bounded against its true circle along its whole dense output both ways
(spatialkin.kernels.certify.closed's distance_bound, in outward-rounded intervals), each contact point by its distance
to the true one. A tangency, which no interval method can prove, is proven here because rational arithmetic decides
the equality.

An answer with another number of curves than the exact one is wrong: its certificate says so, with the exact answer,
every claim not proven. An answer of the right count whose curves cannot be matched (another kind, or farther than
the bounds allow), and pairs the solver does not decide, get no certificate here (None) and go to the search's.

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (outward rounding).
"""
import math

import numpy as np

from ...kernels.certify import closed as kc
from ..closed.conic import ConicSolution
from ..curve.exact import CircleSolution, PointSolution
from ..curve.status import CLOSED, CONTACT, TANGENT
from ..search.exact import enclose, exact_points, float_above, float_below
from .certificate import CLAIMS, NOT_PROVEN, Certificate, Claim
from .closed import NO_SINGULAR, SMALL, answer, faithful, returned_curve

#: Mode of the certificates made here.
MODE = "exact (coaxial)"


def _truth(axis, rho, h):
    """The true circle (rho > 0) at h about the axis as kernels.certify.closed's truth rows (its centre, the plane's
    basis: the other two coordinate axes, exact; A = I / rho^2), or its centre alone (3, 2) for a point."""
    k, line = axis
    centre = np.empty((3, 2))
    others = [j for j in range(3) if j != k]
    for j, x in zip(others, line):
        centre[j] = enclose(x)
    centre[k] = h.enclosure()
    if rho.sign() == 0:
        return centre
    truth = np.zeros((kc.ROWS, 2))
    truth[kc.Z0:kc.Z0 + 3] = centre
    truth[kc.F1 + others[0]] = 1.0
    truth[kc.F2 + others[1]] = 1.0
    lo, hi = rho.enclosure()
    truth[kc.A11] = truth[kc.A22] = (float_below(1.0 / float_above(hi * hi)), float_above(1.0 / float_below(lo * lo)))
    return truth


def _point_bound(p, box):
    """An upper bound of the distance from the point p (3,) to every point of the box (3, 2)."""
    total = 0.0
    for x, (lo, hi) in zip(np.asarray(p, dtype=float).tolist(), box.tolist()):
        far = max(float_above(x - lo), float_above(hi - x))
        total = float_above(total + float_above(far * far))
    return float_above(math.sqrt(total))


def _bound(curve, axis, rho, h, double):
    """The proven bound between the returned curve and the true circle or point (rho, h), or None when the curve is
    not of its kind (a contact for a point on the axis, a tangent circle for a double point, a closed one else) or
    lies far from it."""
    truth = _truth(axis, rho, h)
    if rho.sign() == 0:
        if curve.status != CONTACT or not isinstance(curve.sol, PointSolution):
            return None
        bound = _point_bound(curve.points[0], truth)
        return bound if bound <= 1e3 * curve.tolerance else None
    if curve.status != (TANGENT if double else CLOSED) or not isinstance(curve.sol, (CircleSolution, ConicSolution)):
        return None
    c, P, Q = returned_curve(curve.sol)
    off = faithful(curve, 2.0 * math.pi)
    if c is None or off is None:
        return None
    bound = kc.distance_bound(truth, np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(P, dtype=float),
                              np.ascontiguousarray(Q, dtype=float))
    if not bound < SMALL * rho.enclosure()[0]:
        return None
    return float_above(bound + off)


def coaxial_certificate(a, b, curves):
    """The Certificate of the answer curves (CurveResults) of two surfaces turning about one axis exactly, every
    claim proven in exact arithmetic, or None when the pair is not one this module decides or the answer is not the
    exact one (its curves one to one with the true circles and points, each of the right kind and within the
    bound)."""
    found = exact_points(a, b)
    if found is None:
        return None
    axis, points = found
    how = ("the surfaces turn about one axis exactly (their frames are signed permutations): they meet in the "
           "parallels through the common points of their meridians, found in rational arithmetic")
    touching = sum(1 for rho, _, double in points if double or rho.sign() == 0)
    singular = (f"{touching} circle(s) of tangency or point(s) of contact, each a double common point of the "
                "meridians (or one on the axis), exact in rational arithmetic" if touching else NO_SINGULAR)
    kinds = [("circle(s) of tangency", sum(1 for rho, _, double in points if double and rho.sign() > 0)),
             ("circle(s) crossed", sum(1 for rho, _, double in points if not double and rho.sign() > 0)),
             ("point(s) on the axis", sum(1 for rho, _, _ in points if rho.sign() == 0))]
    exact = "the surfaces meet in " + (", ".join(f"{n} {kind}" for kind, n in kinds if n) or "no point")
    return exact_certificate(curves, [lambda curve, p=p: _bound(curve, axis, *p) for p in points], how, singular,
                             "true circle or point", MODE, exact)


def exact_certificate(curves, bounds_of, how, singular, truth, mode, exact):
    """The Certificate, every claim proven (complete, one_component and distinct for the reason how, singular for
    the reason singular), of curves matched one to one with the true curves: bounds_of holds, per true curve, a
    function of a returned curve giving its proven bound, or None where that curve is not it (of another kind, or
    far); None when the curves cannot be matched so. truth: what the bounds are to. Where the answer has another
    number of curves than the exact one (exact: what that is, said), the answer is wrong: a Certificate with every
    claim not proven, saying so."""
    if len(bounds_of) != len(curves):
        text = f"the answer is not the exact one: exactly, {exact}; {len(curves)} curve(s) returned"
        none = np.empty((0, 3))
        claims = [Claim(name, NOT_PROVEN, text, none, np.empty(0)) for name in CLAIMS]
        return Certificate(claims, None, [np.full(len(curve.points), math.inf) for curve in curves],
                           [None] * len(curves), [math.inf] * len(curves), len(curves), mode=mode)
    bounds = [None] * len(curves)
    for bound_of in bounds_of:
        options = [(bound, i) for i, curve in enumerate(curves) if bounds[i] is None
                   for bound in [bound_of(curve)] if bound is not None]
        if not options:
            return None
        bound, i = min(options)
        bounds[i] = bound
    radii = [np.full(len(curve.points), bound) for curve, bound in zip(curves, bounds)]
    return answer(radii, bounds, how, f"its {truth}", singular, mode)
