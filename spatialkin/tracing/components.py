"""sk.intersect: every component of the intersection of two surfaces, each once."""
import dataclasses
import math
import time

import numpy as np
from scipy.spatial import cKDTree

from ..kernels.curve import near as kn
from ..kernels.geometry import surfaces as ks
from .curve.curvature import normal_sines
from .curve.dense import CLOSEST_NEWTON_STEPS
from .curve.exact import contact_point, exact_curve
from .curve.result import Curve, TracingError, in_sk_order, point_gaps
from .march.ivp import KNOWN_NODE
from .march.segments import NEWTON_MAX_ITER
from .march.start import locate_on_curve, newton_fixed_surfaces
from .certify.certificate import CertificationError, CurveCertificate, certify as certify_answer
from .certify.closed import closed_certificate
from .certify.coaxial import coaxial_certificate
from .certify.parallel import parallel_certificate
from .curve.clip import clip_curves
from .march.graze import across_edges, rejoined
from .closed.forms import Placed, along_normals, closed_form, closed_settings
from .._lib import stages, warm
from .curve.status import BOUNDARY, CONTACT, FAILED, MAX_LENGTH, SINGULAR, TANGENT
from .search.rescue import LOST_RADIUS, crossing_starts
from .search.topology import TopologyError, points_at, topology
from ..geometry.asymptotic import bounded_pair
from ..geometry.traits import check_surface
from .march.trace import (DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, make_settings,
                          trace_from)

#: A seed lying within this distance (relative to the scale) of a curve already traced belongs to it.
SAME_COMPONENT = 1e-6
#: Pairs that meet in conics are solved in closed form (spatialkin.tracing.closed.forms); False forces the general
#: path (the tests compare the two).
CLOSED_FORMS = True


