"""sk.trace: the component of the intersection of two surfaces through a start near it.

The march (spatialkin.tracing.march) integrates it; where the normals come close to parallel at a local minimum of
their angle (NODE_SUSPECT), only the topology search (spatialkin.tracing.search.topology) tells a node, where the
branch jumps across, from a narrow waist or a small loop round a critical point off the curve, which it follows: the
search runs then, once per call (settings.find_nodes), as sk.intersect runs it first.
"""
import functools
import time

import numpy as np

from .curve.clip import clip_curve
from .curve.result import Curve, TracingError
from .march.start import locate_on_curve
from .march.trace import (DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, make_settings,
                          trace_from)
from .search.topology import TopologyError, topology
from ..geometry.asymptotic import bounded_pair
from ..geometry.traits import check_surface
from .._lib import warm
from .._lib.validation import as_float_array


def start_point(a, b, start, gap_tol):
    """(point, y) on the curve from a 3-vector near it or from (u1, v1, u2, v2)."""
    arr = as_float_array("start", start)
    if arr.shape not in ((3,), (4,)):
        raise ValueError(f"start must be a point (3,) or parameters (u1, v1, u2, v2) (4,), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"start must be finite, got {arr.tolist()}")
    if arr.shape == (3,):
        return locate_on_curve(a, b, arr, gap_tol)
    guess = 0.5 * (a.point(arr[0], arr[1]) + b.point(arr[2], arr[3]))
    return locate_on_curve(a, b, guess, gap_tol, y_guess=arr)


def trace(a, b, start, *, tol=1e-10, method=DEFAULT_METHOD, rtol=DEFAULT_RTOL, atol=None, max_length=None,
          singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK, close=True):
    """Trace the component of a ∩ b through a start point, by arc length (Dragilev's method).

    Parameters
    ----------
    a, b : Surface
        The two surfaces (any kinds, trimmed or not).
    start : array_like, shape (3,) or (4,)
        A global point near the curve (the user's length unit), or parameters (u1, v1, u2, v2) near it (u1, v1
        of surface a, u2, v2 of b). Newton moves it onto the curve first.
    tol : float
        Accuracy asked of every returned point and every dense evaluation, relative to the scene scale (the
        smaller characteristic length of the two surfaces: a sphere's or cylinder's radius, a torus's R + r):
        distance to both surfaces <= tol * scale (``curve.tolerance``, an absolute length).
    method : str
        'compiled' (default): solve_ivp with spatialkin.ode.solvers.CompiledDOP853 (scipy's DOP853 steps, many
        per solver step in compiled code), handing singular points and apexes to the same engine with the fine
        events (spatialkin.tracing.march.ivp.FALLBACK_METHOD); 'compiled-rk45' the same with scipy's RK45 steps
        (CompiledRK45); or a solve_ivp method ('DOP853', 'RK45', 'RK23', 'Radau', 'BDF', 'LSODA') for the whole
        curve.
    rtol, atol : float
        solve_ivp tolerances on (u1, v1, u2, v2); atol defaults to rtol for angles and rtol * scale for lengths.
    max_length : float, optional
        Longest arc length traced in each direction, in the user's length unit (default: 32 turns round the
        smaller surface extent).
    singular_tol : float
        A branch stops where sin(angle between the normals) falls below this.
    pullback : float
        Pull-back rate times the scale: the gap |M1 - M2| of the integrated state decays like
        exp(-pullback * s / scale) (0 turns it off).
    close : bool
        Detect closure (True) or trace on to max_length (False; for drift studies); a bool, nothing else.

    Returns
    -------
    Curve
        The component through the start: points (N, 3), arc lengths s (N,), parameters (N, 4), closed or open
        (its ``status`` says how each end stopped), with dense evaluation ``curve(s)``.

    Raises
    ------
    ValueError
        For bad arguments (named: `start`, `tol`, `method`, `rtol`, `atol`, `max_length`, `singular_tol`,
        `pullback`; their ranges: check_options).
    TypeError
        Naming `a` or `b` when it is not a spatialkin surface, `start` or an option when it is not real numbers,
        `close` when it is not a bool.
    TracingError
        If no curve point is found near start (status 'no_start'), or start is a singular point of the
        intersection (the normals parallel there).

    See Also
    --------
    intersect : every component, each traced once, with no start needed.

    Notes
    -----
    The curve M(s) common to both surfaces, s its arc length, solves the Cauchy problem
    dM/ds = N_a x N_b / |N_a x N_b| (N_a, N_b the surfaces' normals), written for the parameters
    (u1, v1, u2, v2) and integrated by scipy.integrate.solve_ivp from the located start in both directions
    until the curve closes, leaves a trim or meets a singular point [1]_; the trims that are not ranges of a
    length (angular ranges, a plane's circle: spatialkin.tracing.curve.clip) then cut it, and the arc nearest the
    start is returned. Every stored point is then corrected
    onto both surfaces by Newton, and the arc length is re-measured on the corrected curve. The integrator is
    a Dormand-Prince pair with dense output [2]_. Where the normals come within about 1e-4 rad of parallel (a
    crossing of branches, a narrow waist, a small loop near a tangency) or the curve nears a cone's apex, the
    topology search of ``intersect`` runs once (where a surface is bounded), and the branch jumps across only the
    singular points it proves.

    References
    ----------
    .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
       machines of the light industry" (in Ukrainian): Dragilev's method.
    .. [2] E. Hairer, S. P. Nørsett, G. Wanner, Solving Ordinary Differential Equations I, 2nd ed., Springer,
       1993.

    Examples
    --------
    Two unit spheres one radius apart meet in a circle of radius sqrt(3)/2 in the plane x = 1/2:

    >>> import numpy as np
    >>> import spatialkin as sk
    >>> a, b = sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0)))
    >>> curve = sk.trace(a, b, (0.5, 0.9, 0.0))
    >>> curve.closed, curve.status
    (True, 'closed')
    >>> round(curve.length, 6)          # 2 pi sqrt(3)/2
    5.441398
    >>> np.allclose(curve.points[:, 0], 0.5), bool(curve.max_distance <= curve.tolerance)
    (True, True)

    A start far from the curve:

    >>> sk.trace(a, sk.Sphere(1.0, sk.Frame((5.0, 0.0, 0.0))), (2.5, 0.0, 0.0))
    Traceback (most recent call last):
    ...
    spatialkin.tracing.curve.result.TracingError: no intersection point found near start [2.5, 0.0, 0.0]: ...
    """
    check_surface("a", a)
    check_surface("b", b)
    if not isinstance(close, (bool, np.bool_)):
        raise TypeError(f"close must be a bool, got {type(close).__name__}")
    warm.refresh()
    t_start = time.perf_counter()
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    settings = make_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback, close, anchor)
    settings.find_nodes = functools.partial(searched_nodes, a, b, settings.scale, settings.tolerance)
    point, y = start_point(a, b, start, settings.gap_tol)
    whole = trace_from(a, b, point, y, settings, t_start)
    if not (a.region or b.region):
        return Curve(whole)
    arcs = clip_curve(a, b, whole, settings.scale)
    if not arcs:
        raise TracingError.of("outside_trims", where=point, point=point.tolist())
    return Curve(min(arcs, key=lambda arc: float(arc.sol.closest(point)[1])))


def searched_nodes(a, b, scale, tolerance):
    """(K, 3) the singular points of a ∩ b the topology search proves a branch may pass (the nodes, and the apexes
    and poles lying on the other surface), as sk.intersect hands them to the march; None where the search cannot
    run (the surfaces coincide, or neither is bounded and no ball holds all they share) or stops (TopologyError):
    every suspect minimum is then taken for a node."""
    a, b = bounded_pair(a, b)             # (two unbounded surfaces: cut to a ball holding all they share)
    try:
        topo = topology(a, b, scale, tolerance)
    except (TopologyError, ValueError):
        return None
    return topo.crossings()
