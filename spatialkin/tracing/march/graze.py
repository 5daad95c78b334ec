"""Components that graze a trim edge: traced again past the edge and cut by the clipper.

The tracer ends a branch where the curve meets a trim edge of a surface (the edge events of
spatialkin.kernels.march.branch_ode). A curve that only touches the edge, from inside (a face whose rim it touches at a
vertex it passes through) or from outside (the faces meet in that one point), dips across the edge by round-off:
the branch ends there and a sliver of the curve is lost, or a tiny arc comes back where there is a point. Those
show as ends on edges closer to each other than GAP x scale (two pieces of one curve, or both ends of a tiny
arc). Each such component is traced again on the surfaces with their length trims widened by WIDEN x scale (a
cone's never across its apex), and cut at the true trims by spatialkin.tracing.curve.clip (Lipschitz-bounded crossings,
touches from inside kept whole, from outside a point).
"""
import math
import time

import numpy as np

from ...kernels.geometry import surfaces as ks
from ...geometry.trims import HEIGHT, level_groups
from ..curve.clip import clip_curve
from ..curve.result import TracingError
from ..curve.status import BOUNDARY
from .trace import trace_from

#: Ends of open curves on trim edges closer than this (relative to the scale) are the two sides of a graze.
GAP = 1e-3
#: The length trims are widened by this (relative to the scale) for the second trace.
WIDEN = 1e-2


class Face:
    """A surface's frame and all its trims as clip reads them (its region, and its length trims as HEIGHT limits
    on its local axes)."""

    def __init__(self, surface):
        self.frame = surface.frame
        self.region = surface.region + length_limits(surface)


def length_limits(surface):
    """The groups of limits of the trims the tracer watches (ranges of a length along a local axis)."""
    groups = ()
    for j, (axis, bounds) in enumerate(zip(surface.traits.parameter_axes, surface.bounds)):
        if axis is not None:
            groups += level_groups((f"{'uv'[j]}_min", f"{'uv'[j]}_max"), HEIGHT, bounds, axis)
    return groups


def widened(surface, margin):
    """A copy of the surface with its length trims widened by margin (a cone's not across its apex)."""
    data = surface.data.copy()
    cone = surface.traits.name == "cone"
    for j in range(4):
        bound = data[ks.BOUNDS + j]
        if not math.isfinite(bound):
            continue
        moved = bound - margin if j % 2 == 0 else bound + margin
        if cone and j >= 2 and bound != 0.0 and (moved > 0.0) != (bound > 0.0):
            moved = 0.5 * bound                              # short of the apex
        data[ks.BOUNDS + j] = moved
    return surface.with_data(data)


def across_edges(a, b, point, y, settings):
    """(the component through point (3,) with parameters y (4,) traced on the surfaces with their length trims
    widened, its pieces inside the true trims), or None where that trace fails. Also the answer for a start on an
    edge from which the curve leaves the faces both ways (they meet in that point, or the start sits beside a
    touch)."""
    margin = WIDEN * settings.scale
    try:
        whole = trace_from(widened(a, margin), widened(b, margin), point, y, settings, time.perf_counter())
    except TracingError:
        return None
    whole.sol.surfaces = (a, b)
    pieces = clip_curve(Face(a), Face(b), whole, settings.scale)
    for piece in pieces:
        piece.sol.surfaces = (a, b)
    return whole, pieces


def grazing_groups(curves, scale):
    """Sets of indices of the open curves whose ends on trim edges lie within GAP x scale of each other (a curve
    with itself when its own two ends do)."""
    ends = [(k, point) for k, c in enumerate(curves) if not c.closed and c.status == BOUNDARY and c.length > 0
            for point in (c.points[0], c.points[-1])]
    parent = list(range(len(curves)))

    def root(k):
        while parent[k] != k:
            k = parent[k]
        return k
    marked = set()
    for i, (k, p) in enumerate(ends):
        for m, q in ends[i + 1:]:
            if float(np.linalg.norm(p - q)) <= GAP * scale:
                parent[root(k)] = root(m)
                marked.update((k, m))
    groups = {}
    for k in marked:
        groups.setdefault(root(k), set()).add(k)
    return list(groups.values())


def rejoined(a, b, curves, settings, on):
    """The CurveResults with every grazing group replaced by its component traced past the edges and cut at the
    true trims: the curves that lie on that trace (on(curve, trace): every point within sk.intersect's radius; the
    group's and the other open arcs, pieces of the same component) are dropped, the others (another component that
    came near: two arcs leaving beside a node) kept; the group kept whole where that trace fails."""
    groups = grazing_groups(curves, settings.scale)
    if not groups:
        return curves
    new, dropped = [], set()
    for group in groups:
        first = curves[min(group)]
        mid = len(first.points) // 2
        found = across_edges(a, b, first.points[mid].copy(), first.params[mid].copy(), settings)
        if found is None:
            continue
        whole, pieces = found
        new += pieces
        dropped |= {k for k, c in enumerate(curves) if k in group or c.status == BOUNDARY
                    if k not in dropped and on(c, whole)}
    return new + [c for k, c in enumerate(curves) if k not in dropped]
