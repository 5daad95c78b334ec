"""The start of one segment of a branch in one compiled call: the charts, the state in them, and the projection.

A branch is integrated segment by segment (spatialkin.tracing.ivp); at each segment start the tracer re-charts the
surfaces that re-chart (a sphere: spatialkin.kernels.surfaces.recharted_sphere, at the point, the equator along
the direction of travel, then along the curve's curvature vector there when it is known), reads the state in the
new charts, and projects it back onto the curve in the plane normal to its tangent (Newton, minimum-norm steps
where that plane is ill-posed). ``segment_start`` does these steps, the same kernels in the same order as
spatialkin.tracing.segments.charts_at, spatialkin.tracing.ivp.curvature_vector and
spatialkin.tracing.segments.project_state do one by one from Python, so that the results agree to the bit.

References
----------
../shared/reference/ssi-notes.md: a corrector in the plane normal to the tangent (pseudo-arclength).
"""
import numpy as np

from .._jit import jit
from .curve import curve_derivatives, curve_frame, project_to_curve
from .surfaces import inverse, recharted_sphere


@jit
def chart_states(user, rechart, point, direction, bend, y_prev, k, out, y):
    """Surface k's chart into out (user re-charted at point along direction, bend the curvature vector or zero,
    when rechart; else a copy of user) and its (u, v) into y[2k:2k + 2] (the foot point's in a new chart, else
    y_prev's)."""
    if rechart:
        recharted_sphere(user, point, direction, bend, out)
        uv = np.empty((1, 2))
        inverse(out, point.reshape((1, 3)), uv)
        y[2 * k] = uv[0, 0]
        y[2 * k + 1] = uv[0, 1]
    else:
        for i in range(out.shape[0]):
            out[i] = user[i]
        y[2 * k] = y_prev[2 * k]
        y[2 * k + 1] = y_prev[2 * k + 1]


@jit
def segment_start(a_user, b_user, rechart_a, rechart_b, point, direction, y_prev, gap_tol, max_iter,
                  a_out, b_out, y, point_out, tangent_out):
    """A segment's charts (into a_out, b_out: re-charted where rechart_a, rechart_b, else copies of the user's data),
    its state y (4,) projected onto the curve, and the curve's point and unit tangent there (point_out,
    tangent_out). Returns True when the projection converged.

    point (3,) and direction (3,) are where the segment starts and the direction of travel; y_prev (4,) the state
    of the surfaces that keep their chart. A re-charting surface is re-charted along direction, then (when the
    curve's curvature vector is defined there) along the curvature vector in the first charts."""
    zero = np.zeros(3)
    chart_states(a_user, rechart_a, point, direction, zero, y_prev, 0, a_out, y)
    chart_states(b_user, rechart_b, point, direction, zero, y_prev, 1, b_out, y)
    if rechart_a or rechart_b:
        dy, ddy, d1, bend = np.empty(4), np.empty(4), np.empty(3), np.empty(3)
        if curve_derivatives(y, a_out, b_out, 1.0, dy, ddy, d1, bend):
            first = y.copy()
            chart_states(a_user, rechart_a, point, direction, bend, first, 0, a_out, y)
            chart_states(b_user, rechart_b, point, direction, bend, first, 1, b_out, y)
    curve_frame(y, a_out, b_out, point_out, tangent_out)
    start = y.copy()
    iters = project_to_curve(y, a_out, b_out, point_out.copy(), tangent_out.copy(), gap_tol, max_iter)
    if iters < 0:        # the plane condition is ill-posed (a tiny loop, near tangency): minimum-norm steps
        for i in range(4):
            y[i] = start[i]
        iters = project_to_curve(y, a_out, b_out, point_out.copy(), zero, gap_tol, max_iter)
    curve_frame(y, a_out, b_out, point_out, tangent_out)
    return iters >= 0
