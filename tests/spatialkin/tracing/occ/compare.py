"""Compare spatialkin's curves of a case with its truth, and name what differs.

A run is ``sk.intersect(a, b)`` (or (b, a)). Its curves are matched to the truth's components: a curve belongs to
the component all of whose points lie within MATCH_RTOL x scale of it, or to an isolated contact point of the
truth when all its points lie that close to the point (a curve of positive length there is a contact returned as
a curve). Then, per component, its curves are joined where they meet (an end on another curve or on the curve's
own far part, a crossing, two loops touching), measured on spatialkin's dense evaluation ``curve(s)``; the
comparison states:

- every returned point lies on both surfaces: ``surface.distance`` <= DIST_RTOL x scale;
- the number of connected components equals the truth's (curves on no component, components with no curve or
  with curves that do not join up count against it);
- each component's length (the sum of its curves' ``length``) and the total length agree with the truth to
  LEN_RTOL (relative) + LEN_ATOL x scale;
- a closed component has no free end, an open one has its free ends where the truth has them.

``problems(case, order)`` lists what differs as (class, message); the classes name the failure in the test's
xfail markers and in README.md. ``python -m tests.spatialkin.tracing.occ.compare`` prints a table of every case, ``--scripts`` the README's
table of scripts, ``--xfail`` rewrites the XFAIL block of cases.py from a run of every case.
"""
import numpy as np
from scipy.spatial import cKDTree

#: Returned points lie within this x scale of both surfaces (spatialkin promises tol x scale, tol = 1e-10).
DIST_RTOL = 1e-9
#: Length agreement: relative, and absolute x scale.
LEN_RTOL = 1e-7
LEN_ATOL = 1e-9
#: A curve belongs to a truth component (or point) when all its points lie within this x scale of it (capped by a
#: quarter of the smallest distance between two components).
MATCH_RTOL = 1e-4
#: Curves closer than this x scale meet (they are joined); a free end this close to a truth end is at it.
JOIN_RTOL = 1e-6
#: Vertices examined per point (polylines meeting at a node share a vertex).
NEAREST = 8
#: Truth polylines are drawn with chords within this x scale of the curve.
SAG_RTOL = 1e-6

#: (phrase of an exception's message, the short name given to it in a failure class).
RAISES = (("found more than", "interior search unresolved"),
          ("could be neither located on the curve nor traced", "start lost"))

_DRAWN = {}                     # (case id, truth) -> the truth's components drawn as Polylines

CLASSES = {
    "count": "the number of connected components differs",
    "raises": "raises instead of returning curves",
    "coincidence": "does not report the coincident faces",
    "off-surface": "returned points off a surface",
    "spurious": "a curve on no component of the truth",
    "missing": "a component (or contact point) not found",
    "split": "a component returned in pieces that do not join",
    "length": "a component's length differs (a piece missing or traced twice)",
    "open/closed": "closedness or free ends differ",
    "contact-as-curve": "a contact point of the truth returned as a short curve",
}


#: Chords of a truth's polyline are cut to at most this fraction of its length (a straight piece comes as its two
#: ends: the nearest vertices of a point in its middle would lie on other pieces).
CHORD_SHARE = 1.0 / 256


def densified(line):
    """The polyline (M, 3) with points inserted so that no chord exceeds CHORD_SHARE of its length."""
    if len(line) < 2:
        return line
    steps = np.linalg.norm(np.diff(line, axis=0), axis=1)
    longest = CHORD_SHARE * float(steps.sum())
    if longest == 0.0 or steps.max() <= longest:
        return line
    out = [line[:1]]
    for a, b, step in zip(line[:-1], line[1:], steps):
        n = max(1, int(np.ceil(step / longest)))
        out.append(a + np.outer(np.arange(1, n + 1) / n, b - a))
    return np.concatenate(out)


