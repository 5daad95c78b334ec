"""Start points: a point near the curve, parameters near it, or the cut of an auxiliary curve ([Looper]).

References
----------
[Looper] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
machines of the light industry" (in Ukrainian): the start from the sphere's equator M3(u2) = M2(u2, 0), solving
M1(u1, v1) = M3(u2) for (u1, v1, u2) with v2 = 0.
"""
import math

import numpy as np

from ...kernels.march import restart as kr
from ...kernels.geometry import surfaces as ks
from ..._lib.validation import check_count, check_positive, check_real
from ...geometry.traits import check_surface
from .segments import NEWTON_MAX_ITER
from .segments import newton_fixed
from ..curve.result import TracingError

#: Samples of an auxiliary parameter line when looking for its crossings with the other surface.
AUX_SAMPLES = 720
#: ... and at most this many.
AUX_SAMPLES_MAX = 10_000_000


def scene_scale(a, b):
    """Length scale of an intersection: the smaller characteristic length of the two surfaces, ignoring
    planes and untrimmed cones (which have none); without one, the smaller half-diagonal of the trimmed
    planes' rectangles (1 where there is none)."""
    return scale_of(scene_reading(a), scene_reading(b))


def scale_of(first, second):
    """scene_scale from the two surfaces' scene_readings."""
    size_a, size_b = first[0], second[0]
    if size_a is not None or size_b is not None:
        return size_a if size_b is None else size_b if size_a is None else min(size_a, size_b)
    span = min(first[1], second[1])
    return span if math.isfinite(span) else 1.0


def scene_reading(surface):
    """(scale length or None, half diagonal of its trims, extent) of the surface, made once (its memo): its traits'
    scale_length (its own length of the scene scale), half the diagonal of its trims (u, v) (inf where one is
    unbounded) and its traits' extent (a length that bounds it; inf for an untrimmed plane, cylinder or cone)."""
    return surface.memo("scene", read_scene)


def read_scene(surface):
    """scene_reading's value, made."""
    traits = surface.traits
    (u0, u1), (v0, v1) = surface.bounds
    span = 0.5 * math.hypot(u1 - u0, v1 - v0)
    return traits.scale_length(surface), span if math.isfinite(span) else math.inf, traits.extent(surface)


def locate_on_curve(a, b, guess, gap_tol, y_guess=None):
    """A point of the curve near guess (3,) by minimum-norm Gauss-Newton on M1 - M2 = 0.

    Returns (point (3,), y (4,) in the user's charts, or with a sphere's (u, v) from its point).
    Raises TracingError if Newton does not converge (no intersection point near guess).
    """
    guess = np.asarray(guess, dtype=float)
    p1, y_user = np.empty(3), np.empty(4)
    keep = y_guess is not None
    # charts_at, project_to_curve and curve_frame, and a re-charted surface's own (u, v), in one compiled call
    if not kr.locate(a.data, b.data, a.traits.recharts, b.traits.recharts, np.ascontiguousarray(guess),
                     np.ascontiguousarray(y_guess, dtype=float) if keep else np.zeros(4), keep, gap_tol,
                     NEWTON_MAX_ITER, p1, y_user):
        raise TracingError.of("no_start", where=guess, point=guess.tolist())
    return p1, y_user


def auxiliary_starts(a, b, v=0.0, samples=AUX_SAMPLES, tol=1e-10):
    """The start of [Looper]: cut surface a with the parameter line v2 = v of surface b.

    For the sphere b and v = 0 this is the equator of [Looper] (M3(u2) = M2(u2, 0)). Every crossing of the
    line with a is found (sign changes of a's implicit function over `samples` points of u2 in [-pi, pi)),
    then M1(u1, v1) = M2(u2, v) is solved by Newton for (u1, v1, u2).

    Parameters
    ----------
    a, b : Surface
    v : float
        The parameter v of b's line (radians or a length, as b reads v).
    samples : int
        Points of the line searched for sign changes, 2 to AUX_SAMPLES_MAX.
    tol : float
        Accuracy of the crossings, relative to the scene scale, in (0, 1).

    Returns
    -------
    ndarray (K, 4)
        (u1, v1, u2, v) of each crossing, in the order of u2.

    Raises
    ------
    ValueError, TypeError
        Naming the argument that is not a surface, a finite real v, a count of samples in range, or a tolerance
        in (0, 1).
    """
    check_surface("a", a)
    check_surface("b", b)
    v = check_real("v", v, finite=True, strict=True)
    samples = check_count("samples", samples, minimum=2, maximum=AUX_SAMPLES_MAX)
    tol = check_positive("tol", tol, strict=True)
    if not tol < 1.0:
        raise ValueError(f"tol must lie in (0, 1), got {tol!r}")
    lo, hi = b.bounds[0]
    lo, hi = (-np.pi, np.pi) if not (np.isfinite(lo) and np.isfinite(hi)) else (lo, hi)
    u2 = np.linspace(lo, hi, int(samples) + 1)
    pts = b.point(u2, np.full_like(u2, v))
    f = np.array([ks.implicit_value(a.data, p) for p in pts])
    scale = scene_scale(a, b)
    out = []
    for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]:
        if f[i] == 0 and i > 0 and f[i - 1] == 0:
            continue
        y = np.array([*a.parameters(pts[i]), u2[i], v])
        y = newton_fixed_surfaces(a, b, y, 3, tol * scale)
        if y is not None and lo <= y[2] <= hi + 1e-12:
            out.append(y)
    out = np.array(out).reshape(-1, 4)
    if len(out) > 1:       # crossings found twice (a root exactly at a sample) are merged
        keep = [0]
        for k in range(1, len(out)):
            if np.min(np.linalg.norm(b.point(out[keep, 2], v) - b.point(out[k, 2], v), axis=-1)) > 1e3 * tol * scale:
                keep.append(k)
        out = out[keep]
    return out


def newton_fixed_surfaces(a, b, y, fixed, gap_tol):
    """spatialkin.tracing.march.segments.newton_fixed for two Surface objects (it takes their data arrays): the
    state (4,) on both surfaces with y[fixed] held, or None where Newton fails."""
    return newton_fixed(a.data, b.data, y, fixed, gap_tol)
