"""Certificates proven exactly for two surfaces along one coordinate axis, in rational arithmetic on the floats:
cylinders whose axes are parallel, and a plane parallel to a cylinder's axis.

Where spatialkin.tracing.search.exact decides such a pair (exact_segments: frames that are signed permutations, both
surfaces along one coordinate axis e_k; the common points of their cross-sections, tangencies included, each a line
along e_k cut by the trims into one segment, kept where it lies strictly inside the plane's range across it), the
intersection is exactly those segments: every claim holds in exact arithmetic, and each returned segment (a segment
of tangency or a line of the closed forms, its dense output affine in s) is bounded against its true segment, ends
enclosed in intervals (spatialkin.kernels.certify.closed.segment_bound). An answer with another number of curves
than the exact one is said to be wrong (spatialkin.tracing.certify.coaxial.exact_certificate). An answer traced by
the tracer (its dense output is not affine), a segment ending on a trim in a single point, a half-open trim, and any
other placement get no certificate here (None).

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM 2009, ch. 5-6 (outward rounding).
"""
import numpy as np

from ...kernels.certify import closed as kc
from ..curve.status import BOUNDARY, TANGENT
from .closed import NO_SINGULAR, SMALL, faithful, is_segment
from ..search.exact import enclose, exact_segments, float_above
from .coaxial import exact_certificate

#: Mode of the certificates made here.
MODE = "exact (parallel)"


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
    return float_above(bound + off)


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