def intersect(a, b, tol=1e-10, *, method=DEFAULT_METHOD, rtol=DEFAULT_RTOL, atol=None, max_length=None,
              singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK, certify=False):
    """Every component of the intersection of two surfaces, each traced once by arc length.

    Parameters
    ----------
    a, b : Surface
        Trimmed or not. Where both are unbounded (planes, cylinders or cones not trimmed all round), their
        intersection is bounded when the directions in which they run to infinity lie apart (a cylinder's axis, a
        cone's cone of rulings, the directions in a plane): those at least 1e-3 rad apart are cut to a ball that
        holds every common point (spatialkin.geometry.asymptotic), and the curves keep the surfaces as given.
    tol : float
        Accuracy of every returned point and every dense evaluation, relative to the scene scale (see Notes).
    method, rtol, atol, max_length, singular_tol, pullback
        As in ``trace``.
    certify : bool or 'strict'
        Prove the answer (in outward-rounded interval arithmetic; a closed form's answer in closed form where the
        pair is two spheres, or a plane and a sphere, cylinder or cone, meeting in one whole ellipse or not at all,
        or two planes; exactly, in rational arithmetic, where the surfaces turn about one coordinate axis or run
        along one, placed by signed permutations, tangencies included; else against the topology search): the
        returned list then has a ``certificate`` (spatialkin.tracing.certify.certificate.Certificate) stating each
        claim (no component missed, each curve one component, the curves distinct, the stored points, the arcs
        between them, the singular points) as proven or not, and where; every curve has its view of it
        (``curve.certificate``). 'strict' raises CertificationError unless every claim is proven. Where the search
        refuses a pair that meets in a closed form, that answer comes back, said not proven. Each curve's tube has a
        work budget (spatialkin.tracing.certify.tubes.MOST_WORK): branches too close beside each other for it are
        said not proven.

    Returns
    -------
    list of Curve
        Closed loops, open curves (ending exactly on a trim edge, status 'boundary', or at a singular point),
        single contact points (status 'contact', length 0) and circles or segments along which the surfaces
        touch (status 'tangent', in closed form: spatialkin.tracing.curve.exact); empty when the surfaces do not meet.
        Curves come longest first; the result does not depend on the argument order, on translation or on
        scale. Each curve runs along N_a x N_b (a's normal S_u x S_v crossed with b's), as the Cauchy problem
        does, whether traced or in closed form (past a node, along the branch it follows); a curve of tangency,
        where N_a x N_b vanishes, runs counterclockwise about its axis.

    Raises
    ------
    CoincidentSurfacesError
        The two patches overlap in a piece of surface (the same sphere twice, coaxial equal cylinders, coplanar
        planes whose rectangles overlap). A subclass of ValueError.
    ValueError
        Both surfaces unbounded and running to infinity in directions less than 1e-3 rad apart (they may meet
        arbitrarily far out: a plane along a cylinder's axis, two parallel cylinders), or bad arguments (named; the
        options' ranges: spatialkin.tracing.march.trace.check_options).
    TypeError
        Naming `a` or `b` when it is not a spatialkin surface, an option when it is not a real number.
    TopologyError
        The search could not resolve the intersection within its budget (it never returns a guess instead).
    CertificationError
        certify='strict' and a claim could not be proven (its ``certificate`` says which, and where).

    See Also
    --------
    trace : one component, from a start near it.
    intersect_many : many pairs in one call, optionally on worker processes.

    Notes
    -----
    **The tolerance.** ``tol`` is relative to the scene scale, the smaller characteristic length of the two
    surfaces (a sphere's or cylinder's radius, a torus's R + r, a cone's slant length when trimmed at both ends;
    without one, the smaller half-diagonal of the trimmed planes' rectangles; of two unbounded surfaces, read as
    they are cut to the ball). Every returned point, and every
    dense evaluation ``curve(s)``, lies within tol x scale of both surfaces: Newton corrects each point onto both
    of them to a hundredth of that, and the distances are measured with the surfaces' exact distance functions
    (``curve.max_distance``, ``curve.distances()``). ``curve.tolerance`` is that absolute length, never below
    64 ulps of the coordinates' magnitude.

    **How components are found.** Pairs that meet in conics (plane-plane, plane-sphere, plane-cylinder, plane-cone,
    sphere-sphere) are solved in closed form (spatialkin.tracing.closed.forms; its degenerate cases take the general
    path, and certify=True runs the search too). Otherwise the topology stage (spatialkin.tracing.search.topology)
    recognises special placements first: surfaces of revolution about one axis meet in parallels, a cylinder and a
    surface invariant along its axis in lines along it, and circles or segments of tangency come in closed form. In
    general it reads the intersection as the level g = F_Q(P(u, v)) = 0 on one surface's parameter domain and seeds
    every component: each one meets an edge of the domain, crosses a seam, passes a collapsed point of the chart (a
    pole, an apex), or is a closed loop holding a critical point where its tangent is normal to a fixed direction.
    Those roots are found by interval subdivision with outward rounding [2]_ [3]_, a box dropped only when an
    enclosure proves it root-free and a root kept once the interval Newton or Krawczyk operator proves it isolated,
    so the search seeds every component, however small [4]_ [5]_; boxes that shrink to round-off without either
    proof are singular points (contacts, nodes), classified by the Hessian. Each component is then traced once by
    ``trace`` (Dragilev's method [1]_), and the starts lying on it are skipped.

    References
    ----------
    .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
       machines of the light industry" (in Ukrainian): the intersection line by arc length, a Cauchy problem.
    .. [2] R. B. Kearfott, M. Novoa, "Algorithm 681: INTBIS, a portable interval Newton/bisection package",
       ACM Trans. Math. Softw. 16(2), 1990, 152-157.
    .. [3] R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM, 2009.
    .. [4] N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing,
       Springer, 2002.
    .. [5] H. Hong, "An efficient method for analyzing the topology of plane real algebraic curves", Math.
       Comput. Simul. 42 (1996).

    Examples
    --------
    A plane 0.6 above the centre of a unit sphere cuts it in a circle of radius 0.8 (in closed form):

    >>> import numpy as np
    >>> import spatialkin as sk
    >>> curves = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
    >>> len(curves), curves[0].closed
    (1, True)
    >>> round(curves[0].length, 6)        # 2 pi 0.8
    5.026548

    A torus and a sphere (the looper drive's pair) meet here in two loops, found by the topology stage:

    >>> torus, sphere = sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    >>> curves = sk.intersect(torus, sphere)
    >>> len(curves), [c.closed for c in curves]
    (2, [True, True])
    >>> all(c.max_distance <= c.tolerance for c in curves)
    True

    With certify=True the answer carries what was proven, claim by claim:

    >>> curves = sk.intersect(torus, sphere, certify=True)
    >>> curves.certificate.proven, list(curves.certificate.claims)
    (True, ['complete', 'one_component', 'distinct', 'points', 'arcs', 'singular'])
    >>> cert = curves[0].certificate
    >>> cert.components, cert.all_points_proven, bool(cert.distance_bound < 1e-12)
    (2, True, True)

    Disjoint surfaces give no curves; coincident ones raise:

    >>> sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((3.0, 0.0, 0.0))))
    []
    >>> sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0))
    Traceback (most recent call last):
    ...
    spatialkin.geometry.placement.CoincidentSurfacesError: a and b are the same sphere and their patches overlap: ...
    """
    check_surface("a", a)
    check_surface("b", b)
    if not (certify is False or certify is True or isinstance(certify, str) and certify == "strict"):
        raise ValueError(f"certify must be False, True or 'strict', got {certify!r}")
    warm.refresh()
    given = None
    if not (a.traits.compact or b.traits.compact):
        cut = bounded_pair(a, b)          # (two unbounded surfaces: cut to a ball holding all they share)
        if cut[0] is not a:
            given, (a, b) = (a, b), cut
    scene = None
    found = None
    if CLOSED_FORMS:                      # (its settings are checked as make_settings checks them)
        closed = closed_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback)
        found = closed_form(a, b, closed)
        if found is not None and not certify:
            curves = in_sk_order(clip_curves(a, b, found, closed.scale))
            return [Curve(c) for c in (curves if given is None else on_given(curves, given))]
        scene = closed.checked
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    settings = make_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback, True, anchor, scene)
    if not certify:
        curves, topo, _ = searched(a, b, settings, max_length is None)
        return [Curve(c, topology=topo) for c in (curves if given is None else on_given(curves, given))]
    # the general path's answer, or the closed forms' (the plain call's): proven in closed form where the algebra
    # settles it, else against the topology search
    wholes = None
    if found is None:
        curves, topo, wholes = searched(a, b, settings, max_length is None)
    else:
        curves, topo = in_sk_order(clip_curves(a, b, found, settings.scale)), None
        wholes = found if a.region or b.region else None
    # exactly (where the placement is exact: the tightest bounds), else in closed form
    proof = coaxial_certificate(a, b, curves) or parallel_certificate(a, b, curves) or closed_certificate(a, b, curves)
    if proof is not None:
        return certified(a, b, curves, None, settings.scale, settings.tolerance, certify, proof=proof, given=given)
    if topo is None:
        try:
            topo = topology(a, b, settings.scale, settings.tolerance)
        except TopologyError as err:
            return certified(a, b, curves, None, settings.scale, settings.tolerance, certify,
                             f"the search stopped ({err}); the answer is the closed form's", given=given)
    return certified(a, b, curves, topo, settings.scale, settings.tolerance, certify, wholes=wholes, given=given)


