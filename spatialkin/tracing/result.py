"""sk.Curve: one traced component of an intersection, with dense evaluation corrected onto both surfaces."""
import numpy as np
from scipy.spatial import cKDTree

from ..kernels import curve as kc
from ..kernels import surfaces as ks
from .bspline import fit as fit_spline
from .curvature import curvature_vectors
from .segments import NEWTON_MAX_ITER, area_flag
from .traits import traits

#: Interior sample points closer than this (relative to the curve scale) to the closing point are dropped,
#: so that a closed curve has no near-duplicate of its first point before the exact copy at its end.
DUPLICATE_SPACING = 1e-9
#: Inside a jump across a node or an apex, a Newton-corrected point farther than this fraction of the jump from
#: the interpolated one has strayed (to another branch, or off through a degenerate chart): the interpolated
#: point on the chords through the node is used instead (within about jump^2 x curvature of the branches).
JUMP_STRAY = 0.5
#: ... or farther than this fraction of its distance from the node passed (it went to the other branch).
NODE_STRAY = 0.2
#: ... and within this fraction of the jump from the node, the branch is interpolated (see Curve._jump_points).
NODE_ANCHOR = 0.05
#: ... unless a parametrisation degenerates there (relative area element below this at the anchors).
ANCHOR_APEX_CLEAR = 1e-2
#: Newton steps in arc length refining the nearest samples in Curve.closest, and how many are refined.
CLOSEST_NEWTON_STEPS = 4
CLOSEST_CANDIDATES = 6


class TracingError(RuntimeError):
    """Tracing could not start or go on; ``where`` is the point (3,) or None, ``status`` a short code."""

    def __init__(self, message, where=None, status="failed"):
        super().__init__(message)
        self.where = where
        self.status = status


class Span:
    """A piece of the dense output: global s in [lo, hi] maps to segment time t = shift + flip * s."""

    __slots__ = ("lo", "hi", "flip", "shift", "seg")

    def __init__(self, lo, hi, flip, shift, seg):
        self.lo, self.hi, self.flip, self.shift, self.seg = lo, hi, flip, shift, seg

    def states(self, s):
        return self.seg.sol(self.shift + self.flip * s)


