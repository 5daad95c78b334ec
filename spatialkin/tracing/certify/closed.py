"""Certificates proven in closed form: two untrimmed spheres, or a plane and an untrimmed sphere, a cylinder or a
cone (each trimmed by lengths, or not) meet in one circle or ellipse or in nothing, and two planes in one segment or
nothing, which interval arithmetic decides without a search (spatialkin.kernels.certify.closed). The returned curve is then proven within a Hausdorff
distance of the true one along its whole dense output, both ways. Any other answer, or a pair the algebra leaves
undecided (a tangency, a hyperbola, a curve reaching a trim edge), goes to the search's certificate
(spatialkin.tracing.certify.certificate).
"""
import math

import numpy as np

from ...geometry.surfaces import Cone, Cylinder, Plane, Sphere
from ...kernels.certify import closed as kc
from ...kernels.geometry.interval import EPS, up
from ...kernels.geometry import surfaces as ks
from ..closed.conic import ELLIPSE, LINE, ConicSolution
from ..curve.exact import CircleSolution, SegmentSolution
from .certificate import PROVEN, Certificate, Claim

#: The pairs proven here (their class names, sorted).
PAIRS = (("Sphere", "Sphere"), ("Plane", "Sphere"), ("Cylinder", "Plane"), ("Cone", "Plane"), ("Plane", "Plane"))
#: The distance bound must stay below this share of the true ellipse's smaller semi-axis.
SMALL = 0.25
#: The singular claim where no point is singular.
NO_SINGULAR = "no singular point: the surfaces cross transversally, or do not meet"


def closed_certificate(a, b, curves):
    """The Certificate of the answer curves (CurveResults) of a pair of PAIRS proven in closed form, or None when
    this pair or answer is not one the algebra settles."""
    pair = sorted((a, b), key=lambda s: type(s).__name__)
    kinds = tuple(type(s).__name__ for s in pair)
    if kinds not in PAIRS or any(s.region for s in pair) or any(isinstance(s, Sphere) and s.trimmed for s in pair):
        return None
    if kinds == ("Plane", "Plane"):
        return segment_certificate(pair, curves)
    truth = np.empty((kc.ROWS, 2))
    if kinds == ("Sphere", "Sphere"):
        outcome = kc.spheres(pair[0].frame.origin, pair[0].radius, pair[1].frame.origin, pair[1].radius, truth)
    else:
        quadric, plane = (pair[1], pair[0]) if kinds == ("Plane", "Sphere") else pair
        p, n, o, axis = plane.frame.origin, column(plane, 2), quadric.frame.origin, column(quadric, 2)
        if isinstance(quadric, Cone):
            outcome = kc.cone_quadric(p, n, o, axis, float(quadric.data[ks.P1]), truth)
        else:
            g = 1.0 if isinstance(quadric, Cylinder) else 0.0
            outcome = kc.plane_quadric(p, n, o, axis, g, quadric.radius, truth)
    if outcome == kc.EMPTY and not curves:
        return answer([], [], "the surfaces have no common point (proven in closed form)", "no curve")
    if outcome != kc.CURVE or not inside_trims(truth, pair) or len(curves) != 1 or not curves[0].closed:
        return None
    c, P, Q = returned_curve(curves[0].sol)
    off = faithful(curves[0], 2.0 * math.pi)
    if c is None or off is None:
        return None
    bound = kc.distance_bound(truth, c, P, Q)
    if not bound < SMALL * math.sqrt(max(kc.semi_minor_squared(truth), 0.0)):
        return None
    radii = np.full(len(curves[0].points), up(bound + off))
    return answer([radii], [bound], "the surfaces meet in exactly one ellipse (or circle), crossing, inside the "
                  "trims (proven in closed form)", "the true curve")