def searched(a, b, settings, closing=True):
    """(CurveResults of every component, in sk's order; the Topology; the components before the faces' regions
    cut them, or None where neither surface has a region): the general path of intersect. closing: max_length is
    the default one (MAX_LENGTH_TURNS turns round the surfaces' extent, longer than any curve they share), so a
    component that reaches it has not been followed (TopologyError)."""
    if stages.ON:
        stages.switch("topology")
    topo = topology(a, b, settings.scale, settings.tolerance)
    if stages.ON:
        stages.switch("setup")
    settings.nodes = topo.crossings()
    # the components as CurveResults (each made a Curve once, complete, at the end)
    curves = [contact_point((a, b), p, settings.tolerance) for p in topo.contacts]
    curves += [exact_curve((a, b), settings.tolerance, circle=c) for c in topo.tangent_circles]
    placed = (a.memo("placed", Placed), b.memo("placed", Placed)) if topo.circles else ()
    curves += [exact_curve((a, b), settings.tolerance, circle=along_normals(placed, c), event="axis_circle")
               for c in topo.circles]
    curves += [exact_curve((a, b), settings.tolerance, segment=seg) for seg in topo.tangent_segments]
    radius = SAME_COMPONENT * settings.scale
    # (point, y, on the curve): exact starts on the edges, then the seeds, located only when one is traced
    pending = [(point, y, True) for point, y in (edge_start(a, b, point, index, fixed, value, settings)
                                                 for point, index, fixed, value in topo.edge_starts) if y is not None]
    if topo.seeds:
        seeds = np.array(topo.seeds, dtype=float).reshape(-1, 3)
        gaps = np.empty(len(seeds))
        ks.farther_distances(a.data, b.data, seeds, math.inf, 0.0, gaps)
        on = gaps <= settings.tolerance
        pending += [(seed, None, bool(exact)) for seed, exact in zip(seeds, on)]
    if stages.ON:
        stages.switch("dedupe")
    reasons = []
    failed = trace_pending(a, b, drop_traced(pending, curves, radius), curves, settings, radius, reasons)
    lost = lost_starts(failed, curves, LOST_RADIUS * settings.scale)
    if lost:                # every start of a component was lost: start it from the lines through their middles
        rescued = crossing_starts(a, b, settings.scale, settings.tolerance, lost)
        trace_pending(a, b, drop_traced([(x, None, False) for x in rescued], curves, radius), curves, settings, radius,
                      reasons)
        lost = lost_starts(lost, curves, LOST_RADIUS * settings.scale)
        if lost:
            why = (f"tracing failed: {reasons[0]}" if reasons else
                   "the surfaces nearly touch there")
            raise TopologyError(f"{len(lost)} start(s) of the topology stage could be neither located on the curve nor "
                                f"traced, and no component found passes near them (first {lost[0].tolist()}): {why}; "
                                "the result would miss a component", where="starts")
    if stages.ON:
        stages.switch("dedupe")
    kept = []
    for i, c in enumerate(curves):          # of two copies of one piece, the first is kept (of a loop, the shorter)
        if c.closed:
            if not traced_twice(c, kept, radius, settings):
                kept.append(c)
        elif not covered(c, kept + curves[i + 1:], radius, settings):
            kept.append(c)
    kept = split_stopped_laps(a, b, split_laps(a, b, kept, settings, radius), settings, radius)
    unclosed = next((c for c in kept if c.status == MAX_LENGTH), None) if closing else None
    if unclosed is not None:
        raise TopologyError(f"a component traced from {np.round(unclosed.points[0], 12).tolist()} ran to "
                            f"max_length = {settings.max_length:.6g} without closing, longer than any curve the "
                            "surfaces share: the march crossed between branches where the surfaces nearly touch",
                            where="march")
    on = lambda curve, whole: bool(within(whole, curve.points, radius).all())          # noqa: E731
    wholes = rejoined(a, b, kept, settings, on)
    curves = clip_curves(a, b, wholes, settings.scale)
    if stages.ON:
        stages.switch("result")
    return in_sk_order(curves), topo, (wholes if a.region or b.region else None)