class Curve:
    """One connected component of the intersection of two surfaces, parametrised by arc length.

    Attributes
    ----------
    points : ndarray (N, 3)
        Points on the curve (solver steps, each corrected onto both surfaces by Newton).
    s : ndarray (N,)
        Arc length at each point, from 0 to ``length``, increasing.
    params : ndarray (N, 4)
        (u1, v1, u2, v2) of each point in the charts of surface a and b (u continuous, not wrapped).
    closed : bool
        True for a closed loop: the last point is the first (exactly), ``length`` is the period.
    length : float
        Arc length of the curve.
    status : str
        'closed', or why an open curve ends: 'singular', 'boundary', 'max_length', 'contact' (a single point
        where the surfaces touch).
    message : str
        A sentence on how it ended (both ends for an open curve).
    max_distance : float
        Largest measured distance (exact distance functions) of the returned points and of dense
        evaluations midway between them, to either surface.
    nfev : int
        Right-hand-side evaluations spent by solve_ivp.
    wall_time : float
        Seconds spent tracing this curve.
    nodes : ndarray (K, 3)
        Singular points the curve passed straight through: nodes where branches cross (each branch is then
        followed on through the node, so a figure-eight is one closed curve passing its node twice), and
        apexes of a spindle or horn torus or a cone.
    tolerance : float
        The accuracy asked for, as an absolute length: tol times the scene scale (the smaller surface
        size), or the round-off floor of the coordinates (64 ulps of their magnitude) where that is larger.
    solver_gap : ndarray (M,)
        |M1 - M2| of the solver's own states at its steps, before the Newton correction: how far plain
        integration (with the pull-back) strays; a diagnostic of drift.
    """

    def __init__(self, surfaces, points, s, params, closed, length, status, message, spans, gap_tol,
                 nfev=0, wall_time=0.0):
        self.surfaces = surfaces
        self.points = points
        self.s = s
        self.params = params
        self.closed = bool(closed)
        self.length = float(length)
        self.status = status
        self.message = message
        self.nfev = int(nfev)
        self.wall_time = float(wall_time)
        self.solver_gap = np.zeros(0)
        self.nodes = np.empty((0, 3))
        self.tolerance = gap_tol
        self._spans = spans
        self._gap_tol = gap_tol
        self._lo = np.array([sp.lo for sp in spans])
        self._grid = None
        self.max_distance = self._measure()

    # --- dense evaluation -------------------------------------------------------------------------
    def _locate(self, s):
        s = np.asarray(s, dtype=float)
        if not np.all(np.isfinite(s)):
            raise ValueError("s must be finite")
        if self.closed and self.length > 0:
            s = np.mod(s, self.length)
        elif np.any((s < -1e-12 * max(1.0, self.length)) | (s > self.length * (1 + 1e-12) + 1e-300)):
            raise ValueError(f"s must lie in [0, {self.length:.12g}] for this open curve")
        idx = np.clip(np.searchsorted(self._lo, s, side="right") - 1, 0, len(self._spans) - 1)
        return s, idx

    def _span_states(self, s):
        """(s wrapped, [(mask, span, solver states (m, 4)) per span hit]) for the flat arc lengths s."""
        s, idx = self._locate(np.ravel(s))
        if len(self._spans) == 1:
            return s, [(slice(None), self._spans[0], np.ascontiguousarray(self._spans[0].states(s).T))]
        pieces = []
        for k in np.unique(idx):
            mask = idx == k
            pieces.append((mask, self._spans[k], np.ascontiguousarray(self._spans[k].states(s[mask]).T)))
        return s, pieces

    def _evaluate(self, s, with_params=True):
        """Corrected states, points and tangents at s (flattened); params is None unless with_params."""
        s, pieces = self._span_states(s)
        points = np.empty((s.size, 3))
        tangents = np.empty((s.size, 3))
        status = np.empty(s.size, dtype=np.int64)
        params = np.empty((s.size, 4)) if with_params else None
        for mask, span, y in pieces:
            p, t, st = points[mask], tangents[mask], status[mask]
            if np.any(span.seg.normal):   # across a node or an apex
                self._jump_points(span, s[mask], y, p, t, st)
            else:
                kc.project_many(y, span.seg.a, span.seg.b, span.seg.normal, self._gap_tol, NEWTON_MAX_ITER, p, t, st)
            points[mask], tangents[mask], status[mask] = p, t * span.flip * span.seg.sign, st
            if with_params:
                params[mask] = user_params(self.surfaces, y, p, span.seg.a, span.seg.b)
        return s, points, tangents, params

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
        self._project_sides(y, a, b, side, chords, p, t, st)
        moved = np.linalg.norm(p - guess, axis=1)
        stray = (st < 0) | (moved > JUMP_STRAY * (span.hi - span.lo)) | (moved > NODE_STRAY * near)
        p[stray] = guess[stray]
        t[stray] = chords[side[stray]]
        anchor = NODE_ANCHOR * (span.hi - span.lo)
        close = near < anchor
        if node is not None and close.any():
            flags = (area_flag(a), area_flag(b))
            for half in np.unique(side[close]):
                rows = close & (side == half)
                sign = 1.0 if half else -1.0
                at = node + sign * chords[half] * np.array([[anchor], [2.0 * anchor]])
                ya = np.repeat(y[rows][:1], 2, axis=0)
                set_states(ya, at, a, b)
                pa, ta, sa = np.empty((2, 3)), np.empty((2, 3)), np.empty(2, np.int64)
                kc.project_many(ya, a, b, chords[half], self._gap_tol, NEWTON_MAX_ITER, pa, ta, sa)
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

    def _project_sides(self, y, a, b, side, chords, p, t, st):
        """Newton in the plane normal to each side's chord (rows of side 0 and 1), in place."""
        for half in np.unique(side):
            rows = side == half
            n = int(rows.sum())
            yh, ph, th, sh = y[rows], np.empty((n, 3)), np.empty((n, 3)), np.empty(n, np.int64)
            kc.project_many(yh, a, b, chords[half], self._gap_tol, NEWTON_MAX_ITER, ph, th, sh)
            y[rows], p[rows], t[rows], st[rows] = yh, ph, th, sh

    def _jump_chords(self, span, s):
        """(points (M, 3), side (M,) in {0, 1}, unit chord directions (2, 3), distances (M,) of the points from the
        node (inf without one), the node (3,) or None) at arc lengths s of a jump span: on
        the chords from its start to the node (or apex) passed and on to its end (one straight chord where no
        node is near): the curve's two branches there are nearly straight, whatever the charts do at the node."""
        sol = span.seg.sol
        ends = np.empty((2, 3))
        ks.evaluate(span.seg.a, np.ascontiguousarray(np.stack([sol.y0[:2], sol.y1[:2]])), ends)
        w = np.clip((span.shift + span.flip * np.asarray(s, dtype=float)) / sol.length, 0.0, 1.0)[:, None]
        straight = span.seg.normal / np.linalg.norm(span.seg.normal)
        if len(self.nodes):
            node = self.nodes[np.argmin(np.linalg.norm(self.nodes - ends.mean(axis=0), axis=1))]
            first, second = np.linalg.norm(node - ends[0]), np.linalg.norm(ends[1] - node)
            if first + second <= 2.0 * max(np.linalg.norm(ends[1] - ends[0]), 1e-300) and first > 0 and second > 0:
                d = w * (first + second)
                chords = np.stack([(node - ends[0]) / first, (ends[1] - node) / second])
                side = (d[:, 0] > first).astype(np.int64)
                return (np.where(d <= first, ends[0] + (node - ends[0]) * (d / first),
                                 node + (ends[1] - node) * ((d - first) / second)), side, chords,
                        np.abs(d[:, 0] - first), node)
        return (ends[0] * (1 - w) + ends[1] * w, np.zeros(len(w), dtype=np.int64), np.stack([straight, straight]),
                np.full(len(w), np.inf), None)

    def __call__(self, s):
        """Points (..., 3) on the curve at arc lengths s (...,), corrected onto both surfaces."""
        shape = np.shape(s)
        if self.length == 0:
            return np.broadcast_to(self.points[0], shape + (3,)).copy()
        _, points, _, _ = self._evaluate(s, with_params=False)
        return points.reshape(shape + (3,))

    def tangent(self, s):
        """Unit tangents (..., 3) at s, pointing towards increasing s."""
        shape = np.shape(s)
        _, _, tangents, _ = self._evaluate(s, with_params=False)
        return tangents.reshape(shape + (3,))

    def parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s (u wrapped to (-pi, pi] where a sphere had to be re-charted)."""
        shape = np.shape(s)
        _, _, _, params = self._evaluate(s)
        return params.reshape(shape + (4,))

    def predicted_parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s from the solver's dense output alone, without the Newton correction:
        within the solver's tolerance of the curve, a cheap start for Newton (a sphere's (u, v) are those of
        the point on surface a, as in parameters())."""
        shape = np.shape(s)
        if self.length == 0:
            return np.broadcast_to(self.params[0], shape + (4,)).copy()
        s, pieces = self._span_states(s)
        params = np.empty((s.size, 4))
        for mask, span, y in pieces:
            on_a = np.empty((len(y), 3))
            ks.evaluate(span.seg.a, np.ascontiguousarray(y[:, :2]), on_a)
            params[mask] = user_params(self.surfaces, y, on_a, span.seg.a, span.seg.b)
        return params.reshape(shape + (4,))

    def sample(self, n):
        """n points evenly spaced in arc length (for a closed curve the last equals the first)."""
        return self(np.linspace(0.0, self.length, int(n)))

    def closest(self, points):
        """Arc length (...,) of the curve point nearest to each point (..., 3), and the distance (...,)."""
        pts = np.asarray(points, dtype=float)
        flat = pts.reshape(-1, 3)
        if self.length == 0:
            return np.zeros(len(flat)).reshape(pts.shape[:-1]), np.linalg.norm(flat - self.points[0], axis=1).reshape(pts.shape[:-1])
        grid, dense = self._closest_grid()
        # refine the few nearest samples (not only the nearest: the curve may pass close to itself)
        k = min(CLOSEST_CANDIDATES, len(grid))
        idx = cKDTree(dense).query(flat, k=k)[1].reshape(len(flat), k)
        cand = grid[idx].ravel()
        s, dist = self._foot_points(np.repeat(flat, k, axis=0), cand, CLOSEST_NEWTON_STEPS)
        best = np.argmin(dist.reshape(-1, k), axis=1)
        s, dist = s.reshape(-1, k)[np.arange(len(flat)), best], dist.reshape(-1, k)[np.arange(len(flat)), best]
        return s.reshape(pts.shape[:-1]), dist.reshape(pts.shape[:-1])

    def near_points(self, points):
        """An upper bound (M,) on the distance of each point (M, 3) to the curve, cheaply: the distance to a
        foot point found by Newton in s from the nearest stored point. Exact for points on or close to the
        curve (within a fraction of a step); use closest() for the true distance of any point."""
        pts = np.asarray(points, dtype=float).reshape(-1, 3)
        if self.length == 0 or len(self.points) < 2:
            return np.linalg.norm(pts - self.points[0], axis=1)
        nearest = cKDTree(self.points).query(pts)[1]
        return self._foot_points(pts, self.s[nearest], CLOSEST_NEWTON_STEPS)[1]

    def _foot_points(self, pts, s, steps):
        """(s, distance) of foot points of pts (M, 3) on the curve by `steps` Newton steps in s from s (M,)."""
        for _ in range(steps):
            _, at, tangent, _ = self._evaluate(s, with_params=False)
            s = s + np.einsum("ij,ij->i", pts - at, tangent)
            s = s if self.closed else np.clip(s, 0.0, self.length)
        s, at, _, _ = self._evaluate(s, with_params=False)
        return s, np.linalg.norm(pts - at, axis=1)

    def _closest_grid(self):
        """Arc lengths and corrected points of the dense grid closest() starts from (computed once: a Curve
        does not change)."""
        if self._grid is None:
            grid = np.linspace(0.0, self.length, max(8 * len(self.points), 64))
            self._grid = (grid, self(grid))
        return self._grid

    def distances(self, points=None):
        """Exact distances (N, 2) of points (default: self.points) to surface a and surface b."""
        pts = self.points if points is None else np.asarray(points, dtype=float)
        return np.stack([surf.distance(pts) for surf in self.surfaces], axis=-1)

    def _measure(self):
        pts = self.points
        if len(self.s) > 1 and self.length > 0:
            pts = np.vstack([pts, self(0.5 * (self.s[1:] + self.s[:-1]))])
        return float(np.max(self.distances(pts))) if len(pts) else 0.0

    def derivatives(self, s):
        """(points, unit tangents C', curvature vectors C'') (..., 3) each at arc lengths s: exact, from the
        corrected points and the two surfaces' implicit functions (NaN at a singular point)."""
        shape = np.shape(s)
        _, points, tangents, _ = self._evaluate(s, with_params=False)
        bend = curvature_vectors(*self.surfaces, points, tangents)
        return tuple(x.reshape(shape + (3,)) for x in (points, tangents, bend))

    def to_bspline(self, tol=1e-8):
        """A C2 quintic B-spline (scipy.interpolate.BSpline, parameter: the arc length s) within tol times the
        scene scale of this curve, measured.

        Built from the exact points, unit tangents and curvature vectors at its knots (quintic Hermite data);
        the knots are refined until the distance between the spline and Newton-corrected points of the curve at
        the same s, measured at nine points inside every span, stays below 0.9 tol x scale. A closed curve gives
        a periodic spline (extrapolate='periodic').

        Parameters
        ----------
        tol : float
            Allowed deviation, relative to the scene scale (the smaller surface size).

        Returns
        -------
        scipy.interpolate.BSpline
            Degree 5, triple interior knots; ``spline.deviation`` is the largest measured distance (length
            unit), ``spline.checked`` how many curve points it was measured against.

        Raises
        ------
        ValueError
            For a non-positive tol, or a curve of length zero (a contact point).
        SplineToleranceError
            If tol lies below the round-off of the curve's points.
        """
        tol = float(tol)
        if not np.isfinite(tol) or tol <= 0:
            raise ValueError(f"tol must be a positive finite number, got {tol!r}")
        if self.length == 0:
            raise ValueError("a curve of length zero (a contact point) has no B-spline")
        from .start import scene_scale       # start imports this module
        return fit_spline(self.derivatives, 0.0, self.length, tol * scene_scale(*self.surfaces),
                          periodic=self.closed)

    def __len__(self):
        return len(self.points)

    def __repr__(self):
        kind = "closed" if self.closed else f"open ({self.status})"
        return (f"Curve({kind}, length={self.length:.6g}, points={len(self.points)}, "
                f"max_distance={self.max_distance:.2e})")


