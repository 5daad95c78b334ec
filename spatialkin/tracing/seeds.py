"""Start points on every component of an intersection.

One surface, P, is kept parametrised; the other, Q, is read through its implicit function f_Q. The
intersection is the zero level set of g = f_Q o P on P's parameter domain, and Morse theory says where to
look: each component of a level set is met by the gradient flow of g leaving the lower end of its edge of
the Reeb graph, a minimum or a saddle (and, going down, by the flow leaving the upper end, a maximum or a
saddle). So from every critical point of g with g < 0 we follow the ascending flow along both senses of
the Hessian's positive eigen-direction, from every one with g > 0 the descending flow, and stop where g
changes sign; a component that reaches the edge of a trimmed surface is also found by scanning the edges.

Critical points come from closed forms where they exist (Q a sphere: the foot points of its centre on a
torus or a sphere; Q a plane: the points of a torus or sphere whose normal is the plane's), otherwise from
Newton started on a grid over P's domain. A critical point on the level itself is a contact point (an
extremum) or a node where branches cross (a saddle).

References
----------
../shared/reference/ssi-notes.md: the critical radii of torus ∩ sphere are the distances from the sphere
centre to its foot points on the torus; small loops are missed by grids coarser than the loop.
"""
import math

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp

from ..kernels import flow as kf
from ..kernels import level as kl
from ..kernels import surfaces as ks
from .segments import BudgetExceeded, budgeted, finite_bounds
from .start import parameter_units

#: Grid of Newton starts for the generic critical-point search (per parameter direction).
GRID = 40
#: Critical points closer than this (relative to the scale) are one.
MERGE_RADIUS = 1e-6
#: Offset (relative to the scene scale, in space) from a critical point at which its gradient flow starts.
FLOW_OFFSET = 1e-4
#: Relative tolerance of the gradient flow integration (only a point near the level is needed).
FLOW_RTOL = 1e-8
#: The flow slows where |grad_S g| falls below FLOW_SATURATION, and stops (without a seed) below
#: FLOW_MIN_GRADIENT: it ran into an extremum that does not reach the level.
FLOW_SATURATION = 1e-3
FLOW_MIN_GRADIENT = 1e-4
#: Longest gradient flow, in turns around P (2 pi times its size).
FLOW_TURNS = 4
#: A gradient flow is cut off after this many right-hand-side evaluations ...
FLOW_MAX_EVALUATIONS = 5_000
#: ... or where P's relative area element falls below this (beside an apex).
FLOW_APEX_GUARD = 1e-3
#: Samples along each edge of a trimmed surface.
EDGE_SAMPLES = 400
#: Eigenvalues of the Hessian below this (relative to the largest) count as zero (degenerate directions).
EIGEN_RATIO = 1e-6
#: Seeds on the arms of a node sit this far (relative to the scene scale) from it: well beyond a jump.
NODE_OFFSET = 2e-2
#: Parameter distance from an apex of the rings sampled for seeds near it.
APEX_RING = 2e-2
#: Charts of a sphere kept away from its poles in the grid search: |latitude| below this.
SPHERE_LATITUDE = 1.25


def roles(a, b):
    """(P, Q, swapped): P parametrised, Q implicit. Best is a pair with closed-form critical points (P a
    torus or sphere, Q a sphere or plane); next, a compact P (its domain is finite)."""
    def score(p, q):
        closed = int(p.data[ks.KIND]) in (ks.TORUS, ks.SPHERE) and int(q.data[ks.KIND]) in (ks.SPHERE, ks.PLANE)
        return 2 * closed + p.compact
    if score(b, a) > score(a, b):
        return b, a, True
    return a, b, False


