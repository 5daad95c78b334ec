"""Arc length measured on the corrected curve, where the solver's time is not it.

The solver's time s is the arc length of the path it integrates. Where that path stays within round-off of the
curve, the two agree; through a narrow waist (two branches passing close, the normals' angle small) the path
wobbles round the curve and its length exceeds the curve's (by 4.6e-7 over 2e-5 of a waist, measured). Each
solver step is therefore checked against the chords of the corrected curve (its two ends and its middle, one
Richardson step); a step whose time disagrees with that measure beyond the measure's own error is measured
again on finer chords, and the segment's time is re-mapped so that s is the corrected curve's arc length.
"""
import numpy as np

from ..kernels import curve as kc
from ..kernels import surfaces as ks
from .segments import NEWTON_MAX_ITER, StepStates

#: Only segments where the normals' sine falls below this are checked: elsewhere the path's tangent is off the
#: curve's by less than (gap / sine) ~ 1e-8 and its excess length by the square of that. The compiled
#: integrator hands over to solve_ivp well above it, so its segments are never checked.
CHECK_BELOW = 0.0      # OFF: at 1e-2 it made two plane-torus loops disagree between orders by 1.6e-7 (CI)

#: A step is cut into at most 2**MAX_DEPTH chords, halving until the Richardson estimate changes by less than
#: this fraction of the step ...
MEASURE_RTOL = 1e-13
MAX_DEPTH = 12
#: ... but no chord shorter than the points' own uncertainty d (NOISE_ULPS ulp of the coordinates / the normals'
#: sine) divided by sqrt(2 NOISE_RTOL): a chord between two points each off by d adds up to d^2 / (2 chord) to
#: the length. Where the floor stops the halving, the last estimate stands if it had settled to SETTLED_RTOL;
#: otherwise the step keeps the solver's time (a tiny near-tangent loop, whose points are fixed only to ~1e-10
#: of its 3e-6 length: measured there on short chords, it came out 55% longer).
NOISE_ULPS = 1
NOISE_RTOL = 1e-9
SETTLED_RTOL = 1e-9


class RemappedStates:
    """A segment's dense output read at corrected arc length t: t_new -> solver time (piecewise linear)."""

    def __init__(self, sol, t_new, t_old):
        self.sol, self.t_new, self.t_old = sol, t_new, t_old

    def __call__(self, t):
        return self.sol(np.interp(t, self.t_new, self.t_old))

    def solver_time(self, t):
        return np.interp(t, self.t_new, self.t_old)


def corrected_points(seg, t, gap_tol):
    """Points (M, 3) of the curve at solver times t of a segment (projected in the planes normal to it)."""
    y = np.ascontiguousarray(np.atleast_2d(np.asarray(seg.sol(t), dtype=float).T).reshape(-1, 4))
    p, tan, st = np.empty((len(y), 3)), np.empty((len(y), 3)), np.empty(len(y), dtype=np.int64)
    kc.project_many(y, seg.a, seg.b, seg.normal, gap_tol, NEWTON_MAX_ITER, p, tan, st)
    return p, st


def richardson(points_ends, points_mid):
    """Arc length per interval from its ends (n + 1, 3) and middles (n, 3): two chords plus a third of what they
    add to one (the chords' error falls as the cube of their length)."""
    one = np.linalg.norm(np.diff(points_ends, axis=0), axis=1)
    two = (np.linalg.norm(points_mid - points_ends[:-1], axis=1)
           + np.linalg.norm(points_ends[1:] - points_mid, axis=1))
    return two + (two - one) / 3.0


def measure_step(seg, t0, t1, gap_tol, shortest):
    """Arc length of the corrected curve over solver times [t0, t1], by chords halved until Richardson settles
    (None when a chord would be shorter than `shortest` before that, or Newton fails)."""
    previous, change = None, np.inf
    for depth in range(1, MAX_DEPTH + 1):
        if (t1 - t0) / 2 ** depth < shortest:
            return previous if change <= SETTLED_RTOL * (t1 - t0) else None
        t = np.linspace(t0, t1, 2 ** depth + 1)
        p, st = corrected_points(seg, t, gap_tol)
        if np.any(st < 0):
            return None
        value = float(richardson(p[::2], p[1::2]).sum())
        if previous is not None:
            change = abs(value - previous)
            if change <= MEASURE_RTOL * (t1 - t0):
                return value
        previous = value
    return previous


def remeasure_segment(seg, gap_tol):
    """Re-map the time of a solver segment that comes near a singular point (normals' sine below CHECK_BELOW) to
    the corrected curve's arc length. Returns the segment's new length (its old one when it was not checked)."""
    t = np.asarray(seg.t, dtype=float)
    if len(t) < 2 or np.any(seg.normal) or isinstance(seg.sol, StepStates):
        return float(seg.s1 - seg.s0)
    y = np.ascontiguousarray(np.asarray(seg.y, dtype=float).T)
    sine = min(kc.degeneracy(y[i], seg.a, seg.b, 0, 0) for i in range(len(y)))
    if sine >= CHECK_BELOW:
        return float(seg.s1 - seg.s0)
    points = np.empty((len(y), 3))
    ks.evaluate(seg.a, np.ascontiguousarray(y[:, :2]), points)
    noise = NOISE_ULPS * np.finfo(float).eps * float(np.abs(points).max()) / max(sine, 1e-300)
    shortest = noise / np.sqrt(2.0 * NOISE_RTOL)
    lengths = np.diff(t)
    for i in np.nonzero(lengths > 0)[0]:
        value = measure_step(seg, t[i], t[i + 1], gap_tol, shortest)
        if value is not None:
            lengths[i] = value
    t_new = np.concatenate([[0.0], np.cumsum(lengths)])
    seg.sol = RemappedStates(seg.sol, t_new, t)
    seg.t = t_new
    return float(t_new[-1])


def remeasure_branch(branch, gap_tol):
    """Re-measure every solver segment of a branch (see remeasure_segment) and shift the segments' arc lengths,
    the nodes passed and the branch's length to match."""
    if CHECK_BELOW <= 0.0:
        return branch                     # switched off: no segment would be checked
    old_knots, new_knots = [0.0], [0.0]
    s = 0.0
    for seg in branch.segments:
        old1 = seg.s1
        length = remeasure_segment(seg, gap_tol)
        seg.s0, seg.s1 = s, s + length
        s = seg.s1
        old_knots.append(old1)
        new_knots.append(s)
    if s == old_knots[-1] or len(old_knots) < 2:
        return branch
    old_knots, new_knots = np.array(old_knots), np.array(new_knots)
    beyond = branch.length - old_knots[-1]          # a closure found past the last segment's end
    if branch.length <= old_knots[-1]:
        branch.length = float(np.interp(branch.length, old_knots, new_knots))
    else:
        branch.length = float(new_knots[-1] + beyond)
    branch.nodes = [(float(np.interp(sn, old_knots, new_knots)), p) for sn, p in branch.nodes]
    return branch