def segment_certificate(planes, curves):
    """The Certificate of two planes' answer: one segment (the line of the planes inside both rectangles, a convex
    set: one piece or none), proven in closed form, or None."""
    bands = np.array([np.concatenate([plane.frame.origin, column(plane, k), [lo, hi]]) for plane in planes
                      for k, (lo, hi) in enumerate(plane.bounds) if np.isfinite(lo) or np.isfinite(hi)])
    ends = np.empty((6, 2))
    outcome = kc.plane_plane(planes[0].frame.origin, column(planes[0], 2), planes[1].frame.origin,
                             column(planes[1], 2), bands.reshape(-1, 8), ends)
    if outcome == kc.EMPTY and not curves:
        return answer([], [], "the surfaces have no common point (proven in closed form)", "no curve")
    if outcome != kc.CURVE or len(curves) != 1 or curves[0].closed or not is_segment(curves[0].sol):
        return None
    curve = curves[0]
    off = faithful(curve, None)
    if off is None:
        return None
    a, b = (np.asarray(p, dtype=float) for p in curve.sol(np.array([0.0, curve.length])))
    bound = kc.segment_bound(ends, a, b)
    if not bound < SMALL * float(np.linalg.norm(b - a)):
        return None
    return answer([np.full(len(curve.points), up(bound + off))], [bound], "the planes meet in exactly one segment, "
                  "ending on their trims (proven in closed form)", "the true segment")


def faithful(curve, turn):
    """How far (at most) the curve's stored points lie from its dense output at their arc lengths, when its dense
    output is the whole closed form the bound is about (turn: the parameter range of a whole turn, 2 pi, for a
    circle or an ellipse; None for a segment: its length) and its length the dense output's; else None."""
    sol = curve.sol
    length = float(sol.length)
    if not (length > 0.0 and abs(curve.length - length) <= 1e-12 * length):
        return None
    if isinstance(sol, CircleSolution):
        whole = abs(length - turn * sol.radius) <= 1e-12 * length
    elif isinstance(sol, ConicSolution):
        t_lo, t_hi = sol._t_range[:2]
        span = turn if turn is not None else length
        whole = abs((t_hi - t_lo) - span) <= 1e-12 * max(span, 1.0)
    else:                                           # a segment: its own length is its extent
        whole = turn is None
    if not whole or len(curve.points) != len(curve.s):
        return None
    points = np.asarray(curve.points, dtype=float)
    size = float(np.max(np.abs(points)))
    if points is sol.samples()[0] and curve.s is sol.knots:
        return 64.0 * EPS * size                # the closed form's own samples at its knots (SampledResult)
    dense = np.asarray(sol(np.asarray(curve.s, dtype=float)), dtype=float).reshape(-1, 3)
    off = float(np.max(np.linalg.norm(points - dense, axis=1)))
    return off * (1.0 + 1e-9) + 64.0 * EPS * size if off <= 1e-9 * max(size, 1.0) else None


def is_segment(sol):
    """True for a straight closed form (a line conic, a segment): its dense output affine in s."""
    return isinstance(sol, SegmentSolution) or (isinstance(sol, ConicSolution) and sol.conic.shape == LINE)


def column(surface, k):
    """The surface's frame column k (3,), contiguous."""
    return np.ascontiguousarray(surface.frame.rotation[:, k])


def inside_trims(truth, pair):
    """True when the true curve lies strictly inside every length trim of the pair (a plane's u and v, a
    cylinder's or cone's v: bands along its frame's columns 0, 1 and 2)."""
    for surface in pair:
        for k, (lo, hi) in enumerate(surface.bounds):
            if not (np.isfinite(lo) or np.isfinite(hi)):
                continue
            along = column(surface, k if isinstance(surface, Plane) else 2)
            if not kc.within_band(truth, surface.frame.origin, along, lo, hi):
                return False
    return True


def returned_curve(sol):
    """(c, P, Q) (3,) each of a closed curve's closed form X(t) = c + P cos t + Q sin t (a circle, a whole
    ellipse), or (None, None, None)."""
    if isinstance(sol, CircleSolution):
        return sol.centre, sol.radius * sol.e1, sol.radius * sol.e2
    if isinstance(sol, ConicSolution) and sol.conic.shape == ELLIPSE:
        conic = sol.conic
        return conic.centre, conic.P, conic.Q
    return None, None, None


def answer(radii, bounds, how, truth, singular=NO_SINGULAR, mode=None):
    """The Certificate of an answer proven in closed form (or exactly: mode): every claim proven, complete,
    one_component and distinct for the reason `how`, the singular points for the reason `singular` (truth: what the
    curves are proven near)."""
    none = np.empty((0, 3))
    texts = {"complete": how, "one_component": how, "distinct": how,
             "points": f"every stored point lies within the distance bound of {truth}",
             "arcs": f"the whole dense output lies within the distance bound of {truth}, and {truth} within it of "
                     "the dense output",
             "singular": singular}
    claims = [Claim(name, PROVEN, text, none, np.empty(0)) for name, text in texts.items()]
    return Certificate(claims, None, radii, [None] * len(radii), bounds, len(radii), mode=mode)