def closed_form_critical(p, q):
    """Critical parameters (K, 2) of g on P in closed form, or None where none is known."""
    kp, kq = int(p.data[ks.KIND]), int(q.data[ks.KIND])
    if kp not in (ks.TORUS, ks.SPHERE) or kq not in (ks.SPHERE, ks.PLANE):
        return None
    rot = p.frame.rotation
    if kq == ks.SPHERE:
        w = rot.T @ (q.frame.origin - p.frame.origin)      # the source point in P's frame
        is_point = True
    else:
        w = rot.T @ q.frame.rotation[:, 2]                  # the plane normal in P's frame
        is_point = False
    if kp == ks.SPHERE:
        if np.linalg.norm(w) == 0.0:
            return np.array([[0.0, 0.0]])                   # concentric: g is constant
        d = w / np.linalg.norm(w)
        uv = [[math.atan2(d[1], d[0]), math.asin(np.clip(d[2], -1, 1))]]
        uv.append([uv[0][0] + math.pi, -uv[0][1]])
        return np.array(uv)
    big = p.major_radius
    theta = math.atan2(w[1], w[0])
    out = []
    for u in (theta, theta + math.pi):
        er = np.array([math.cos(u), math.sin(u), 0.0])
        x = w - big * er if is_point else w
        v = math.atan2(x[2], float(x @ er))
        out += [[u, v], [u, v + math.pi]]
    return np.array(out)


def parameter_box(p, q):
    """(lo (2,), hi (2,)) of P's domain to search, bounded by Q's extent where P is not."""
    kind = int(p.data[ks.KIND])
    if kind == ks.TORUS:
        return np.array([-math.pi, -math.pi]), np.array([math.pi, math.pi])
    if kind == ks.SPHERE:
        return np.array([-math.pi, -SPHERE_LATITUDE]), np.array([math.pi, SPHERE_LATITUDE])
    lo = np.array([p.u_range[0], p.v_range[0]], dtype=float)
    hi = np.array([p.u_range[1], p.v_range[1]], dtype=float)
    if kind != ks.PLANE:                 # u of a cylinder or cone is an angle
        lo[0], hi[0] = -math.pi, math.pi
    if not np.all(np.isfinite(np.r_[lo, hi])):
        if not q.compact:
            raise ValueError(f"intersect needs a bounded domain: give {type(p).__name__} a v_range "
                             "(and a Plane u_range and v_range) when the other surface is unbounded too")
        centre = p.frame.to_local(q.frame.origin)
        reach = 1.05 * q.size
        if kind == ks.PLANE:
            box_lo, box_hi = centre[:2] - reach, centre[:2] + reach
            lo = np.where(np.isfinite(lo), lo, box_lo)
            hi = np.where(np.isfinite(hi), hi, box_hi)
        else:
            # cylinder and cone: v is the axial coordinate
            lo[1] = lo[1] if np.isfinite(lo[1]) else centre[2] - reach
            hi[1] = hi[1] if np.isfinite(hi[1]) else centre[2] + reach
    return lo, hi


def param_steps(p, uv, scale):
    """Parameter increments (2,) that move P's point by `scale` in space at uv (the scene's length scale
    may be far below the surface's own)."""
    d = p.derivatives(*uv)
    lengths = np.array([np.linalg.norm(d[1]), np.linalg.norm(d[2])])
    fallback = parameter_units(p.data, scale)
    return np.where(lengths > 1e-12 * fallback, scale / np.maximum(lengths, 1e-300), fallback)


def grid_critical(p, q, lo, hi, param_scale):
    """Critical parameters of g on P by Newton from a GRID x GRID lattice over [lo, hi]."""
    cells = [(np.arange(GRID) + 0.5) / GRID * (hi[i] - lo[i]) + lo[i] for i in range(2)]
    uu, vv = np.meshgrid(*cells, indexing="ij")
    starts = np.ascontiguousarray(np.stack([uu.ravel(), vv.ravel()], axis=1))
    out = np.empty_like(starts)
    status = np.empty(len(starts), dtype=np.int64)
    kl.critical_newton(p.data, q.data, starts, param_scale, 40, out, status)
    inside = (status == 1) & np.all(out >= lo - 1e-9, axis=1) & np.all(out <= hi + 1e-9, axis=1)
    return out[inside]


