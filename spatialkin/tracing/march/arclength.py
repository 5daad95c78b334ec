"""Arc length measured on the curve itself, where the solver's time is not it.

The solver's time s is the arc length of the path M1(y(s)) it integrates. Where that path stays within
round-off of the curve, the two agree. Beside a near-node waist (two branches passing close, the normals'
angle small) the two surfaces nearly touch, so a gap of round-off size lets M1 slide off the curve along the
curve's normal (2.6e-7 where the normals' sine is 4e-5, measured), and there the curve bends sharply: the path
runs on the outside of the bend, and its length exceeds the curve's (by 1.7e-7 over one passage, measured on a
sphere-cylinder near-node).

Each solver step of a segment that comes near such a waist is therefore measured again: Gauss–Legendre on
the speed of the curve point beside M1 (kernels.curve.curve_speed_many: the path's velocity along the curve's
tangent, over 1 - curvature x offset), and the segment's time is re-mapped so that s is the curve's arc length.
On that near-node the two argument orders then come within 1.3e-11 and 1.9e-12 of the true length (40-digit
quadrature of the closed form), from 2.1e-8 and 1.7e-9.
"""
import numpy as np

from ...geometry.quadrature import gauss_legendre
from ...kernels.curve import near as kn
from ...kernels.march import curve as kc
from .segments import NEWTON_MAX_ITER

#: Only segments where the normals' sine falls below this are measured: elsewhere M1 stays within
#: (gap / sine) < 1e-8 of the curve and the path's excess length is below round-off. The compiled method
#: hands over (to its fine events) above it, so its segments are never measured.
CHECK_BELOW = 1e-2
#: Gauss–Legendre nodes per solver step (4, 8 and 16 agree to 5e-12 on the near-node above).
NODES = 8
#: A step keeps the solver's time unless the measure differs from it by more than this fraction of the step
#: (the measure's own noise, round-off / sine over a step, stays below it).
KEEP_RTOL = 1e-10


class RemappedStates:
    """A segment's dense output read at curve arc length t: t_new -> solver time (piecewise linear; beyond the
    ends, along the end steps' lines, so that a loop's closure found past the segment's last step extends its
    last step as a segment that was not re-measured does)."""

    def __init__(self, sol, t_new, t_old):
        self.sol = sol
        self.t_new, self.t_old = (np.ascontiguousarray(x, dtype=float) for x in (t_new, t_old))

    def __call__(self, t):
        return self.sol(self.solver_time(t))

    def solver_time(self, t):
        """Solver times of the arc lengths t (float or array): kernels.curve.near.remapped_time."""
        flat = np.ascontiguousarray(np.ravel(t), dtype=float)
        out = np.empty(flat.size)
        kn.remapped_times(flat, self.t_new, self.t_old, out)
        return out.reshape(np.shape(t)) if np.ndim(t) else float(out[0])


def step_lengths(seg, pullback, gap_tol):
    """Arc length of the curve over each solver step of a segment (NaN where the measure fails), NODES
    Gauss-Legendre nodes a step."""
    t = np.asarray(seg.t, dtype=float)

    def speed(s):
        """The curve's speed at solver times s (K,); NaN where the kernel fails (its negative speed)."""
        ys = np.ascontiguousarray(np.asarray(seg.sol(s), dtype=float).T)
        out = np.empty(len(ys))
        kc.curve_speed_many(ys, seg.a, seg.b, float(seg.sign), float(pullback), gap_tol, NEWTON_MAX_ITER, out)
        return np.where(out >= 0.0, out, np.nan)

    return gauss_legendre(speed, t[:-1], t[1:], NODES)


def remeasure_segment(seg, pullback, gap_tol):
    """Re-map the time of a solver segment that comes near a waist (normals' sine below CHECK_BELOW) to the
    curve's arc length. Returns the segment's new length (its old one when it was not measured)."""
    if seg.compiled:                 # the compiled method hands over well above
        return float(seg.s1 - seg.s0)
    t = np.asarray(seg.t, dtype=float)
    if len(t) < 2 or seg.jump:
        return float(seg.s1 - seg.s0)
    y = np.ascontiguousarray(np.asarray(seg.y, dtype=float).T)
    if min(kc.degeneracy(row, seg.a, seg.b, 0.0, 0.0) for row in y) >= CHECK_BELOW:
        return float(seg.s1 - seg.s0)
    h = np.diff(t)
    measured = step_lengths(seg, pullback, gap_tol)
    change = np.isfinite(measured) & (np.abs(measured - h) > KEEP_RTOL * h)
    if not np.any(change):
        return float(seg.s1 - seg.s0)
    lengths = np.where(change, measured, h)
    t_new = np.concatenate([[0.0], np.cumsum(lengths)])
    seg.sol = RemappedStates(seg.sol, t_new, t)
    seg.t = t_new
    return float(t_new[-1])


def remeasure_branch(branch, pullback, gap_tol):
    """Re-measure every solver segment of a branch (see remeasure_segment) and shift the segments' arc lengths,
    the nodes passed and the branch's length to match."""
    old_knots, new_knots = [0.0], [0.0]
    s = 0.0
    for seg in branch.segments:
        old1 = seg.s1
        length = remeasure_segment(seg, pullback, gap_tol)
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
