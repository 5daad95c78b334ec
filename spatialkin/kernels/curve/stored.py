"""The stored points of a traced curve: the solver's states at its steps, span by span, corrected onto the curve.

``corrected_spans`` does in one compiled call, span by span: each span's states corrected by Newton in that span's
charts (spatialkin.kernels.march.curve.corrected_many), the user's parameters of a re-charted surface read back from the
corrected points (spatialkin.kernels.geometry.surfaces.inverse, as spatialkin.tracing.curve.result.user_params), and the whole
turns removed from a re-charted surface's u (unwrap_turns, which the closed forms call too): the same kernels and the
same operations in the same order as a span-by-span loop over them in Python, so that the results agree with it to the
bit.

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002
(marching: Newton projection of the predicted points onto both surfaces).
"""
import math

import numpy as np

from ..._lib.jit import borrowed, jit, kept
from ..march.curve import corrected_many
from ..geometry.surfaces import inverse

#: One turn of an angle.
TWO_PI = 2.0 * math.pi


@jit
def unwrap_turns(u):
    """The angles u (N,) in place, whole turns removed from the jumps between neighbours (continuous):
    u[1:] -= 2 pi cumsum(rint(diff(u) / 2 pi)), the jumps taken from the angles as given."""
    n = u.shape[0]
    turns = np.empty(max(n - 1, 0))
    for i in range(n - 1):
        turns[i] = np.rint((u[i + 1] - u[i]) / TWO_PI)
    total = 0.0
    for i in range(n - 1):
        total += turns[i]
        u[i + 1] -= TWO_PI * total


@jit
def user_parameters(user, points, lo, hi, column, params):
    """params[lo:hi, column:column + 2] = the (u, v) in the user's chart of the points[lo:hi] (foot points)."""
    uv = np.empty((hi - lo, 2))
    inverse(user, points[lo:hi], uv)
    for k in range(hi - lo):
        params[lo + k, column] = uv[k, 0]
        params[lo + k, column + 1] = uv[k, 1]


@jit
def corrected_spans(y_all, cuts, charts_a, charts_b, normals, user_a, user_b, own_a, own_b, unwrap_a, unwrap_b,
                    gap_tol, max_iter, points, params, gaps):
    """Correct the states y_all (N, 4), in pieces [cuts[j], cuts[j + 1]) each integrated in charts_a[j],
    charts_b[j] (with the fixed correction plane normals[j], zero for none): points (N, 3) and the solver's gaps
    (N,) as corrected_many writes them, params (N, 4) the corrected states, where own_a[j] (own_b[j]) with
    surface a's (b's) (u, v) from the points in the user's chart user_a (user_b); with unwrap_a (unwrap_b) the
    whole turns removed from that surface's u over all N points."""
    y_all, charts_a, charts_b, normals, points, params, gaps = borrowed((y_all, charts_a, charts_b, normals, points,
                                                                         params, gaps))
    for j in range(cuts.shape[0] - 1):
        lo, hi = cuts[j], cuts[j + 1]
        states = y_all[lo:hi].copy()
        y = borrowed(states)
        corrected_many(y, charts_a[j], charts_b[j], normals[j], gap_tol, max_iter, points[lo:hi], gaps[lo:hi])
        for k in range(hi - lo):
            for i in range(4):
                params[lo + k, i] = y[k, i]
        if own_a[j]:
            user_parameters(user_a, points, lo, hi, 0, params)
        if own_b[j]:
            user_parameters(user_b, points, lo, hi, 2, params)
        kept(states)
    if unwrap_a:
        unwrap_turns(params[:, 0])
    if unwrap_b:
        unwrap_turns(params[:, 2])
