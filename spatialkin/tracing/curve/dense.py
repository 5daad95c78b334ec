"""Dense output of a curve: points, tangents and parameters at any arc length (scipy's OdeSolution is the model).

``CurveSolution`` is the interface (and what every dense output shares: arc-length checks, the closest point);
``TracedSolution`` evaluates a traced curve from the solver's dense output, each state corrected onto both surfaces
by Newton. The closed-form ones (a circle, a segment, a point) are in spatialkin.tracing.curve.exact.
"""
import numpy as np
from scipy.spatial import cKDTree

from ...kernels.curve import near as kn
from ...kernels.curve.near import FOOT_HALVINGS
from ...kernels.march import curve as kc
from ...kernels.geometry import surfaces as ks
from .curvature import curvature_vectors
from .packed import pack
from .result import set_states, user_params
from ..march.segments import NEWTON_MAX_ITER

#: Inside a jump across a node or an apex, a Newton-corrected point farther than this fraction of the jump from
#: the interpolated one has strayed (to another branch, or off through a degenerate chart): the interpolated
#: point on the chords through the node is used instead (within about jump^2 x curvature of the branches).
JUMP_STRAY = 0.5
#: ... or farther than this fraction of its distance from the node passed (it went to the other branch).
NODE_STRAY = 0.2
#: ... and within this fraction of the jump from the node, the branch is interpolated (see
#: TracedSolution._jump_points).
NODE_ANCHOR = 0.05
#: ... unless a parametrisation degenerates there (relative area element below this at the anchors).
ANCHOR_APEX_CLEAR = 1e-2
#: Newton steps in arc length refining the nearest samples in CurveSolution.closest, and how many are refined.
CLOSEST_NEWTON_STEPS = 4
CLOSEST_CANDIDATES = 6
#: closest() starts from a dense grid of this many points per stored point, and at least CLOSEST_GRID_MIN.
CLOSEST_GRID_FACTOR = 8
CLOSEST_GRID_MIN = 64
#: Relative slack of the arc-length range check of an open curve (round-off of s at its ends).
S_RANGE_SLACK = 1e-12