def on_given(results, given):
    """The results (CurveResults), their surfaces those the user gave (given: (a, b) or None) where intersect cut
    them to a ball (spatialkin.geometry.asymptotic): the same surfaces, untrimmed where the cut copies are not."""
    if given is not None:
        for result in results:
            result.sol.surfaces = given
    return results


class Curves(list):
    """The list of curves sk.intersect(..., certify=True) returns, with the answer's ``certificate``
    (spatialkin.tracing.certify.certificate.Certificate; empty answers have one too)."""

    certificate = None


def certified(a, b, results, topo, scale, tolerance, mode, failure=None, proof=None, wholes=None, given=None):
    """The Curves of the results (CurveResults), each with its view of the answer's certificate (failure: why no
    search stands behind them; proof: the certificate when made already, in closed form; wholes: the components
    before the faces' regions cut them; given: the surfaces as the user gave them, where a and b were cut to a ball);
    with mode 'strict', CertificationError when a claim is not proven."""
    answer = proof if proof is not None else certify_answer(a, b, results, topo, scale, tolerance, failure, wholes)
    if mode == "strict" and not answer.proven:
        raise CertificationError(answer)
    out = Curves(Curve(c, topology=topo, certificate=CurveCertificate(answer, i))
                 for i, c in enumerate(on_given(results, given)))
    out.certificate = answer
    return out