def critical_points(p, q, scale):
    """Critical points of g on P: list of (uv (2,), value, eigenvalues (2,), eigenvectors (2, 2))."""
    uv = closed_form_critical(p, q)
    kind = int(p.data[ks.KIND])
    param_scale = parameter_units(p.data, scale)
    if uv is None:
        lo, hi = parameter_box(p, q)
        found = [grid_critical(p, q, lo, hi, param_scale)]
        if kind == ks.SPHERE:     # a second chart, its poles on the first one's equator
            turned = p.with_frame(type(p.frame)(p.frame.origin, p.frame.rotation @ np.array(
                [[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])))
            extra = grid_critical(turned, q, lo, hi, param_scale)
            found.append(p.parameters(turned.point(extra[:, 0], extra[:, 1])) if len(extra) else extra)
        uv = np.vstack([f.reshape(-1, 2) for f in found])
    pts = p.point(uv[:, 0], uv[:, 1]) if len(uv) else np.empty((0, 3))
    result, kept = [], []
    for k in range(len(uv)):
        if any(np.linalg.norm(pts[k] - pts[j]) <= MERGE_RADIUS * scale for j in kept):
            continue
        kept.append(k)
        hess = np.empty((2, 2))
        h = kl.FD_STEP_HESS * param_steps(p, uv[k], scale)
        kl.level_hessian(p.data, q.data, uv[k, 0], uv[k, 1], h, hess)
        d = p.derivatives(*uv[k])
        metric = np.array([[d[1] @ d[1], d[1] @ d[2]], [d[1] @ d[2], d[2] @ d[2]]])
        if np.linalg.det(metric) <= 1e-14 * np.trace(metric) ** 2:
            continue                                 # a singular point of the parametrisation
        lam, vec = scipy.linalg.eigh(hess, metric)
        value = kl.level_value(p.data, q.data, uv[k, 0], uv[k, 1])
        result.append((uv[k].copy(), float(value), lam, vec))
    return result


def flow_to_level(p, q, uv, direction, sigma, scale):
    """Follow the unit-speed gradient flow of g (sigma = +1 up, -1 down) from uv + offset * direction
    until g = 0; returns the point (3,) near the level, or None if the flow ends first."""
    x0 = np.asarray(uv, dtype=float)
    if direction is not None:            # a step of FLOW_OFFSET * scale in space
        d = p.derivatives(*x0)
        length = np.linalg.norm(d[1] * direction[0] + d[2] * direction[1])
        x0 = x0 + FLOW_OFFSET * scale * direction / max(length, 1e-300)
    h = kl.FD_STEP_GRAD * param_steps(p, x0, scale)

    def level(t, x, *_):
        return kl.level_value(p.data, q.data, x[0], x[1])
    level.terminal = True

    def stalled(t, x, *_):
        return kl.surface_gradient_norm(p.data, q.data, x[0], x[1], h) - FLOW_MIN_GRADIENT
    stalled.terminal, stalled.direction = True, -1
    events = [level, stalled]
    if apex_lines(p):
        def apex(t, x, *_):
            return kl.relative_area_at(p.data, x[0], x[1]) - FLOW_APEX_GUARD
        apex.terminal, apex.direction = True, -1
        events.append(apex)
    for _, _, idx, bound, lower in finite_bounds(p.data):
        def edge(t, x, *_, idx=idx, bound=bound, lower=lower):
            return x[idx] - bound if lower else bound - x[idx]
        edge.terminal, edge.direction = True, -1
        events.append(edge)
    g0 = level(0.0, x0)
    if g0 == 0.0:
        return p.point(*x0)
    t_bound = FLOW_TURNS * 2 * math.pi * max(p.size, scale)
    lo, hi = np.full(2, -np.inf), np.full(2, np.inf)
    for _, _, idx, bound, lower in finite_bounds(p.data):
        if lower:
            lo[idx] = max(lo[idx], bound)
        else:
            hi[idx] = min(hi[idx], bound)
    hit = np.empty(2)
    status = kf.flow_to_level(np.ascontiguousarray(x0), p.data, q.data, float(sigma), h, FLOW_SATURATION, t_bound,
                              np.inf, FLOW_RTOL, FLOW_RTOL, FLOW_MAX_EVALUATIONS, FLOW_MIN_GRADIENT,
                              bool(apex_lines(p)), FLOW_APEX_GUARD, lo, hi, hit)
    if status == kf.HIT:
        return p.point(*hit)
    if status == kf.NO_HIT:
        return None
    # the flow stalls, nears an apex or an edge: solve_ivp and its event functions decide
    try:
        res = solve_ivp(budgeted(kl.gradient_flow_rhs, FLOW_MAX_EVALUATIONS), (0.0, FLOW_TURNS * 2 * math.pi * max(p.size, scale)), x0,
                        method="RK45", rtol=FLOW_RTOL, atol=FLOW_RTOL, events=events,
                        args=(p.data, q.data, float(sigma), h, FLOW_SATURATION))
    except BudgetExceeded:       # bounded time: a flow stalling beside an apex is cut off
        return None
    if res.status == 1 and res.t_events[0].size:
        return p.point(*res.y_events[0][0])
    return None


def edges(p):
    """Sampled edges of a trimmed P: list of (uv (n, 2), index of the fixed parameter, its value)."""
    (ulo, uhi), (vlo, vhi) = p.u_range, p.v_range
    kind = int(p.data[ks.KIND])
    out = []
    if kind == ks.PLANE and np.all(np.isfinite([ulo, uhi, vlo, vhi])):
        t = np.linspace(vlo, vhi, EDGE_SAMPLES)
        out += [(np.column_stack([np.full_like(t, u), t]), 0, u) for u in (ulo, uhi)]
    if np.all(np.isfinite([vlo, vhi])):
        lo, hi = (ulo, uhi) if kind == ks.PLANE else (-math.pi, math.pi)
        if np.all(np.isfinite([lo, hi])):
            t = np.linspace(lo, hi, EDGE_SAMPLES)
            out += [(np.column_stack([t, np.full_like(t, v)]), 1, v) for v in (vlo, vhi)]
    return out


def edge_seeds(p, q, scale):
    """Seeds from the edges of a trimmed P: the points where the level meets an edge (sign changes of g
    along it), and gradient flows from the edge's local extrema of g (for components inside that touch
    no edge, as the interior critical points do for closed surfaces)."""
    seeds = []
    for uv, fixed, value in edges(p):
        g = np.array([kl.level_value(p.data, q.data, x, y) for x, y in uv])
        for i in np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) <= 0)[0]:
            w = g[i] / (g[i] - g[i + 1]) if g[i] != g[i + 1] else 0.0
            seeds.append(("edge", p.point(*((1 - w) * uv[i] + w * uv[i + 1])), fixed, value))
        interior = np.arange(1, len(g) - 1)
        extrema = interior[((g[interior] - g[interior - 1]) * (g[interior + 1] - g[interior]) <= 0)]
        lower = (p.u_range, p.v_range)[fixed][0]
        nudge = np.zeros(2)                      # flows start just inside the edge
        nudge[fixed] = (1.0 if value == lower else -1.0) * FLOW_OFFSET * param_steps(p, uv[0], scale)[fixed]
        for i in np.r_[extrema, 0, len(g) - 1]:
            if g[i] != 0:
                hit = flow_to_level(p, q, uv[i] + nudge, None, -np.sign(g[i]), scale)
                if hit is not None:
                    seeds.append(("flow", hit, None, None))
    return seeds


