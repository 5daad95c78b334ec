"""sk.intersect: every component of the intersection of two surfaces, each once."""
import time

import numpy as np

from ..surfaces import check_surface
from .result import Curve, TracingError
from .seeds import find_seeds
from .start import locate_on_curve
from .trace import DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, make_settings, trace_from

#: A seed lying within this distance (relative to the scale) of a curve already traced belongs to it.
SAME_COMPONENT = 1e-6


def intersect(a, b, tol=1e-10, *, method="DOP853", rtol=DEFAULT_RTOL, atol=None, max_length=None,
              singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK):
    """Every component of a ∩ b.

    Start points come from the critical points of one surface's implicit function read on the other
    (spatialkin.tracing.seeds); each component is traced once by ``trace`` and seeds on it are skipped.

    Parameters
    ----------
    a, b : Surface
    tol : float
        Accuracy of every returned point, relative to the scene scale (see ``trace``).
    method, rtol, atol, max_length, singular_tol, pullback
        As in ``trace``.

    Returns
    -------
    list of Curve
        Closed loops, open curves (ending at singular points or edges) and single contact points
        (status 'contact', length 0); empty when the surfaces do not meet.
    """
    check_surface("a", a)
    check_surface("b", b)
    t0 = time.perf_counter()
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    settings = make_settings(a, b, tol, method, rtol, atol, max_length, singular_tol, pullback, True, anchor)
    seeds, contacts, nodes = find_seeds(a, b, settings.scale, tol * settings.scale)
    curves = [contact_curve(a, b, p, settings) for p in contacts]
    radius = SAME_COMPONENT * settings.scale
    for seed in seeds:
        try:
            point, y = locate_on_curve(a, b, seed, settings.gap_tol)
        except TracingError:
            continue
        if any(np.min(c.closest(point)[1]) <= radius for c in curves):
            continue
        try:
            curves.append(trace_from(a, b, point, y, settings, time.perf_counter()))
        except TracingError:
            continue            # the seed sits on a singular point: the arms' seeds trace it
    for c in curves:
        c.search_time = time.perf_counter() - t0
    return curves


def contact_curve(a, b, point, settings):
    """A component that is a single point where the surfaces touch."""
    y = np.concatenate([a.parameters(point), b.parameters(point)]).reshape(1, 4)
    return Curve((a, b), point.reshape(1, 3), np.zeros(1), y, False, 0.0, "contact",
                 f"the surfaces touch at {point.tolist()}", [], settings.gap_tol)
