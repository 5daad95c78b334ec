"""sk.intersect: every component of the intersection of two surfaces, each once."""
import dataclasses
import time

import numpy as np
from scipy.spatial import cKDTree

from .dense import CLOSEST_NEWTON_STEPS
from .exact import contact_point, exact_curve
from .result import Curve, TracingError
from .start import locate_on_curve, newton_fixed
from .certificate import certificates
from .closed import closed_form
from . import stages
from .status import CONTACT
from .topology import topology
from .traits import check_surface
from .trace import DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, make_settings, trace_from

#: A seed lying within this distance (relative to the scale) of a curve already traced belongs to it.
SAME_COMPONENT = 1e-6
#: Pairs that meet in conics are solved in closed form (spatialkin.tracing.closed); False forces the general
#: path (the tests compare the two).
CLOSED_FORMS = True


def intersect(a, b, tol=1e-10, *, method=DEFAULT_METHOD, rtol=DEFAULT_RTOL, atol=None, max_length=None,
              singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK, certify=False):
    """Every component of a ∩ b.

    Start points come from the topology stage (spatialkin.tracing.topology: an interval subdivision of one
    surface's parameter domain that provably finds a start on every component); each component is traced
    once by ``trace`` and the starts on it are skipped. The result does not depend on the argument order
    (curves come longest first), on translation or on scale.

    Parameters
    ----------
    a, b : Surface
        Trimmed or not; at least one of them bounded (a sphere, a torus, or a trimmed plane, cylinder or cone).
    tol : float
        Accuracy of every returned point, relative to the scene scale (see ``trace``).
    method, rtol, atol, max_length, singular_tol, pullback
        As in ``trace``.
    certify : bool
        Attach ``curve.certificate`` (spatialkin.tracing.certificate.Certificate) to every curve: what the
        search proved, and a proven radius round every stored point (needs the ``certify`` extra,
        python-flint).

    Returns
    -------
    list of Curve
        Closed loops, open curves (ending exactly on a trim edge, status 'boundary', or at a singular point),
        single contact points (status 'contact', length 0) and circles or segments along which the surfaces
        touch (status 'tangent', in closed form: spatialkin.tracing.exact); empty when the surfaces do not meet.

    Raises
    ------
    CoincidentSurfacesError
        The two patches overlap in a piece of surface (the same sphere twice, coaxial equal cylinders, coplanar
        planes whose rectangles overlap).
    ValueError
        Both surfaces unbounded, or bad arguments.
    TopologyError
        The search could not resolve the intersection within its budget (it never returns a guess instead).
    """
    check_surface("a", a)
    check_surface("b", b)
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    settings = make_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback, True, anchor)
    if CLOSED_FORMS and not certify:
        found = closed_form(a, b, settings)
        if found is not None:
            return [Curve(c) for c in found]
    if stages.ON:
        stages.switch("topology")
    topo = topology(a, b, settings.scale, settings.tolerance)
    if stages.ON:
        stages.switch("setup")
    settings = dataclasses.replace(settings, nodes=np.array(topo.nodes + topo.apexes).reshape(-1, 3))
    # the components as CurveResults (each made a Curve once, complete, at the end)
    curves = [contact_point((a, b), p, settings.tolerance) for p in topo.contacts]
    curves += [exact_curve((a, b), settings.tolerance, circle=c) for c in topo.tangent_circles]
    curves += [exact_curve((a, b), settings.tolerance, circle=c, event="axis_circle") for c in topo.circles]
    curves += [exact_curve((a, b), settings.tolerance, segment=seg) for seg in topo.tangent_segments]
    radius = SAME_COMPONENT * settings.scale
    # (point, y, on the curve): exact starts on the edges, then the seeds, located only when one is traced
    pending = [(point, y, True) for point, y in (edge_start(a, b, point, index, fixed, value, settings)
                                                 for point, index, fixed, value in topo.edge_starts) if y is not None]
    if topo.seeds:
        seeds = np.array(topo.seeds, dtype=float).reshape(-1, 3)
        on = np.maximum(a.distance(seeds), b.distance(seeds)) <= settings.tolerance
        pending += [(seed, None, bool(exact)) for seed, exact in zip(seeds, on)]
    if stages.ON:
        stages.switch("dedupe")
    pending = drop_traced(pending, curves, radius)
    while pending:
        point, y, _ = pending.pop(0)
        if y is None:
            if stages.ON:
                stages.switch("correction")
            try:
                point, y = locate_on_curve(a, b, point, settings.gap_tol)
            except TracingError:
                continue
            if stages.ON:
                stages.switch("dedupe")
            if any(near_curve(c, point, radius)[0] for c in curves):
                continue
        if stages.ON:
            stages.switch("trace_setup")
        try:
            curve = trace_from(a, b, point, y, settings, time.perf_counter())
        except TracingError:
            continue            # the seed sits on a singular point: the arms' seeds trace it
        curves.append(curve)
        if stages.ON:
            stages.switch("dedupe")
        pending = drop_traced(pending, [curve], radius)
    if stages.ON:
        stages.switch("dedupe")
    kept = []
    for i, c in enumerate(curves):          # of two copies of one piece, the first is kept
        if not covered(c, kept + curves[i + 1:], radius):
            kept.append(c)
    curves = kept
    if stages.ON:
        stages.switch("result")
    curves.sort(key=lambda c: (-c.length, tuple(np.round(c.points[0], 9))))
    proofs = certificates(a, b, curves, topo) if certify else [None] * len(curves)
    return [Curve(dataclasses.replace(c, topology=topo, certificate=proof)) for c, proof in zip(curves, proofs)]