class Polylines:
    """Distances from points to a set of polylines (exact to the polylines' chords)."""

    def __init__(self, lines):
        self.lines = [densified(np.asarray(line, dtype=float).reshape(-1, 3)) for line in lines if len(line)]
        pts, owner, index = [], [], []
        for k, line in enumerate(self.lines):
            pts.append(line)
            owner += [k] * len(line)
            index += list(range(len(line)))
        self.points = np.concatenate(pts) if pts else np.zeros((0, 3))
        self.owner, self.index = np.array(owner, dtype=int), np.array(index, dtype=int)
        self.tree = cKDTree(self.points) if len(self.points) else None

    def distance(self, q):
        """Distances from points q (..., 3) to the polylines: the chords at the nearest few vertices (several
        polylines may share a vertex, as at a node)."""
        q = np.asarray(q, dtype=float).reshape(-1, 3)
        if self.tree is None:
            return np.full(len(q), np.inf)
        k = min(NEAREST, len(self.points))
        _, nearest = self.tree.query(q, k=k)
        nearest = np.asarray(nearest).reshape(len(q), k)
        out = np.empty(len(q))
        for m, p in enumerate(q):
            best = np.inf
            for j in nearest[m]:
                line, i = self.lines[self.owner[j]], self.index[j]
                best = min(best, float(np.linalg.norm(line[i] - p)))
                for a, b in ((i - 1, i), (i, i + 1)):
                    if a < 0 or b >= len(line):
                        continue
                    d = line[b] - line[a]
                    dd = d @ d
                    t = 0.0 if dd == 0 else min(1.0, max(0.0, (p - line[a]) @ d / dd))
                    best = min(best, float(np.linalg.norm(line[a] + t * d - p)))
            out[m] = best
        return out


def run(case, order):
    """sk.intersect on the case's surfaces in the given order ('ab' or 'ba'): (curves or None, exception)."""
    import spatialkin as sk
    a, b = case.surfaces()
    if order == "ba":
        a, b = b, a
    try:
        return sk.intersect(a, b), None
    except Exception as exc:          # noqa: BLE001 - every failure is a result to classify
        return None, exc


