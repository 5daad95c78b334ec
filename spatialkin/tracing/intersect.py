"""sk.intersect: every component of the intersection of two surfaces, each once."""
import dataclasses
import time

import numpy as np
from scipy.spatial import cKDTree

from .result import Curve, ExactCurve, TracingError
from .start import locate_on_curve, newton_fixed
from .certificate import certify as attach_certificates
from .topology import topology
from .traits import check_surface
from .trace import DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, make_settings, trace_from

#: A seed lying within this distance (relative to the scale) of a curve already traced belongs to it.
SAME_COMPONENT = 1e-6
#: A node the tracer passed is the proven singular point within this distance (relative to the scale).
SNAP = 1e-2


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
        touch (status 'tangent', spatialkin.tracing.result.ExactCurve); empty when the surfaces do not meet.

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
    topo = topology(a, b, settings.scale, settings.tolerance)
    settings = dataclasses.replace(settings, nodes=np.array(topo.nodes + topo.apexes).reshape(-1, 3))
    curves = [contact_curve(a, b, p, settings) for p in topo.contacts]
    curves += [ExactCurve((a, b), circle=c, tolerance=settings.tolerance) for c in topo.tangent_circles]
    curves += [ExactCurve((a, b), circle=c, tolerance=settings.tolerance, status="closed",
                          message="a circle about the surfaces' common axis, in closed form") for c in topo.circles]
    curves += [ExactCurve((a, b), segment=seg, tolerance=settings.tolerance) for seg in topo.tangent_segments]
    radius = SAME_COMPONENT * settings.scale
    # (point, y, on the curve): exact starts on the edges, then the seeds, located only when one is traced
    pending = [(point, y, True) for point, y in (edge_start(a, b, point, index, fixed, value, settings)
                                                 for point, index, fixed, value in topo.edge_starts) if y is not None]
    if topo.seeds:
        seeds = np.array(topo.seeds, dtype=float).reshape(-1, 3)
        on = np.maximum(a.distance(seeds), b.distance(seeds)) <= settings.tolerance
        pending += [(seed, None, bool(exact)) for seed, exact in zip(seeds, on)]
    pending = drop_traced(pending, curves, radius)
    while pending:
        point, y, _ = pending.pop(0)
        if y is None:
            try:
                point, y = locate_on_curve(a, b, point, settings.gap_tol)
            except TracingError:
                continue
            if any(near_curve(c, point, radius)[0] for c in curves):
                continue
        try:
            curve = trace_from(a, b, point, y, settings, time.perf_counter())
        except TracingError:
            continue            # the seed sits on a singular point: the arms' seeds trace it
        snap_nodes(curve, settings.nodes, settings.scale)
        curves.append(curve)
        pending = drop_traced(pending, [curve], radius)
    kept = []
    for i, c in enumerate(curves):          # of two copies of one piece, the first is kept
        if not covered(c, kept + curves[i + 1:], radius):
            kept.append(c)
    curves = kept
    curves.sort(key=lambda c: (-c.length, tuple(np.round(c.points[0], 9))))
    for c in curves:
        c.topology = topo
    if certify:
        attach_certificates(a, b, curves, topo)
    return curves


def snap_nodes(curve, known, scale):
    """Replace each node the tracer located (to about its jump's accuracy) by the singular point the topology
    stage proved there (Newton on grad g, or an apex), when one lies within SNAP x scale."""
    if not len(curve.nodes) or known is None or not len(known):
        return
    for k, node in enumerate(curve.nodes):
        d = np.linalg.norm(known - node, axis=1)
        if d.min() <= SNAP * scale:
            curve.nodes[k] = known[np.argmin(d)]


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
    """Mask (M,) of the points (M, 3) lying within radius of the curve. A point farther than radius plus half
    the longest step from every stored point is farther than radius from the curve (each arc between two
    stored points lies within half its length of one of them); a point within radius of a foot point found
    from the nearest stored point is near; Curve.closest decides the rest."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    out = np.zeros(len(points), dtype=bool)
    ask = np.ones(len(points), dtype=bool)
    if curve.length > 0 and len(curve.points) > 1:
        reach = radius + 0.5 * float(np.max(np.diff(curve.s)))
        ask = cKDTree(curve.points).query(points, distance_upper_bound=reach)[0] <= reach
        if ask.any():
            out[ask] = curve.near_points(points[ask]) <= radius
            ask &= ~out
    if ask.any():
        out[ask] = curve.closest(points[ask])[1] <= radius
    return out


def covered(curve, others, radius):
    """True for an open curve lying wholly on another curve (a piece of a component traced again)."""
    if curve.closed or curve.status == "contact":
        return False
    return any(other.length >= curve.length and np.max(other.closest(curve.points)[1]) <= radius
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


def contact_curve(a, b, point, settings):
    """A component that is a single point where the surfaces touch."""
    y = np.concatenate([a.parameters(point), b.parameters(point)]).reshape(1, 4)
    curve = Curve((a, b), point.reshape(1, 3), np.zeros(1), y, False, 0.0, "contact",
                  f"the surfaces touch at {point.tolist()}", [], settings.gap_tol)
    curve.tolerance = settings.tolerance
    return curve