def set_states(y, points, a, b):
    """Rows of the states y (M, 4) moved to the foot parameters of points (M, 3) on the charts a, b (angles kept
    within pi of the old ones); returns y."""
    uv = np.empty((len(points), 2))
    for k, data in enumerate((a, b)):
        ks.inverse(data, np.ascontiguousarray(points), uv)
        d = uv - y[:, 2 * k:2 * k + 2]
        for j, angle in enumerate(traits(data).angular):
            if angle:
                d[:, j] = np.mod(d[:, j] + np.pi, 2.0 * np.pi) - np.pi
        y[:, 2 * k:2 * k + 2] += d
    return y


def user_params(surfaces, y, points, a_chart, b_chart):
    """(u1, v1, u2, v2) in the surfaces' own charts: a re-charted sphere's (u, v) come from the point."""
    out = np.array(y, dtype=float, copy=True)
    for k, (surf, chart) in enumerate(zip(surfaces, (a_chart, b_chart))):
        if chart is not surf.data and not np.array_equal(chart, surf.data):
            uv = np.empty((len(points), 2))
            ks.inverse(surf.data, np.ascontiguousarray(points), uv)
            out[:, 2 * k:2 * k + 2] = uv
    return out


class ExactCurve(Curve):
    """A component known in closed form, evaluated exactly: a circle or a segment along which the two surfaces
    touch (status 'tangent'; the tracer cannot follow it, its normals being parallel all along), or a circle
    about the common axis of two surfaces of revolution (status 'closed').

    Parameters
    ----------
    surfaces : (Surface, Surface)
    circle : (centre (3,), unit axis (3,), radius), or None
    segment : (p0 (3,), p1 (3,)), or None
    tolerance : float
        The accuracy asked for, as an absolute length.
    samples : int
        Stored points.
    """

    def __init__(self, surfaces, circle=None, segment=None, tolerance=0.0, samples=65, status="tangent",
                 message=""):
        if circle is not None:
            centre, axis, radius = (np.asarray(circle[0], dtype=float), np.asarray(circle[1], dtype=float),
                                    float(circle[2]))
            helper = np.eye(3)[np.argmin(np.abs(axis))]
            e1 = np.cross(axis, helper)
            e1 /= np.linalg.norm(e1)
            self._shape = ("circle", centre, e1, np.cross(axis, e1), radius)
            length, closed = 2 * np.pi * radius, True
        else:
            p0, p1 = (np.asarray(x, dtype=float) for x in segment)
            length = float(np.linalg.norm(p1 - p0))
            self._shape = ("segment", p0, (p1 - p0) / max(length, 1e-300))
            closed = False
        self.surfaces = surfaces
        self.closed, self.length = closed, float(length)
        self.status = status
        self.message = message or ("the surfaces touch all along this " + self._shape[0])
        self.nfev, self.wall_time = 0, 0.0
        self.solver_gap = np.zeros(0)
        self.nodes = np.empty((0, 3))
        self.tolerance = tolerance
        self._grid = None
        self.s = np.linspace(0.0, self.length, samples)
        _, self.points, _, self.params = self._evaluate(self.s)
        if closed:
            self.points[-1] = self.points[0]
        self.max_distance = self._measure()

    def _locate(self, s):
        s = np.asarray(s, dtype=float)
        if not np.all(np.isfinite(s)):
            raise ValueError("s must be finite")
        if self.closed:
            return np.mod(s, self.length), None
        if np.any((s < -1e-12 * max(1.0, self.length)) | (s > self.length * (1 + 1e-12) + 1e-300)):
            raise ValueError(f"s must lie in [0, {self.length:.12g}] for this open curve")
        return s, None

    def _evaluate(self, s, with_params=True):
        s, _ = self._locate(np.ravel(s))
        if self._shape[0] == "circle":
            _, centre, e1, e2, radius = self._shape
            angle = s / radius
            c, n = np.cos(angle)[:, None], np.sin(angle)[:, None]
            points = centre + radius * (c * e1 + n * e2)
            tangents = -n * e1 + c * e2
        else:
            _, p0, direction = self._shape
            points = p0 + s[:, None] * direction
            tangents = np.broadcast_to(direction, points.shape).copy()
        params = None
        if with_params:
            params = np.concatenate([surf.parameters(points) for surf in self.surfaces], axis=1)
        return s, points, tangents, params

    def predicted_parameters(self, s):
        return self.parameters(s)

    def derivatives(self, s):
        """(points, unit tangents, curvature vectors) (..., 3) at s, in closed form."""
        shape = np.shape(s)
        _, points, tangents, _ = self._evaluate(s, with_params=False)
        if self._shape[0] == "circle":
            bend = -(points - self._shape[1]) / self._shape[4] ** 2
        else:
            bend = np.zeros_like(points)
        return tuple(x.reshape(shape + (3,)) for x in (points, tangents, bend))