def problems(case, order, curves=None, exc=None, truth=None):
    """[(class, message)]: what differs between spatialkin's run and the truth (empty when they agree)."""
    from spatialkin.geometry.placement import CoincidentSurfacesError
    if curves is None and exc is None:
        curves, exc = run(case, order)
    truth = truth if truth is not None else case.truth()
    scale = case.scale
    if truth.coincident:
        if isinstance(exc, CoincidentSurfacesError):
            return []
        got = f"{type(exc).__name__}: {exc}" if exc else f"{len(curves)} curves"
        return [("coincidence", f"expected CoincidentSurfacesError, got {got}")]
    if exc is not None:
        return [("raises", f"{type(exc).__name__}: {str(exc)[:200]}")]
    out = []
    a, b = case.surfaces()
    for k, c in enumerate(curves):
        pts = np.asarray(c.points, dtype=float).reshape(-1, 3)
        d = max(float(a.distance(pts).max()), float(b.distance(pts).max()))
        if d > DIST_RTOL * scale:
            out.append(("off-surface", f"curve {k} ({c.status}): a point {d:.3g} from a surface "
                                       f"(> {DIST_RTOL:g} x scale {scale:.6g})"))
    key = (case.id, id(truth))
    if key not in _DRAWN:
        _DRAWN[key] = [Polylines(comp.polylines(SAG_RTOL * scale)) for comp in truth.components]
    comps = _DRAWN[key]
    pts_truth = list(truth.points)
    match = MATCH_RTOL * scale
    seps = []
    for i in range(len(comps)):
        for j in range(i + 1, len(comps)):
            seps.append(float(comps[j].distance(comps[i].points).min()))
        for p in pts_truth:
            seps.append(float(comps[i].distance(p)[0]))
    for i in range(len(pts_truth)):
        for j in range(i + 1, len(pts_truth)):
            seps.append(float(np.linalg.norm(pts_truth[i] - pts_truth[j])))
    if seps:
        match = min(match, 0.25 * min(seps))
    assigned = {i: [] for i in range(len(comps))}
    found_points = set()
    spurious = []
    point_length = 0.0
    for k, c in enumerate(curves):
        pts = np.asarray(c.points, dtype=float).reshape(-1, 3)
        if pts_truth:
            dp = [float(np.linalg.norm(pts - p, axis=1).max()) for p in pts_truth]
            if min(dp) <= match:
                found_points.add(int(np.argmin(dp)))
                if c.length > 0:
                    point_length += c.length
                    where = np.round(pts_truth[int(np.argmin(dp))], 9).tolist()
                    out.append(("contact-as-curve", f"curve {k} ({c.status}, length {c.length:.3g}) stands for the "
                                                    f"contact point {where}"))
                continue
        dists = [float(cp.distance(pts).max()) for cp in comps]
        if dists and min(dists) <= match:
            assigned[int(np.argmin(dists))].append(c)
        else:
            where = f", {min(dists):.3g} from the nearest component" if dists else ""
            spurious.append(k)
            out.append(("spurious", f"curve {k} ({c.status}, length {c.length:.9g}, {len(pts)} points) lies on no "
                                    f"component of the truth{where}"))
    ncomp = len(spurious) + len(found_points)
    join = JOIN_RTOL * scale
    for i, comp in enumerate(truth.components):
        mine = assigned[i]
        if not mine:
            out.append(("missing", f"component {i} ({comp.label or 'curve'}, length {comp.length:.9g}, "
                                   f"{'closed' if comp.closed else 'open'}) not found"))
            continue
        groups, free, gap = _join(mine, join)
        ncomp += groups
        if groups > 1:
            out.append(("split", f"component {i} (length {comp.length:.9g}) comes in {groups} pieces that do not "
                                 f"join (nearest gap {gap:.3g})"))
        got = sum(c.length for c in mine)
        tol = LEN_RTOL * comp.length + LEN_ATOL * scale
        if abs(got - comp.length) > tol:
            out.append(("length", f"component {i}: length {got:.12g} from {len(mine)} curve(s), truth "
                                  f"{comp.length:.12g} (difference {got - comp.length:.3g}, tolerance {tol:.3g})"))
        if comp.closed and free:
            out.append(("open/closed", f"component {i} is closed, spatialkin's has {len(free)} free end(s) "
                                       f"(first at {np.round(free[0], 9).tolist()})"))
        elif comp.closed and len(mine) == 1 and not comp.nodes and not mine[0].closed:
            out.append(("open/closed", f"component {i} is a simple loop, spatialkin's curve is open "
                                       f"({mine[0].status}) with coincident ends"))
        elif not comp.closed:
            want = comp.ends
            ok = len(free) == len(want) and all(min(np.linalg.norm(f - w) for f in free) <= max(join, 1e-9 * scale)
                                                 for w in want)
            if not ok:
                out.append(("open/closed", f"component {i} is open with {len(want)} free end(s); spatialkin's has "
                                           f"{len(free)} and they are not the truth's"))
    for j in range(len(pts_truth)):
        if j not in found_points:
            out.append(("missing", f"contact point {np.round(pts_truth[j], 9).tolist()} not found"))
    if ncomp != truth.count:
        out.insert(0, ("count", f"{ncomp} component(s), truth {truth.count}"))
    total = sum(c.length for c in curves) - point_length
    tol = LEN_RTOL * truth.total_length + LEN_ATOL * scale * max(1, len(truth.components))
    if abs(total - truth.total_length) > tol:
        out.append(("length", f"total length {total:.12g}, truth {truth.total_length:.12g}"))
    return out


def _nearest_on(curve, q, s_lo=None, s_hi=None):
    """(distance, s) from point q to a spatialkin curve, refined with its dense evaluation curve(s) around the
    nearest stored point (optionally among the stored points with s in [s_lo, s_hi])."""
    pts = np.asarray(curve.points, dtype=float).reshape(-1, 3)
    s = np.asarray(curve.s, dtype=float)
    allowed = np.ones(len(s), dtype=bool)
    if s_lo is not None:
        allowed &= (s >= s_lo) & (s <= s_hi)
    if not allowed.any():
        return np.inf, None
    d = np.where(allowed, np.linalg.norm(pts - q, axis=1), np.inf)
    j = int(np.argmin(d))
    if len(s) == 1 or curve.length == 0:
        return float(d[j]), float(s[j])
    lo, hi = s[max(j - 1, 0)], s[min(j + 1, len(s) - 1)]
    if s_lo is not None:
        lo, hi = max(lo, s_lo), min(hi, s_hi)
    best = (float(d[j]), float(s[j]))
    for _ in range(3):
        ss = np.linspace(lo, hi, 65)
        dd = np.linalg.norm(np.asarray(curve(ss), dtype=float).reshape(-1, 3) - q, axis=1)
        k = int(np.argmin(dd))
        if dd[k] < best[0]:
            best = (float(dd[k]), float(ss[k]))
        lo, hi = ss[max(k - 1, 0)], ss[min(k + 1, 64)]
    return best