class CurveSolution:
    """Dense output of one curve of length ``length`` (closed: periodic in s), through its stored points at
    arc lengths ``knots``, on the two ``surfaces``. Subclasses define ``evaluate``.

    Attributes
    ----------
    surfaces : (Surface, Surface)
    length : float
    closed : bool
    knots : ndarray (N,)
        Arc lengths of the curve's stored points (they size the grid closest() starts from).
    """

    #: The compiled tables of the dense output (spatialkin.tracing.curve.packed), or None: a closed form has none.
    table = None

    def __init__(self, surfaces, length, closed, knots):
        self.surfaces = tuple(surfaces)
        self.length = float(length)
        self.closed = bool(closed)
        self.knots = knots
        self._grid = None

    def evaluate(self, s, with_params=True):
        """(s wrapped (M,), points (M, 3), unit tangents (M, 3), params (M, 4) or None unless with_params) at the
        flattened arc lengths s."""
        raise NotImplementedError

    def wrap(self, s):
        """Arc lengths s as an array, wrapped into [0, length) for a closed curve; ValueError if not finite or,
        for an open curve, outside [0, length]."""
        s = np.asarray(s, dtype=float)
        if not np.all(np.isfinite(s)):
            raise ValueError("s must be finite")
        if self.closed and self.length > 0:
            return np.mod(s, self.length)
        if np.any((s < -S_RANGE_SLACK * max(1.0, self.length)) | (s > self.length * (1 + S_RANGE_SLACK) + 1e-300)):
            raise ValueError(f"s must lie in [0, {self.length:.12g}] for this open curve")
        return s

    def __call__(self, s):
        """Points (..., 3) on the curve at arc lengths s (...,)."""
        return self.evaluate(s, with_params=False)[1].reshape(np.shape(s) + (3,))

    def tangent(self, s):
        """Unit tangents (..., 3) at s, pointing towards increasing s."""
        return self.evaluate(s, with_params=False)[2].reshape(np.shape(s) + (3,))

    def parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s."""
        return self.evaluate(s)[3].reshape(np.shape(s) + (4,))

    def predicted_parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s, as cheaply as the dense output gives them (here: parameters())."""
        return self.parameters(s)

    def derivatives(self, s):
        """(points, unit tangents C', curvature vectors C'') (..., 3) each at arc lengths s: from the points and
        the two surfaces' implicit functions (C'' NaN at and beside a singular point: curvature_vectors)."""
        shape = np.shape(s)
        _, points, tangents, _ = self.evaluate(s, with_params=False)
        bend = curvature_vectors(*self.surfaces, points, tangents, float(getattr(self, "gap_tol", 0.0)))
        return tuple(x.reshape(shape + (3,)) for x in (points, tangents, bend))

    def closest(self, points):
        """Arc length (...,) of the curve point nearest to each point (..., 3), and the distance (...,)."""
        pts = np.asarray(points, dtype=float)
        flat = pts.reshape(-1, 3)
        grid, dense = self.grid()
        # refine the few nearest samples (not only the nearest: the curve may pass close to itself)
        k = min(CLOSEST_CANDIDATES, len(grid))
        idx = cKDTree(dense).query(flat, k=k)[1].reshape(len(flat), k)
        cand = grid[idx].ravel()
        s, dist = self.foot_points(np.repeat(flat, k, axis=0), cand, CLOSEST_NEWTON_STEPS)
        best = np.argmin(dist.reshape(-1, k), axis=1)
        s, dist = s.reshape(-1, k)[np.arange(len(flat)), best], dist.reshape(-1, k)[np.arange(len(flat)), best]
        return s.reshape(pts.shape[:-1]), dist.reshape(pts.shape[:-1])

    def foot_points(self, pts, s, steps):
        """(s, distance) of foot points of pts (M, 3) on the curve by `steps` Newton steps in s from s (M,): on
        g(s) = (p - C(s)) . C'(s), its slope read by the secant through the last two iterates (-1 at the first),
        each step halved until the distance does not grow (as spatialkin.kernels.curve.near.foot_distance)."""
        s = np.array(s, dtype=float)
        at_s, at, tangent, _ = self.evaluate(s, with_params=False)
        dist = np.linalg.norm(pts - at, axis=1)
        g = np.einsum("ij,ij->i", pts - at, tangent)
        s_prev, g_prev = np.full(len(s), np.nan), np.full(len(s), np.nan)
        active = np.ones(len(s), dtype=bool)
        for _ in range(steps):
            with np.errstate(divide="ignore", invalid="ignore"):
                slope = (g - g_prev) / (s - s_prev)
            step = -g / np.where(slope < 0.0, slope, -1.0)
            pending, moved = active.copy(), np.zeros(len(s), dtype=bool)
            for _ in range(FOOT_HALVINGS + 1):
                idx = np.nonzero(pending)[0]
                if not len(idx):
                    break
                trial = s[idx] + step[idx]
                trial = trial if self.closed else np.clip(trial, 0.0, self.length)
                wrapped, t_at, t_tangent, _ = self.evaluate(trial, with_params=False)
                t_dist = np.linalg.norm(pts[idx] - t_at, axis=1)
                ok = t_dist <= dist[idx]
                keep = idx[ok]
                s_prev[keep], g_prev[keep] = s[keep], g[keep]
                s[keep], at_s[keep], dist[keep] = trial[ok], wrapped[ok], t_dist[ok]
                g[keep] = np.einsum("ij,ij->i", pts[keep] - t_at[ok], t_tangent[ok])
                moved[keep] = True
                pending[keep] = False
                step[idx[~ok]] *= 0.5
            active &= moved                         # (no step brought it nearer: the foot, to round-off)
        return at_s, dist

    def grid(self):
        """Arc lengths and points of the dense grid closest() starts from (computed once: a curve does not
        change)."""
        if self._grid is None:
            grid = self.grid_s()
            self._grid = (grid, self(grid))
        return self._grid

    def grid_s(self):
        """The arc lengths of grid(): evenly spaced, CLOSEST_GRID_FACTOR per knot (at least CLOSEST_GRID_MIN)."""
        return np.linspace(0.0, self.length, max(CLOSEST_GRID_FACTOR * len(self.knots), CLOSEST_GRID_MIN))


