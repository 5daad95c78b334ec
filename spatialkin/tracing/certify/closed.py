"""Certificates proven in closed form: two untrimmed spheres, or an untrimmed sphere and a plane (trimmed to a
rectangle or not), meet in one circle or in nothing, which interval arithmetic decides without a search
(spatialkin.kernels.certify.circle). The returned circle is then proven within a Hausdorff distance of the true
one along its whole dense output, both ways. Any other answer, or a pair the algebra leaves undecided (a tangency,
a circle reaching a trim edge), goes to the search's certificate (spatialkin.tracing.certify.certificate).
"""
import numpy as np

from ...kernels.certify import circle as kc
from ..closed.conic import ELLIPSE, ConicSolution
from ..curve.exact import CircleSolution
from .certificate import PROVEN, Certificate, Claim


def closed_certificate(a, b, curves):
    """The Certificate of the answer curves (CurveResults) of a sphere-sphere or sphere-plane pair proven in
    closed form, or None when this pair or answer is not one the algebra settles."""
    pair = sorted((a, b), key=lambda s: type(s).__name__)
    kinds = [type(s).__name__ for s in pair]
    if kinds not in (["Sphere", "Sphere"], ["Plane", "Sphere"]) or pair[1].trimmed:
        return None
    circle = np.empty((7, 2))
    if kinds == ["Sphere", "Sphere"]:
        if pair[0].trimmed:
            return None
        outcome = kc.spheres(pair[0].frame.origin, pair[0].radius, pair[1].frame.origin, pair[1].radius, circle)
        inside = True
    else:
        plane, sphere = pair
        if plane.region:
            return None
        frame = plane.frame
        outcome = kc.plane_sphere(frame.origin, np.ascontiguousarray(frame.rotation[:, 2]), sphere.frame.origin,
                                  sphere.radius, circle)
        (u0, u1), (v0, v1) = plane.bounds
        inside = outcome == kc.CIRCLE and kc.within_rectangle(
            circle, frame.origin, np.ascontiguousarray(frame.rotation[:, 0]),
            np.ascontiguousarray(frame.rotation[:, 1]), u0, u1, v0, v1)
    if outcome == kc.EMPTY and not curves:
        return answer([], [], "the surfaces have no common point (the circle's radius squared is proven negative)",
                      "no curve")
    if outcome != kc.CIRCLE or not inside or len(curves) != 1 or not curves[0].closed:
        return None
    c, P, Q = returned_circle(curves[0].sol)
    if c is None:
        return None
    bound = kc.distance_bound(circle, c, P, Q)
    if not bound < 0.25 * circle[6, 0]:
        return None
    radii = np.full(len(curves[0].points), bound)
    return answer([radii], [bound], "the surfaces meet in exactly one circle, crossing (its radius squared is proven "
                  "positive), inside the trims", "the true circle")


def returned_circle(sol):
    """(c, P, Q) (3,) each of a closed curve's closed form X(t) = c + P cos t + Q sin t, or (None, None, None)."""
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