def apex_lines(p):
    """Parameter lines (fixed index, value) along which P's parametrisation collapses to a point: the axis
    points of a horn or spindle torus (R + r cos v = 0), the apex of a cone (v = 0)."""
    kind = int(p.data[ks.KIND])
    if kind == ks.TORUS and p.minor_radius >= p.major_radius:
        v = math.acos(-p.major_radius / p.minor_radius)
        return [v, -v] if v < math.pi else [v]          # a horn torus has one axis point
    if kind == ks.CONE:
        return [0.0]
    return []


def apex_seeds(p, q, scale, level_tol):
    """Seeds near an apex of P that lies on Q: there the critical points of g sit on the degenerate line
    and are not found; the level is sampled on small parameter circles around the apex instead. An apex
    on Q with no level crossing around it is an isolated point of the intersection.

    Returns (seeds, isolated points)."""
    out, isolated = [], []
    for v_apex in apex_lines(p):
        if abs(kl.level_value(p.data, q.data, 0.0, v_apex)) > max(level_tol, 1e-9 * scale):
            continue
        u = np.linspace(-math.pi, math.pi, EDGE_SAMPLES)
        found_any = False
        for dv in (-APEX_RING, APEX_RING):
            ring = np.column_stack([u, np.full_like(u, v_apex + dv)])
            g = np.array([kl.level_value(p.data, q.data, x, y) for x, y in ring])
            crossings = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) <= 0)[0]
            for i in crossings:
                w = g[i] / (g[i] - g[i + 1]) if g[i] != g[i + 1] else 0.0
                out.append(p.point(*((1 - w) * ring[i] + w * ring[i + 1])))
            found_any = found_any or len(crossings) > 0
        if not found_any:
            isolated.append(p.point(0.0, v_apex))
    return out, isolated