def _curves_distance(c1, c2):
    """The smallest distance between two spatialkin curves (alternating refinement from their closest stored
    points)."""
    p1 = np.asarray(c1.points, dtype=float).reshape(-1, 3)
    p2 = np.asarray(c2.points, dtype=float).reshape(-1, 3)
    dist, idx = cKDTree(p2).query(p1)
    i = int(np.argmin(dist))
    q1 = p1[i]
    best = float(dist[i])
    for _ in range(4):
        d2, s2 = _nearest_on(c2, q1)
        q2 = np.asarray(c2(np.array([s2])), dtype=float).reshape(3) if s2 is not None and c2.length > 0 else p2[idx[i]]
        d1, s1 = _nearest_on(c1, q2)
        q1 = np.asarray(c1(np.array([s1])), dtype=float).reshape(3) if s1 is not None and c1.length > 0 else q1
        best = min(best, d1, d2)
    return best


def _join(curves, join):
    """(groups, free ends, smallest gap between groups) of the curves of one component: two curves are joined
    where they meet (an end on the other, or crossing or touching it), an end is free unless it meets another
    curve or the curve's own far part (a loop through a node it ends at)."""
    n = len(curves)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    gaps = {}
    for i in range(n):
        for j in range(i + 1, n):
            gaps[i, j] = _curves_distance(curves[i], curves[j])
            if gaps[i, j] <= join:
                parent[find(i)] = find(j)
    free = []
    for i, c in enumerate(curves):
        if c.closed or c.length == 0:
            continue
        pts = np.asarray(c.points, dtype=float)
        s = np.asarray(c.s, dtype=float)
        for end, other, far in ((pts[0], pts[-1], (s[0] + 100 * join, s[-1])),
                                (pts[-1], pts[0], (s[0], s[-1] - 100 * join))):
            hit = np.linalg.norm(end - other) <= join
            if not hit and far[0] < far[1]:
                hit = _nearest_on(c, end, *far)[0] <= join
            hit = hit or any(j != i and _nearest_on(curves[j], end)[0] <= join for j in range(n))
            if not hit:
                free.append(end)
    groups = len({find(i) for i in range(n)})
    gap = 0.0
    if groups > 1:
        gap = min(g for (i, j), g in gaps.items() if find(i) != find(j))
    return groups, free, gap


def summary(curves, exc):
    """spatialkin's result in a few words."""
    if exc is not None:
        return type(exc).__name__
    if not curves:
        return "no curve"
    parts = []
    for c in curves:
        kind = "point" if c.length == 0 else ("loop" if c.closed else c.status)
        parts.append(kind if c.length == 0 else f"{kind} {c.length:.6g}")
    return ", ".join(parts)


def truth_summary(truth):
    if truth.coincident:
        return "coincident faces"
    parts = [f"{'loop' if c.closed else 'open'} {c.length:.6g}" for c in truth.components]
    parts += ["point"] * len(truth.points)
    return ", ".join(parts) if parts else "nothing"


def table():
    """The README table: case, source, truth method, truth, spatialkin's result per order, failure class."""
    from tests.oracles.occ import cases
    rows = ["| case | OCCT script | truth (method) | spatialkin (a, b) / (b, a) | failure class |",
            "|---|---|---|---|---|"]
    for c in cases.CASES:
        truth = c.truth()
        cells, classes = [], []
        for order in ("ab", "ba"):
            curves, exc = run(c, order)
            cells.append(summary(curves, exc))
            found = sorted({k for k, _ in problems(c, order, curves, exc, truth)})
            classes.append(", ".join(found) if found else "pass")
        res = cells[0] if cells[0] == cells[1] else f"{cells[0]} / {cells[1]}"
        cls = classes[0] if classes[0] == classes[1] else f"{classes[0]} / {classes[1]}"
        method = "closed form" if c.method.startswith("closed form") else (
            "sweep" if "sweep" in c.method else ("torus sections" if "torus sections" in c.method else c.method))
        rows.append(f"| {c.id} | {c.source.replace('tests/', '')} | {truth_summary(truth)} ({method}) | {res} | "
                    f"{cls} |")
    return "\n".join(rows)