def trace_pending(a, b, pending, curves, settings, radius, reasons):
    """Trace the components of the pending starts ((point, y, on the curve) each; y None: to be located first),
    appending each to curves (a list, changed in place) and dropping the starts on it; returns the starts (3,) that
    could be neither located nor traced (the messages of the tracing failures appended to reasons). Once a curve is
    traced, the starts still to be located are located together and tested against the curves in one query per
    curve (on_traced), and tested again each time more curves come."""
    failed = []
    largest = {}                # (id: (curve, the largest of its points' gaps); the curve held, its id kept)
    checked = [0]               # (the curves the located starts among pending have been tested against)

    def other_gap(curve):
        if id(curve) not in largest:
            largest[id(curve)] = curve, curve.largest_gap if len(curve.points) > 1 else 0.0
        return largest[id(curve)][1]

    def on_traced(points, against):
        """Mask (M,) of the points (M, 3) on the curve lying on a curve of `against` traced already: within radius,
        or within their place's error and the curve's largest (where the surfaces nearly touch: same_loop)."""
        points = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)
        out = np.zeros(len(points), dtype=bool)
        gap = point_gaps(a, b, points, settings.tolerance) if len(points) else None
        for curve in against:
            ask = ~out
            if not ask.any():
                break
            out[ask] = near_curve(curve, points[ask], radius)
            ask = ~out
            if other_gap(curve) > 0 and ask.any():
                # (the widest reach, sines at settings.singular_tol, picks the points whose sines are needed)
                widest = reach(radius, gap[ask], 0.0, other_gap(curve), settings)
                maybe = near_curve(curve, points[ask], float(widest.max()))
                if maybe.any():
                    idx = np.flatnonzero(ask)[maybe]
                    far = reach(radius, gap[idx], sines(a, b, points[idx]), other_gap(curve), settings)
                    out[idx] = curve.sol.closest(points[idx])[1] <= far
        return out

    def traced(point):
        """True where the point lies on a curve traced already (on_traced)."""
        return bool(on_traced(point, curves)[0])

    def settle(pending):
        """The pending starts, each still to be located located (or set aside, failed), those lying on a curve
        traced already dropped; the located ones tested against the curves that came since they were."""
        if stages.ON:
            stages.switch("correction")
        kept, fresh, old = [], [], []
        for item in pending:
            if item[1] is None:
                try:
                    point, y = locate_on_curve(a, b, item[0], settings.gap_tol)
                except TracingError:
                    failed.append(np.asarray(item[0], dtype=float))
                    continue
                fresh.append(len(kept))
                item = (point, y, item[2], True)        # (located here: tested against every curve to come)
            elif len(item) > 3:
                old.append(len(kept))
            kept.append(item)
        if stages.ON:
            stages.switch("dedupe")
        hit = np.zeros(len(kept), dtype=bool)
        if fresh:
            hit[fresh] = on_traced([kept[k][0] for k in fresh], curves)
        if old and checked[0] < len(curves):
            hit[old] = on_traced([kept[k][0] for k in old], curves[checked[0]:])
        checked[0] = len(curves)
        return [item for k, item in enumerate(kept) if not hit[k]]

    while pending:
        if curves and (pending[0][1] is None or checked[0] < len(curves)):
            pending = settle(pending)
            if not pending:
                break
        point, y = pending.pop(0)[:2]
        if y is None:
            if stages.ON:
                stages.switch("correction")
            try:
                point, y = locate_on_curve(a, b, point, settings.gap_tol)
            except TracingError:
                failed.append(np.asarray(point, dtype=float))
                continue
            if stages.ON:
                stages.switch("dedupe")
        if stages.ON:
            stages.switch("trace_setup")
        try:
            found = trace_from(a, b, point, y, settings, time.perf_counter(), known=traced)
            if found is None:
                continue        # (the start lay off the curve, beside a component traced already)
            found = [found]
        except TracingError as err:
            wide = across_edges(a, b, point, y, settings) if err.status == BOUNDARY else None
            if wide is None:
                failed.append(np.asarray(point, dtype=float))
                if err.status == FAILED:
                    reasons.append(str(err))
                continue        # the seed sits on a singular point (the arms' seeds trace it), or tracing failed
            found = wide[1]     # it leaves the faces both ways at once: the pieces inside them (a touch point)
        found = [c for c in found if not (traced_twice(c, curves, radius, settings) if c.closed else
                                          covered(c, curves, radius, settings))]
        curves += found
        if stages.ON:
            stages.switch("dedupe")
        pending = drop_traced(pending, found, radius)
    return failed


def split_laps(a, b, curves, settings, radius):
    """The curves (CurveResults), each closed one that runs round a shorter closed one of them and on round another
    loop replaced by that other loop. Such a lap comes from a march that took a node the search reported where the
    surfaces nearly touch for a crossing, and jumped there onto the other loop, so that one loop would come back
    twice. Beside a reported node (within KNOWN_NODE) the loop turns where the lap went straight on: there the two
    need not lie along each other. The other loop is traced from the lap's stored point farthest from the loop, with
    the reported nodes beside the loop set aside (there the march turns with the branch), and taken only when it
    closes, lies along the lap and, with the loop, covers the whole lap."""
    out = list(curves)
    if settings.nodes is None or not len(settings.nodes):
        return out
    for i, lap in enumerate(out):
        if not lap.closed:
            continue
        for loop in out:
            if loop is lap or not loop.closed or loop.length >= lap.length:
                continue
            if not along_union(loop, [lap], radius, settings, off_nodes(loop, settings)):
                continue
            away = beyond(lap, loop, radius, settings)
            if away.max() <= 0:
                continue            # (each lies along the other: traced_twice's copies)
            other = other_loop(a, b, lap.points[int(np.argmax(away))], loop, settings)
            if other is not None and along_union(other, [lap], radius, settings, off_nodes(other, settings)) and \
                    along_union(lap, [loop, other], radius, settings):
                out[i] = other
            break
    return out