def drop_traced(pending, curves, radius):
    """The pending starts (point, y, on the curve) less those on the curve (within the accuracy asked) and
    within radius of one of the curves, tested in one query per curve; the others are kept and tested once
    located."""
    for curve in curves:
        exact = [k for k, item in enumerate(pending) if item[2]]
        if not exact:
            break
        hit = near_curve(curve, np.array([pending[k][0] for k in exact]), radius)
        dropped = {k for k, h in zip(exact, hit) if h}
        pending = [item for k, item in enumerate(pending) if k not in dropped]
    return pending


def near_curve(curve, points, radius):
    """Mask (M,) of the points (M, 3) lying within radius of the curve (a CurveResult). A point farther than radius
    plus half the longest step from every stored point is farther than radius from the curve (each arc between
    two stored points lies within half its length of one of them); a point within radius of a foot point found
    by Newton in s from the nearest stored point is near; the closest point decides the rest."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    out = np.zeros(len(points), dtype=bool)
    ask = np.ones(len(points), dtype=bool)
    if curve.length > 0 and len(curve.points) > 1:
        reach = radius + 0.5 * float(np.max(np.diff(curve.s)))
        gap, nearest = cKDTree(curve.points).query(points, distance_upper_bound=reach)
        ask = gap <= reach
        if ask.any():
            out[ask] = curve.sol.foot_points(points[ask], curve.s[nearest[ask]], CLOSEST_NEWTON_STEPS)[1] <= radius
            ask &= ~out
    if ask.any():
        out[ask] = curve.sol.closest(points[ask])[1] <= radius
    return out


def covered(curve, others, radius):
    """True for an open curve lying wholly on another curve (a piece of a component traced again)."""
    if curve.closed or curve.status == CONTACT:
        return False
    return any(other.length >= curve.length and np.max(other.sol.closest(curve.points)[1]) <= radius
               for other in others)


def edge_start(a, b, point, p_index, fixed, value, settings):
    """(point, y) on the curve exactly on the edge parameter `fixed` = value of surface p_index (0 a, 1 b), or
    None."""
    y = np.concatenate([a.parameters(point), b.parameters(point)])
    index = 2 * p_index + fixed
    y[index] = value
    y = newton_fixed(a, b, y, index, settings.gap_tol)
    if y is None:
        return None
    return a.point(y[0], y[1]), y