def find_seeds(a, b, scale, level_tol):
    """Start points on the intersection of a and b.

    Returns
    -------
    seeds : list of ndarray (3,)
        Points near the curve, at least one on every component (more are harmless).
    contacts : list of ndarray (3,)
        Isolated points where the surfaces touch (an extremum of g on the level).
    nodes : list of ndarray (3,)
        Points where branches cross (a saddle of g on the level); seeds near them are included.
    edge_points : list of (point (3,), fixed, value)
        Points near where the level meets an edge of P, parameter `fixed` (0 u, 1 v) of P held at value.
    """
    p, q, _ = roles(a, b)
    seeds, contacts, nodes = [], [], []
    critical = critical_points(p, q, scale)
    values = np.array([c[1] for c in critical])
    if p.compact and len(values) and (values.min() > level_tol or values.max() < -level_tol):
        # g keeps one sign on a closed surface: no intersection, but for an apex of P touching Q
        return seeds, apex_seeds(p, q, scale, level_tol)[1], nodes, []
    for uv, value, lam, vec in critical:
        big = max(abs(lam[0]), abs(lam[1]), 1e-300)
        on_level = abs(value) <= level_tol
        if on_level:
            nonzero = np.abs(lam) > EIGEN_RATIO * big
            if np.all(nonzero) and lam[0] * lam[1] > 0:
                contacts.append(p.point(*uv))
                continue
            if np.all(nonzero):   # a node: start on each of the four arms, along the asymptotic directions
                nodes.append(p.point(*uv))
                ratio = math.sqrt(-lam[0] / lam[1])
                steps = param_steps(p, uv, scale)
                for d in (vec[:, 0] + ratio * vec[:, 1], vec[:, 0] - ratio * vec[:, 1]):
                    d = d / np.linalg.norm(d / steps)           # a step of NODE_OFFSET * scale in space
                    for sense in (1.0, -1.0):
                        seeds.append(p.point(*(uv + NODE_OFFSET * sense * d)))
            continue
        sigma = 1.0 if value < 0 else -1.0
        for i in range(2):
            if sigma * lam[i] > EIGEN_RATIO * big:
                for sense in (1.0, -1.0):
                    hit = flow_to_level(p, q, uv, sense * vec[:, i], sigma, scale)
                    if hit is not None:
                        seeds.append(hit)
    near_apex, apex_points = apex_seeds(p, q, scale, level_tol)
    seeds += near_apex
    contacts += apex_points
    edge_points = []
    for kind, point, fixed, value in edge_seeds(p, q, scale):
        if kind == "flow":
            seeds.append(point)
        else:
            edge_points.append((point, fixed, value))
    return seeds, contacts, nodes, edge_points