def split_stopped_laps(a, b, curves, settings, radius):
    """The curves (CurveResults), each open one stopped at reported nodes (status singular) that runs round one or
    two loops replaced by them. Such a curve comes from a march that stopped at a node the search reported where the
    surfaces nearly touch, or jumped across it onto the other loop and stopped when it came back to it. The first
    loop is traced from the curve's stored point farthest from the nodes, the second (where the curve runs on
    beyond the first) from its point farthest from the first loop, each with the reported nodes beside the curve
    set aside (other_loop); they are taken only when each closes and lies along the curve and the curve lies along
    them, each unless another curve is that loop already."""
    out = list(curves)
    if settings.nodes is None or not len(settings.nodes):
        return out
    for lap in curves:
        if lap.closed or lap.status != SINGULAR or not (lap.length > 0 and len(lap.points) > 2):
            continue
        clearance = node_distances(lap, settings)
        off = clearance > KNOWN_NODE * settings.scale
        if not off.any():
            continue
        first = other_loop(a, b, lap.points[int(np.argmax(clearance))], lap, settings)
        if first is None or not along_union(first, [lap], radius, settings, off_nodes(first, settings)):
            continue
        away = beyond(lap, first, radius, settings)
        away[~off] = -np.inf
        loops = [first]
        if away.max() > 0:              # (else it lies along the first loop: a loop stopped at the node)
            second = other_loop(a, b, lap.points[int(np.argmax(away))], lap, settings)
            if second is None or not (along_union(second, [lap], radius, settings, off_nodes(second, settings)) and
                                      along_union(lap, [first, second], radius, settings)):
                continue
            loops.append(second)
        others = [c for c in out if c is not lap]
        at = out.index(lap)
        out[at:at + 1] = [loop for loop in loops if not traced_twice(loop, others, radius, settings)]
    return out


def node_distances(curve, settings):
    """(M,) the distance of each stored point of the curve to the nearest node the search reported."""
    nodes = np.asarray(settings.nodes, dtype=float).reshape(-1, 3)
    return cKDTree(nodes).query(np.ascontiguousarray(curve.points))[0]


def off_nodes(curve, settings):
    """Mask of the curve's stored points farther than KNOWN_NODE from every node the search reported."""
    return node_distances(curve, settings) > KNOWN_NODE * settings.scale


def beyond(curve, other, radius, settings):
    """(M,) how far each stored point of the curve lies beyond its reach (same_loop's, with the other curve's
    largest gap) of the other curve: <= 0 where it lies along it (both CurveResults)."""
    points = np.ascontiguousarray(curve.points)
    return other.sol.closest(points)[1] - reach(radius, curve.gaps, sines(*curve.sol.surfaces, points),
                                                other.largest_gap, settings)


def other_loop(a, b, point, loop, settings):
    """The closed curve traced from the point (located on the curve first), with the reported nodes (settings.nodes,
    some) within KNOWN_NODE of the loop (a CurveResult) set aside; None where it cannot be located, traced or does
    not close."""
    nodes = np.asarray(settings.nodes, dtype=float).reshape(-1, 3)
    nodes = nodes[~near_curve(loop, nodes, KNOWN_NODE * settings.scale)]
    try:
        point, y = locate_on_curve(a, b, point, settings.gap_tol)
        other = trace_from(a, b, point, y, dataclasses.replace(settings, nodes=nodes), time.perf_counter())
    except TracingError:
        return None
    return other if other is not None and other.closed else None


def traced_twice(loop, curves, radius, settings):
    """True when the closed curve loop (a CurveResult) is a component in curves (a list, changed in place) traced
    again (same_loop); of the two, the shorter is kept in curves (a march whose start lies a gap over the sine off
    the curve may close only after two laps)."""
    for k, other in enumerate(curves):
        if same_loop(loop, other, radius, settings):
            if loop.length < other.length:
                curves[k] = loop
            return True
    return False


def same_loop(loop, other, radius, settings):
    """True when the closed curves loop and other (CurveResults) each lie along the other: one component traced
    twice, from two starts apart on it where the surfaces nearly touch (each march closes on its own start). Each
    stored point is placed only to within its gap to the surfaces (plus GAP_ROUNDOFF_ULPS of its coordinates) over the
    sine of the normals' angle there (at least settings.singular_tol, below which no march goes on), twice that where
    it lies the gap from both surfaces (the far corner of the rhombus the two bands of that width cut): a point lies
    along a curve within radius plus twice its own and the curve's largest such error (a gap counted at most
    settings.tolerance: a point farther is no point of the curve)."""
    if not other.closed:
        return False
    return (lies_along(loop, other, loop.gaps, other.largest_gap, radius, settings)
            and lies_along(other, loop, other.gaps, loop.largest_gap, radius, settings))