def _method(case):
    m = case.method
    if m.startswith("closed form"):
        return "closed form"
    if m.startswith("coincidence"):
        return "coincidence"
    if "generators" in m:
        return "sweep by generators"
    if "normal to the parallel axes" in m:
        return "sweep by axial planes" + (" + closed form" if "circle of tangency" in m else "")
    if "spheres about" in m:
        return "sweep by spheres"
    if "torus sections" in m:
        return "torus sections"
    return m


def script_table():
    """The README table, one row per OCCT script: its cases, truth, spatialkin's result in both orders, failure
    classes (with the number of runs each)."""
    import collections

    from tests.oracles.occ import cases
    groups = collections.OrderedDict()
    for c in cases.CASES:
        groups.setdefault(c.source, []).append(c)
    rows = ["| OCCT script | case(s) | truth (method) | spatialkin, both orders | failure class |",
            "|---|---|---|---|---|"]
    for source, members in groups.items():
        truths, results, classes, passed = [], [], collections.Counter(), 0
        for c in members:
            truth = c.truth()
            truths.append(truth_summary(truth))
            cells = []
            for order in ("ab", "ba"):
                curves, exc = run(c, order)
                cells.append(summary(curves, exc))
                found = problems(c, order, curves, exc, truth)
                if found:
                    classes[failure_class(found, exc)] += 1
                else:
                    passed += 1
            results.append(cells[0] if cells[0] == cells[1] else f"{cells[0]} / {cells[1]}")
        methods = sorted({_method(c) for c in members})
        name = source.replace("tests/", "")
        if len(members) == 1:
            what = members[0].id.split("/", 1)[1]
            truth_cell = f"{truths[0]} ({', '.join(methods)})"
            result_cell = results[0]
        else:
            what = f"{len(members)} face pairs"
            truth_cell = f"{len(members)} truths ({', '.join(methods)})"
            result_cell = f"{passed} of {2 * len(members)} runs pass"
        cls = "; ".join(f"{k} ({n})" for k, n in sorted(classes.items())) if classes else "pass"
        rows.append(f"| {name} | {what} | {truth_cell} | {result_cell} | {cls} |")
    return "\n".join(rows)


def failure_class(found, exc=None):
    """The xfail reason of a failing run: its classes (CLASSES), the exception's type when it raises."""
    kinds = sorted({k for k, _ in found})
    text = ", ".join(kinds)
    if "raises" in kinds and exc is not None:
        what = next((tag for phrase, tag in RAISES if phrase in str(exc)), "")
        text = text.replace("raises", f"raises {type(exc).__name__}{' (' + what + ')' if what else ''}")
    return text


def xfails():
    """{case id: {order: failure class}} of every run spatialkin fails (the XFAIL block of cases.py)."""
    from tests.oracles.occ import cases
    out = {}
    for c in cases.CASES:
        truth = c.truth()
        for order in ("ab", "ba"):
            curves, exc = run(c, order)
            found = problems(c, order, curves, exc, truth)
            if found:
                out.setdefault(c.id, {})[order] = failure_class(found, exc)
    return out


def write_xfails():
    """Rewrite the XFAIL block of cases.py from a run of every case."""
    import pprint
    from tests.oracles.occ import cases
    path = cases.__file__
    text = open(path).read()
    head, rest = text.split("# BEGIN XFAIL\n", 1)
    _, tail = rest.split("# END XFAIL\n", 1)
    body = "XFAIL = " + pprint.pformat(xfails(), width=116, sort_dicts=True) + "\n"
    open(path, "w").write(head + "# BEGIN XFAIL\n" + body + "# END XFAIL\n" + tail)


if __name__ == "__main__":
    import sys
    if "--xfail" in sys.argv:
        write_xfails()
    elif "--scripts" in sys.argv:
        print(script_table())
    else:
        print(table())