class Span:
    """A piece of the dense output: global s in [lo, hi] maps to segment time t = shift + flip * s."""

    __slots__ = ("lo", "hi", "flip", "shift", "seg")

    def __init__(self, lo, hi, flip, shift, seg):
        self.lo, self.hi, self.flip, self.shift, self.seg = lo, hi, flip, shift, seg

    def states(self, s):
        return self.seg.sol(self.shift + self.flip * s)


class TracedSolution(CurveSolution):
    """Dense output of a traced curve: the solver's dense output of each segment (``spans``, in order of s),
    each state corrected onto both surfaces by Newton to ``gap_tol``; across a node or an apex (of ``nodes``)
    along the chords through it.

    Parameters
    ----------
    surfaces : (Surface, Surface)
    spans : list of Span
        Covering [0, length] in order.
    nodes : ndarray (K, 3)
        Singular points the curve passes straight through.
    gap_tol : float
        Newton's target for |M1 - M2| (length unit).
    length, closed, knots
        As in CurveSolution.
    """

    def __init__(self, *, surfaces, spans, nodes, gap_tol, length, closed, knots):
        super().__init__(surfaces, length, closed, knots)
        self.spans = spans
        self.nodes = nodes
        self.gap_tol = gap_tol
        self._lo = np.array([sp.lo for sp in spans])
        self._table = False

    @property
    def table(self):
        """The compiled tables of the spans (spatialkin.tracing.curve.packed.pack; None when they hold none), made
        on first use (a curve does not change)."""
        if self._table is False:
            self._table = pack(self.spans)
        return self._table

    def _span_states(self, s):
        """(s wrapped, [(mask, span, solver states (m, 4)) per span hit]) for the flat arc lengths s."""
        s = self.wrap(np.ravel(s))
        idx = np.clip(np.searchsorted(self._lo, s, side="right") - 1, 0, len(self.spans) - 1)
        if len(self.spans) == 1:
            return s, [(slice(None), self.spans[0], np.ascontiguousarray(self.spans[0].states(s).T))]
        pieces = []
        for k in np.unique(idx):
            mask = idx == k
            pieces.append((mask, self.spans[k], np.ascontiguousarray(self.spans[k].states(s[mask]).T)))
        return s, pieces

    def evaluate(self, s, with_params=True):
        """Corrected states, points and tangents at s (flattened); params is None unless with_params. The spans the
        compiled tables hold are evaluated there (kernels.curve.near.curve_states: the segment's record, then Newton
        onto both surfaces); the others (a jump across a node or an apex, a solve_ivp method without polynomial
        steps) here."""
        s = self.wrap(np.ravel(s))
        points = np.empty((s.size, 3))
        tangents = np.empty((s.size, 3))
        ys = np.empty((s.size, 4))
        table = self.table
        if table is not None:
            index = np.empty(s.size, dtype=np.int64)          # (curve_states writes every row: -1 where not held)
            kn.curve_states(table, self.closed, self.length, float(self.gap_tol), NEWTON_MAX_ITER,
                            np.ascontiguousarray(s), ys, points, tangents, index)
        else:
            index = np.full(s.size, -1, dtype=np.int64)
        rest = index < 0
        held = not rest.any()
        if held and not with_params:
            return s, points, tangents, None
        if not held:
            index[rest] = np.clip(np.searchsorted(self._lo, s[rest], side="right") - 1, 0, len(self.spans) - 1)
        params = np.empty((s.size, 4)) if with_params else None
        for k in np.unique(index).tolist():
            span = self.spans[k]
            mask = index == k
            if not held and rest[mask].any():         # a span the tables do not hold
                y = np.ascontiguousarray(span.states(s[mask]).T)
                p, t, st = np.empty((len(y), 3)), np.empty((len(y), 3)), np.empty(len(y), dtype=np.int64)
                if np.any(span.seg.normal):   # across a node or an apex
                    self._jump_points(span, s[mask], y, p, t, st)
                else:
                    kc.project_many(y, span.seg.a, span.seg.b, span.seg.normal, self.gap_tol, NEWTON_MAX_ITER, p,
                                    t, st)
                ys[mask], points[mask], tangents[mask] = y, p, t * span.flip * span.seg.sign
            if with_params:
                params[mask] = user_params(self.surfaces, ys[mask], points[mask], span.seg.a, span.seg.b)
        return s, points, tangents, params

    def foot_points(self, pts, s, steps):
        """(s, distance) of foot points of pts (M, 3) by `steps` Newton steps in s from s (M,): in compiled code
        (kernels.curve.near.foot_many), the points whose Newton meets a span the tables do not hold by
        CurveSolution.foot_points."""
        table = self.table
        if table is None:
            return super().foot_points(pts, s, steps)
        pts = np.ascontiguousarray(pts, dtype=float)
        s_out, d_out = np.empty(len(pts)), np.empty(len(pts))
        kn.foot_many(table, self.closed, self.length, float(self.gap_tol), NEWTON_MAX_ITER, pts,
                     np.ascontiguousarray(s, dtype=float), int(steps), s_out, d_out)
        rest = np.isnan(d_out)
        if rest.any():
            s_out[rest], d_out[rest] = super().foot_points(pts[rest], np.asarray(s, dtype=float)[rest], steps)
        return s_out, d_out

    def closest(self, points):
        """Arc length (...,) of the curve point nearest to each point (..., 3), and the distance (...,): in compiled
        code (kernels.curve.near.closest_many, from the CLOSEST_CANDIDATES grid points nearest to each), the
        points whose Newton meets a span the tables do not hold by CurveSolution.closest."""
        table = self.table
        if table is None:
            return super().closest(points)
        pts = np.asarray(points, dtype=float)
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        grid_s, grid = self.grid()
        s_out, d_out = np.empty(len(flat)), np.empty(len(flat))
        kn.closest_many(flat, grid_s, np.ascontiguousarray(grid), table, self.closed, self.length,
                        float(self.gap_tol), NEWTON_MAX_ITER, CLOSEST_NEWTON_STEPS, CLOSEST_CANDIDATES, s_out, d_out)
        rest = np.isnan(d_out)
        if rest.any():
            s_out[rest], d_out[rest] = super().closest(flat[rest])
        return s_out.reshape(pts.shape[:-1]), d_out.reshape(pts.shape[:-1])

    def predicted_parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s from the solver's dense output alone, without the Newton correction:
        within the solver's tolerance of the curve, a cheap start for Newton (a sphere's (u, v) are those of
        the point on surface a, as in parameters())."""
        shape = np.shape(s)
        s, pieces = self._span_states(s)
        params = np.empty((s.size, 4))
        for mask, span, y in pieces:
            on_a = np.empty((len(y), 3))
            ks.evaluate(span.seg.a, np.ascontiguousarray(y[:, :2]), on_a)
            params[mask] = user_params(self.surfaces, y, on_a, span.seg.a, span.seg.b)
        return params.reshape(shape + (4,))

    def _jump_points(self, span, s, y, p, t, st):
        """Points of a jump span (across a node or an apex) at arc lengths s, written to y, p, t, st: Newton from
        the chords through the node, in the plane normal to the chord of each side (the branch's own side of
        the node: the other branch crosses that plane about |s - s_node| x sin(crossing angle) away). A point
        farther than JUMP_STRAY x jump from its chord point (a degenerate chart at an apex), or than NODE_STRAY
        x its distance from the node (the other branch, where Newton's system is singular), has strayed: the
        chord point stands for it. Within NODE_ANCHOR x jump of the node, where Newton's error grows like
        round-off / distance, the branch is the parabola through the node and two Newton points farther out."""
        a, b = span.seg.a, span.seg.b
        guess, side, chords, near, node = self._jump_chords(span, s)
        set_states(y, guess, a, b)
        self._project_sides(y, a, b, side, chords, guess, p, t, st)
        moved = np.linalg.norm(p - guess, axis=1)
        stray = (st < 0) | (moved > JUMP_STRAY * (span.hi - span.lo)) | (moved > NODE_STRAY * near)
        p[stray] = guess[stray]
        t[stray] = chords[side[stray]]
        anchor = NODE_ANCHOR * (span.hi - span.lo)
        close = near < anchor
        if node is not None and close.any():
            flags = span.seg.area
            for half in np.unique(side[close]):
                rows = close & (side == half)
                sign = 1.0 if half else -1.0
                at = node + sign * chords[half] * np.array([[anchor], [2.0 * anchor]])
                ya = np.repeat(y[rows][:1], 2, axis=0)
                set_states(ya, at, a, b)
                pa, ta, sa = np.empty((2, 3)), np.empty((2, 3)), np.empty(2, np.int64)
                kc.project_through(ya, a, b, chords[half], at, self.gap_tol, NEWTON_MAX_ITER, pa, ta, sa)
                if np.any(sa < 0) or (any(flags) and min(kc.area_degeneracy(ya[i], a, b, *flags)
                                                         for i in range(2)) < ANCHOR_APEX_CLEAR):
                    continue                       # beside an apex (a horn torus's cusp): Newton's points stand
                r = near[rows][:, None] / anchor           # the parabola node + c1 r + c2 r^2 through pa at 1, 2
                c2 = 0.5 * (pa[1] - node) - (pa[0] - node)
                c1 = pa[0] - node - c2
                p[rows] = node + c1 * r + c2 * r * r
                t[rows] = sign * (c1 + 2.0 * c2 * r)
                t[rows] /= np.linalg.norm(t[rows], axis=1)[:, None]
                y[rows] = set_states(y[rows], p[rows], a, b)
        direction = span.seg.normal
        t[np.sum(t * direction, axis=1) < 0] *= -1.0

    def _project_sides(self, y, a, b, side, chords, guess, p, t, st):
        """Newton in the plane normal to each side's chord through each guess point (rows of side 0 and 1), in
        place."""
        for half in np.unique(side):
            rows = side == half
            n = int(rows.sum())
            yh, ph, th, sh = y[rows], np.empty((n, 3)), np.empty((n, 3)), np.empty(n, np.int64)
            kc.project_through(yh, a, b, chords[half], np.ascontiguousarray(guess[rows]), self.gap_tol,
                               NEWTON_MAX_ITER, ph, th, sh)
            y[rows], p[rows], t[rows], st[rows] = yh, ph, th, sh

    def _jump_chords(self, span, s):
        """(points (M, 3), side (M,) in {0, 1}, unit chord directions (2, 3), distances (M,) of the points from the
        node (inf without one), the node (3,) or None) at arc lengths s of a jump span: on
        the chords from its start to the node (or apex) passed and on to its end (one straight chord where no
        node is near): the curve's two branches there are nearly straight, whatever the charts do at the node."""
        sol = span.seg.sol
        w = np.clip((span.shift + span.flip * np.asarray(s, dtype=float)) / sol.length, 0.0, 1.0)[:, None]
        if sol.arc is not None:                 # the jump's own chords, start to node to end, and its arc on them
            start, node, end = sol.arc.points
            ends = np.stack([start, end])
            d = sol.arc.chord_position(w[:, 0] * sol.length)[:, None]
        else:
            ends = np.empty((2, 3))
            ks.evaluate(span.seg.a, np.ascontiguousarray(np.stack([sol.y0[:2], sol.y1[:2]])), ends)
            node = (self.nodes[np.argmin(np.linalg.norm(self.nodes - ends.mean(axis=0), axis=1))] if len(self.nodes)
                    else None)
            d = None
        if node is not None:
            first, second = np.linalg.norm(node - ends[0]), np.linalg.norm(ends[1] - node)
            if first + second <= 2.0 * max(np.linalg.norm(ends[1] - ends[0]), 1e-300) and first > 0 and second > 0:
                d = w * (first + second) if d is None else d
                chords = np.stack([(node - ends[0]) / first, (ends[1] - node) / second])
                side = (d[:, 0] > first).astype(np.int64)
                return (np.where(d <= first, ends[0] + (node - ends[0]) * (d / first),
                                 node + (ends[1] - node) * ((d - first) / second)), side, chords,
                        np.abs(d[:, 0] - first), node)
        straight = span.seg.normal / np.linalg.norm(span.seg.normal)
        return (ends[0] * (1 - w) + ends[1] * w, np.zeros(len(w), dtype=np.int64), np.stack([straight, straight]),
                np.full(len(w), np.inf), None)