def reach(radius, gap, sine, other_gap, settings):
    """How far from a curve points with these gaps and sines (gaps, sines) may lie and still lie on it, whose largest
    gap is other_gap (same_loop)."""
    return radius + 2 * (gap + other_gap) / np.maximum(sine, settings.singular_tol)


def sines(a, b, points):
    """(M,) sine of the normals' angle of the surfaces a and b at the points (M, 3) (0 where they meet no normal)."""
    return np.nan_to_num(normal_sines(a, b, points), nan=0.0)


def lies_along(curve, other, gap, other_gap, radius, settings):
    """True when every stored point of curve lies within its reach (same_loop's: gap (M,) its gaps, other_gap the
    largest of the other's) of the curve other (CurveResults). The widest reach (sines at settings.singular_tol)
    is tried first, by the stored points alone, before any sine is computed."""
    points = np.ascontiguousarray(curve.points)
    if not could_cover(other, points, float(reach(radius, gap, 0.0, other_gap, settings).max())):
        return False
    far = reach(radius, gap, sines(*curve.sol.surfaces, points), other_gap, settings)
    return could_cover(other, points, float(far.max())) and bool((other.sol.closest(points)[1] <= far).all())


def lost_starts(points, curves, radius):
    """The points (a list of (3,)) farther than radius from every curve (CurveResults)."""
    if not points:
        return []
    points = np.array(points, dtype=float).reshape(-1, 3)
    near = np.zeros(len(points), dtype=bool)
    for curve in curves:
        near |= near_curve(curve, points, radius)
    return list(points[~near])


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
    """Mask (M,) of the points (M, 3) lying within radius of the curve (a CurveResult), on a sheet of each cone of
    the pair that the curve visits (other_sheet: beside a cone's apex two components on its two nappes pass
    within any distance of each other). A point farther than radius plus half the longest step from every stored
    point is farther than radius from the curve (each arc between two stored points lies within half its length
    of one of them); a point within radius of a foot point found by Newton in s from the nearest stored point is
    near; the closest point decides the rest. A traced curve is tested in compiled code (spatialkin.kernels.curve.near:
    there a point within radius of one of Newton's iterates, each a point of the curve, is near too), except where
    Newton meets a span the compiled tables do not hold (a jump across a node or an apex): there, and on the other
    curves, the dense output's methods decide."""
    points = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)
    near = within_radius(curve, points, radius)
    if near.any():
        near &= ~other_sheet(curve, points)
    return near


def other_sheet(curve, points):
    """Mask (M,) of the points (M, 3) on a nappe of a cone of the curve's pair (CurveResult) that the curve never
    visits: farther than the curve's tolerance beyond the plane through the apex normal to the axis, on the side
    none of its stored points is on (a curve through the apex has points on both and passes every point)."""
    out = np.zeros(len(points), dtype=bool)
    guard = curve.tolerance
    for surface in getattr(curve.sol, "surfaces", ()):
        if surface.traits.name != "cone":
            continue
        heights = surface.frame.local_of(curve.points)[..., 2]
        side = 1.0 if np.all(heights > guard) else -1.0 if np.all(heights < -guard) else 0.0
        if side:
            out |= side * surface.frame.local_of(points)[..., 2] < -guard
    return out


def within_radius(curve, points, radius):
    """near_curve without the sheets' test (points (M, 3) contiguous)."""
    if not (curve.length > 0 and len(curve.points) > 1 and len(points)):
        return curve.sol.closest(points)[1] <= radius if len(points) else np.zeros(0, dtype=bool)
    table = curve.sol.table
    if table is None:
        verdict = np.full(len(points), kn.PYTHON)
    else:
        verdict = np.empty(len(points), dtype=np.int64)
        if not kn.near_mask(points, curve.points, curve.s, float(radius), table, curve.sol.closed,
                            curve.sol.length, float(curve.sol.gap_tol), NEWTON_MAX_ITER, CLOSEST_NEWTON_STEPS,
                            verdict):
            return verdict == kn.NEAR
    python = verdict == kn.PYTHON
    if python.any():
        verdict[python] = python_verdicts(curve, points[python], radius)
    out = verdict == kn.NEAR
    ask = verdict == kn.UNDECIDED
    if ask.any():
        out[ask] = within(curve, points[ask], radius)
    return out


def within(curve, points, radius):
    """Mask (M,) of the points (M, 3) whose closest point on the curve (a CurveResult; its dense output's closest,
    in compiled code for a traced curve) lies within radius."""
    return curve.sol.closest(points)[1] <= radius


