"""Certificates proven in closed form: two untrimmed spheres, an untrimmed sphere and a plane, or a plane and a
cylinder (each trimmed by lengths, or not) meet in one circle or ellipse or in nothing, which interval arithmetic
decides without a search (spatialkin.kernels.certify.closed). The returned curve is then proven within a Hausdorff
distance of the true one along its whole dense output, both ways. Any other answer, or a pair the algebra leaves
undecided (a tangency, a curve reaching a trim edge), goes to the search's certificate
(spatialkin.tracing.certify.certificate).
"""
import numpy as np

from ...kernels.certify import closed as kc
from ..closed.conic import ELLIPSE, ConicSolution
from ..curve.exact import CircleSolution
from ...geometry.surfaces import Plane
from .certificate import PROVEN, Certificate, Claim

#: The pairs proven here (their class names, sorted).
PAIRS = (("Sphere", "Sphere"), ("Plane", "Sphere"), ("Cylinder", "Plane"))


def closed_certificate(a, b, curves):
    """The Certificate of the answer curves (CurveResults) of a pair of PAIRS proven in closed form, or None when
    this pair or answer is not one the algebra settles."""
    pair = sorted((a, b), key=lambda s: type(s).__name__)
    kinds = tuple(type(s).__name__ for s in pair)
    if kinds not in PAIRS or any(s.region for s in pair):
        return None
    truth = np.empty((10, 2))
    if kinds == ("Sphere", "Sphere"):
        if pair[0].trimmed or pair[1].trimmed:
            return None
        outcome = kc.spheres(pair[0].frame.origin, pair[0].radius, pair[1].frame.origin, pair[1].radius, truth)
    elif kinds == ("Plane", "Sphere"):
        plane, sphere = pair
        if sphere.trimmed:
            return None
        outcome = kc.plane_sphere(plane.frame.origin, column(plane, 2), sphere.frame.origin, sphere.radius, truth)
    else:
        cylinder, plane = pair
        outcome = kc.plane_cylinder(plane.frame.origin, column(plane, 2), cylinder.frame.origin, column(cylinder, 2),
                                    cylinder.radius, truth)
    if outcome == kc.EMPTY and not curves:
        return answer([], [], "the surfaces have no common point (the circle's radius squared is proven negative)",
                      "no curve")
    if outcome != kc.CURVE or not inside_trims(truth, pair) or len(curves) != 1 or not curves[0].closed:
        return None
    c, P, Q = returned_curve(curves[0].sol)
    if c is None:
        return None
    bound = kc.distance_bound(truth, c, P, Q)
    if not bound < 0.25 * truth[kc.R, 0]:
        return None
    radii = np.full(len(curves[0].points), bound)
    shape = "circle" if kinds != ("Cylinder", "Plane") else "ellipse"
    return answer([radii], [bound], f"the surfaces meet in exactly one {shape}, crossing, inside the trims (proven "
                  "in closed form)", f"the true {shape}")


def column(surface, k):
    """The surface's frame column k (3,), contiguous."""
    return np.ascontiguousarray(surface.frame.rotation[:, k])


def inside_trims(truth, pair):
    """True when the true curve lies strictly inside every length trim of the pair (a plane's u and v, a
    cylinder's v: bands along its frame's columns 0, 1 and 2)."""
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


def answer(radii, bounds, how, truth):
    """The Certificate of an answer proven in closed form: every claim proven, for the reason `how` (truth: what
    the curves are proven near)."""
    none = np.empty((0, 3))
    texts = {"complete": how, "one_component": how, "distinct": how,
             "points": f"every stored point lies within the distance bound of {truth}",
             "arcs": f"the whole dense output lies within the distance bound of {truth}, and {truth} within it of "
                     "the dense output",
             "singular": "no singular point: the surfaces cross transversally, or do not meet"}
    claims = [Claim(name, PROVEN, text, none, np.empty(0)) for name, text in texts.items()]
    return Certificate(claims, None, radii, [None] * len(radii), bounds, len(radii))