def python_verdicts(curve, points, radius):
    """near_mask's verdicts (kernels.near: FAR, NEAR or UNDECIDED) of the points (M, 3) against the curve (a
    CurveResult of positive length) in Python: the nearest stored point by a cKDTree, the foot point by the dense
    output's foot_points."""
    reach = radius + 0.5 * float(np.max(np.diff(curve.s)))
    gap, nearest = cKDTree(curve.points).query(points, distance_upper_bound=reach)
    verdict = np.full(len(points), kn.FAR)
    ask = gap <= reach
    if ask.any():
        near = curve.sol.foot_points(points[ask], curve.s[nearest[ask]], CLOSEST_NEWTON_STEPS)[1] <= radius
        verdict[ask] = np.where(near, kn.NEAR, kn.UNDECIDED)
    return verdict


def covered(curve, others, radius, settings):
    """True for an open curve lying wholly on another curve (a piece of a component traced again: each point within
    radius), or on others together, each point within its place's error (where the surfaces nearly touch: same_loop)
    of one of them (a march that crossed between two loops a round-off's width apart), or a contact point on a
    circle or segment of tangency (where the surfaces touch all along). A curve one of whose points lies beyond the
    reach of every stored point of the other (kernels.near.within_reach) is not on it; the closest points decide the
    rest. A curve followed to max_length is covered only within radius."""
    if curve.closed:
        return False
    points = np.ascontiguousarray(curve.points)
    if curve.status == CONTACT:
        return any(other.status == TANGENT and within(other, points, radius).all() for other in others)
    if any(other.length >= curve.length and could_cover(other, points, radius) and within(other, points, radius).all()
           for other in others):
        return True
    if curve.status == MAX_LENGTH:
        return False            # (a march that crossed between branches and never closed: searched refuses the pair)
    return along_union(curve, others, radius, settings)


def along_union(curve, others, radius, settings, mask=None):
    """True when every stored point of the curve (those of the mask, if given) lies within its reach (same_loop's,
    with each other curve's largest gap) of one of the others (CurveResults)."""
    points = np.ascontiguousarray(curve.points if mask is None else curve.points[mask])
    if not len(points):
        return True
    others = [other for other in others
              if other.status != CONTACT and other.length > 0 and len(other.points) > 1]
    if not others:
        return False
    gap = curve.gaps if mask is None else curve.gaps[mask]
    largest = [other.largest_gap for other in others]
    # the widest reach (sines at settings.singular_tol) first: a point beyond it of every other curve's stored
    # points, by more than half the longest step, settles the answer before any sine is computed
    if beyond_stored(points, others, [reach(radius, gap, 0.0, g, settings) for g in largest]).any():
        return False
    sine = sines(*curve.sol.surfaces, points)
    lo, hi = points.min(axis=0), points.max(axis=0)
    near = np.zeros(len(points), dtype=bool)
    for other, other_gap in zip(others, largest):
        far = reach(radius, gap, sine, other_gap, settings)
        if np.any(other.points.min(axis=0) > hi + far.max()) or np.any(other.points.max(axis=0) < lo - far.max()):
            continue
        ask = ~near
        near[ask] = other.sol.closest(points[ask])[1] <= far[ask]
        if near.all():
            return True
    return False


def beyond_stored(points, curves, reaches):
    """Mask (M,) of the points (M, 3) farther from every stored point of each curve (CurveResults of positive
    length) than that curve's reach (M,) plus half its longest step: each such point lies farther than its reach
    from every curve (each arc between two stored points lies within half its length of one of them)."""
    out = np.ones(len(points), dtype=bool)
    for curve, far in zip(curves, reaches):
        out &= cKDTree(curve.points).query(points)[0] > far + 0.5 * float(np.max(np.diff(curve.s)))
        if not out.any():
            break
    return out


def could_cover(curve, points, radius):
    """False when one of the points (M, 3) is proven farther than radius from the curve (a CurveResult) by its
    stored points alone (kernels.near.within_reach); True otherwise."""
    if curve.length > 0 and len(curve.points) > 1:
        return kn.within_reach(points, np.ascontiguousarray(curve.points), np.ascontiguousarray(curve.s),
                               float(radius))
    return True


def edge_start(a, b, point, p_index, fixed, value, settings):
    """(point, y) on the curve exactly on the edge parameter `fixed` = value of surface p_index (0 a, 1 b), or
    None."""
    y = np.concatenate([a.parameters(point), b.parameters(point)])
    index = 2 * p_index + fixed
    y[index] = value
    y = newton_fixed_surfaces(a, b, y, index, settings.gap_tol)
    if y is None:
        return None
    return points_at(a, y[:2])[0], y                 # (Surface.point's evaluation, without its broadcasting)
