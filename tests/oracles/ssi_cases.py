"""Deterministic surface–surface intersection cases for the topology stress test (every pair of Plane, Sphere,
Cylinder, Cone and Torus, same-kind pairs included), each with its truth when a closed form exists.

Families
--------
random      general placements (truth: brute force)
aligned     axes along the global axes, origins with zero or random coordinates (truth: brute force)
coaxial     a common axis: the truth is the intersection of the meridian curves in the (rho, z) half-plane,
            one circle per meridian intersection point (a point on the axis is an isolated point)
scaled      a random and a coaxial scene of every pair scaled by 1e-4, by 1e4, and moved 1e5 from the origin
            (truth: the base case's, mapped by the similarity)
contact     contacts within 1e-9 x scale and exact ones: isolated contacts, near-nodes, tangency along curves
tiny        loops of 1e-6 .. 1e-3 of the scale (closed forms: circle radius, or a refined ring round the
            contact point)
villarceau  bitangent plane of a ring torus: two circles crossing at two points, one component
steinmetz   equal cylinders with intersecting axes: two ellipses crossing at two nodes, one component
viviani     sphere R and cylinder R/2 through its centre: a figure-eight, one component
trimmed     rectangular patches (and trimmed cylinders) cutting curves into arcs, or missing them
face        CAD faces: angular ranges of cylinders, cones, spheres and tori, a sphere's zone, a plane's disc or
            annulus, cutting circles and ellipses into arcs
tangent     tangency along a curve (torus and plane z = r, sphere and coaxial cylinder, cylinder on a plane...)
simple      the first scenes a user tries: coaxial sphere, cylinder, plane, cone and torus pairs, coincident
            surfaces, a patch that misses a torus
special     coincident surfaces and unbounded pairs (the expected outcome is a ValueError or a typed result)

Run ``python -m tests.oracles.ssi_cases`` for the oracle self-check: the brute force against every closed form, and the
closed-form samples' distances to both surfaces before Newton polishing.
"""
import sys
import time
from dataclasses import dataclass

import numpy as np

import spatialkin as sk
from tests.oracles.ssi import (KINDS, brute_force, distance, frame_of, kind, loop_samples, refine,
                        samples_near, scene_scale, shape_params, trim_margin, trims)

EPS = 1e-9                  # contact offsets, relative to the scale
TANG = 1e-14                # meridian discriminants below this (relative to r^2) are tangencies
BIG = 1e3                   # extent standing in for an untrimmed line in the meridian half-plane
DEG = np.pi / 180.0


@dataclass
class Case:
    name: str
    family: str
    a: object
    b: object
    count: int = None           # closed-form number of components (None: ask the brute force)
    kind: str = None            # 'generic', 'tangent', 'contact', 'node', 'coincident', 'unbounded'
    samples: np.ndarray = None  # closed-form points on the intersection (refined onto both surfaces)
    sample_tol: float = 0.0     # extra slack for samples that only locate a component (tiny loops)
    scale: float = 1.0
    base: str = None            # a 'scaled' case: the base case's name ...
    factor: float = 1.0         # ... and the similarity x -> factor * x + shift
    shift: np.ndarray = None
    raw_residual: float = 0.0   # max distance of the closed-form samples to the surfaces before polishing
    note: str = ""

    @property
    def pair(self):
        ka, kb = sorted((kind(self.a), kind(self.b)), key=KINDS.index)
        return f"{ka}-{kb}"

    @property
    def closed_form(self):
        return self.count is not None or self.kind in ("coincident", "unbounded") or self.base is not None


# ----------------------------------------------------------------------------------------------------------
# frames and surfaces
# ----------------------------------------------------------------------------------------------------------
def rand_rot(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def rot_z(phi):
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


FLIP = np.diag([1.0, -1.0, -1.0])          # turn a frame upside down (pi about local x)


def aligned_rotations():
    """The 24 proper rotations that permute the global axes (with signs)."""
    out = []
    for perm in ((0, 1, 2), (1, 2, 0), (2, 0, 1), (0, 2, 1), (2, 1, 0), (1, 0, 2)):
        for signs in np.ndindex(2, 2, 2):
            m = np.zeros((3, 3))
            for col, row in enumerate(perm):
                m[row, col] = 1.0 if signs[col] == 0 else -1.0
            if np.linalg.det(m) > 0:
                out.append(m)
    return out


def F(o=(0.0, 0.0, 0.0), R=None):
    return sk.Frame(np.asarray(o, dtype=float), np.eye(3) if R is None else np.asarray(R, dtype=float))


def rng_tuple(r):
    return None if r is None else (float(r[0]), float(r[1]))


def make(k, frame, p, u_range=None, v_range=None):
    """Surface of kind k in `frame` with shape numbers p."""
    if k == "plane":
        return sk.Plane(frame, u_range=rng_tuple(u_range), v_range=rng_tuple(v_range))
    if k == "sphere":
        return sk.Sphere(p[0], frame)
    if k == "cylinder":
        return sk.Cylinder(p[0], frame, v_range=rng_tuple(v_range))
    if k == "cone":
        return sk.Cone(p[0], frame, v_range=rng_tuple(v_range))
    return sk.Torus(p[0], p[1], frame)


def transformed(s, factor, shift):
    """The surface mapped by x -> factor * x + shift (a similarity)."""
    k, q = kind(s), shape_params(s)
    o, R = frame_of(s)
    frame = F(factor * o + shift, R)
    ur, vr = trims(s)

    def tr(r):
        return None if not np.all(np.isfinite(r)) else (factor * r[0], factor * r[1])

    if k == "plane":
        return make(k, frame, (), tr(ur), tr(vr))
    if k == "sphere":
        return make(k, frame, (factor * q["R"],))
    if k == "cylinder":
        return make(k, frame, (factor * q["r"],), v_range=tr(vr))
    if k == "cone":
        return make(k, frame, (q["a"],), v_range=tr(vr))
    return make(k, frame, (factor * q["R"], factor * q["r"]))


def gpt(s, p):
    """Global point of a local point of surface s."""
    o, R = frame_of(s)
    return o + np.asarray(p, dtype=float) @ R.T


# ----------------------------------------------------------------------------------------------------------
# closed forms
# ----------------------------------------------------------------------------------------------------------
def circle_points(centre, w, rho, n=720):
    w = np.asarray(w, dtype=float) / np.linalg.norm(w)
    e1 = np.cross(w, [1.0, 0.0, 0.0])
    if np.linalg.norm(e1) < 0.5:
        e1 = np.cross(w, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(w, e1)
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return centre + rho * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)


def runs(mask, closed):
    """Number of maximal runs of True in a sampled curve (cyclic when closed)."""
    mask = np.asarray(mask, dtype=bool)
    if not mask.any():
        return 0
    if mask.all():
        return 1
    rises = np.count_nonzero(mask & ~np.roll(mask, 1)) if closed else \
        np.count_nonzero(mask[1:] & ~mask[:-1]) + int(mask[0])
    return int(rises)


def margins(a, b, pts):
    return np.minimum(trim_margin(a, pts), trim_margin(b, pts))


def clipped(a, b, curves, scale, grazing=1e-3):
    """Count the arcs of exact curves (list of (points (M, 3), closed)) inside both trims, and their points.
    Returns (count, samples, robust): robust is False when a curve grazes a trim edge or passes near a
    corner (a local extremum of the margin within grazing x scale of zero)."""
    count, pts, robust = 0, [], True
    for p, closed in curves:
        m = margins(a, b, p)
        m = np.where(np.isfinite(m), m, 1e300)
        count += runs(m >= 0, closed)
        pts.append(p[m >= 0])
        d = np.diff(np.concatenate([m, m[:1]]) if closed else m)
        ext = np.nonzero(np.sign(d[1:]) != np.sign(d[:-1]))[0] + 1
        ext = ext[ext < len(m)]
        if len(ext) and np.any(np.abs(m[ext]) < grazing * scale):
            robust = False
        # crossings of a trim edge must be clean (not near the curve's own ends for open curves)
        if not closed and (abs(m[0]) < grazing * scale or abs(m[-1]) < grazing * scale):
            robust = False
    samples = np.vstack(pts) if pts else np.zeros((0, 3))
    return count, samples, robust


# --- meridian curves of coaxial surfaces of revolution ---------------------------------------------------
def meridian(s, o, w, scale):
    """Primitives of the meridian of surface s in the (rho >= 0, z) half-plane of the axis (o, w):
    ('circle', centre, radius, half) or ('seg', p0, p1)."""
    k, q = kind(s), shape_params(s)
    so, R = frame_of(s)
    z0 = float(np.dot(so - o, w))
    flip = float(np.sign(np.dot(R[:, 2], w)))
    ur, vr = trims(s)
    big = BIG * scale
    if k == "sphere":
        return [("circle", np.array([0.0, z0]), q["R"], True)]
    if k == "torus":
        return [("circle", np.array([q["R"], z0]), q["r"], False)]
    if k == "plane":
        return [("seg", np.array([0.0, z0]), np.array([big, z0]))]
    lo, hi = (max(vr[0], -big), min(vr[1], big))
    if k == "cylinder":
        return [("seg", np.array([q["r"], z0 + flip * lo]), np.array([q["r"], z0 + flip * hi]))]
    t = q["t"]
    out = []
    for a0, a1 in ((lo, min(hi, 0.0)), (max(lo, 0.0), hi)):
        if a1 > a0:
            out.append(("seg", np.array([abs(a0) * t, z0 + flip * a0]), np.array([abs(a1) * t, z0 + flip * a1])))
    return out


def _meet(p, q, scale):
    """Intersections of two meridian primitives: list of (point, tangent), margin, coincident."""
    pts, margin, coincident = [], np.inf, False
    if p[0] == "seg" and q[0] == "circle":
        p, q = q, p
    if p[0] == "circle" and q[0] == "circle":
        (_, c1, r1, h1), (_, c2, r2, h2) = p, q
        dv = c2 - c1
        D = float(np.hypot(*dv))
        if D <= 1e-14 * scale:
            if abs(r1 - r2) <= 1e-14 * scale:
                coincident = True
            return pts, abs(r1 - r2) / scale, coincident
        a = (D * D + r1 * r1 - r2 * r2) / (2 * D)
        hh = r1 * r1 - a * a
        margin = abs(hh) / (r1 * r1)
        e = dv / D
        n = np.array([-e[1], e[0]])
        if abs(hh) <= TANG * r1 * r1:
            pts.append((c1 + a * e, True))
        elif hh > 0:
            hq = np.sqrt(hh)
            pts += [(c1 + a * e + hq * n, False), (c1 + a * e - hq * n, False)]
        half = h1 or h2
        if half:
            margin = min(margin, min([abs(x[0][0]) / scale for x in pts] + [np.inf]))
            pts = [x for x in pts if x[0][0] >= -1e-12 * scale]
        return pts, margin, coincident
    if p[0] == "circle":
        _, c, r, half = p
        _, p0, p1 = q
        if np.hypot(*(p1 - c)) < np.hypot(*(p0 - c)):
            p0, p1 = p1, p0                              # parametrise from the end nearer the circle
        d = p1 - p0
        A = float(d @ d)
        sm = -float((p0 - c) @ d) / A                    # foot of the perpendicular from the centre
        m = p0 + sm * d
        q2 = r * r - float((m - c) @ (m - c))           # squared half chord
        margin = abs(q2) / (r * r)
        roots = []
        if abs(q2) <= TANG * r * r:
            roots = [(sm, True)]
        elif q2 > 0:
            ds = np.sqrt(q2 / A)
            roots = [(sm - ds, False), (sm + ds, False)]
        L = np.sqrt(A)
        for sv, tan in roots:
            margin = min(margin, abs(sv) * L / scale, abs(sv - 1) * L / scale)
            if -1e-12 <= sv <= 1 + 1e-12:
                x = m + (sv - sm) * d
                if half:
                    margin = min(margin, abs(x[0]) / scale)
                    if x[0] < -1e-12 * scale:
                        continue
                pts.append((x, tan))
        return pts, margin, coincident
    _, p0, p1 = p
    _, q0, q1 = q
    d, e = p1 - p0, q1 - q0
    cr = d[0] * e[1] - d[1] * e[0]
    if abs(cr) <= 1e-14 * np.linalg.norm(d) * np.linalg.norm(e):
        off = (q0 - p0)
        if abs(off[0] * d[1] - off[1] * d[0]) <= 1e-12 * np.linalg.norm(d) * scale:
            t0 = float(off @ d) / float(d @ d)
            t1 = float((q1 - p0) @ d) / float(d @ d)
            if max(min(t0, t1), 0.0) < min(max(t0, t1), 1.0):
                coincident = True
        return pts, np.inf, coincident
    r = q0 - p0
    sv = (r[0] * e[1] - r[1] * e[0]) / cr
    tv = (r[0] * d[1] - r[1] * d[0]) / cr
    Ld, Le = np.linalg.norm(d), np.linalg.norm(e)
    margin = min(abs(sv) * Ld, abs(sv - 1) * Ld, abs(tv) * Le, abs(tv - 1) * Le) / scale
    if -1e-12 <= sv <= 1 + 1e-12 and -1e-12 <= tv <= 1 + 1e-12:
        pts.append((p0 + sv * d, False))
    return pts, margin, coincident


def coaxial_truth(a, b, o, w, scale, n=720):
    """Closed form for coaxial surfaces of revolution (a plane must be perpendicular to the axis and
    untrimmed, except plane-plane). Returns dict(count, kind, samples, margin, points)."""
    if kind(a) == "plane" and kind(b) == "plane":
        za = float(np.dot(frame_of(a)[0] - o, w))
        zb = float(np.dot(frame_of(b)[0] - o, w))
        if abs(za - zb) <= 1e-14 * scale:
            return dict(count=None, kind="coincident", samples=np.zeros((0, 3)), margin=np.inf, points=[])
        return dict(count=0, kind="generic", samples=np.zeros((0, 3)), margin=abs(za - zb) / scale, points=[])
    found, margin, coincident = [], np.inf, False
    for p in meridian(a, o, w, scale):
        for q in meridian(b, o, w, scale):
            pts, m, c = _meet(p, q, scale)
            found += pts
            margin = min(margin, m)
            coincident |= c
    if coincident:
        return dict(count=None, kind="coincident", samples=np.zeros((0, 3)), margin=margin, points=[])
    uniq = []
    for x, tan in found:
        if all(np.hypot(*(x - y)) > 1e-9 * scale for y, _ in uniq):
            uniq.append((x, tan))
    samples, kinds = [], set()
    for (rho, z), tan in uniq:
        centre = o + z * w
        if rho <= 1e-12 * scale:
            samples.append(centre[None])
            kinds.add("contact")
        else:
            samples.append(circle_points(centre, w, rho, n))
            if tan:
                kinds.add("tangent")
    kd = "tangent" if "tangent" in kinds else ("contact" if "contact" in kinds else "generic")
    return dict(count=len(uniq), kind=kd, samples=np.vstack(samples) if samples else np.zeros((0, 3)),
                margin=margin, points=uniq)


def finish(case):
    """Polish closed-form samples onto both surfaces (recording how far they were), keep those in the trims."""
    if case.samples is None or len(case.samples) == 0:
        case.samples = np.zeros((0, 3))
        return case
    s = np.asarray(case.samples, dtype=float).reshape(-1, 3)
    raw = np.maximum(distance(case.a, s), distance(case.b, s))
    case.raw_residual = float(raw.max()) / case.scale
    ref, res = refine(case.a, case.b, s)
    ok = res <= 1e-9 * case.scale + 64 * np.spacing(np.abs(ref).max())
    s = np.where(ok[:, None], ref, s)
    m = margins(case.a, case.b, s)
    case.samples = s[m >= -1e-9 * case.scale]
    return case


# ----------------------------------------------------------------------------------------------------------
# families
# ----------------------------------------------------------------------------------------------------------
def pairs():
    return [(KINDS[i], KINDS[j]) for i in range(5) for j in range(i, 5)]


def random_surface(rng, k, centre, R, partner_bounded, size=1.0):
    """A random surface of kind k around `centre` with rotation R."""
    frame = F(centre, R)
    untrim = partner_bounded and rng.random() < 0.25
    if k == "sphere":
        return make(k, frame, (size * rng.uniform(0.6, 1.5),))
    if k == "torus":
        big = size * rng.uniform(0.9, 1.6)
        return make(k, frame, (big, big * rng.uniform(0.2, 0.55)))
    if k == "cylinder":
        vr = None if untrim else (-size * rng.uniform(0.8, 2.2), size * rng.uniform(0.8, 2.2))
        return make(k, frame, (size * rng.uniform(0.3, 1.1),), v_range=vr)
    if k == "cone":
        if untrim:
            vr = None
        elif rng.random() < 0.5:
            vr = (-size * rng.uniform(0.6, 2.0), size * rng.uniform(0.6, 2.0))
        else:
            vr = (size * rng.uniform(0.1, 0.6), size * rng.uniform(1.2, 2.4))
        return make(k, frame, (rng.uniform(15, 50) * DEG,), v_range=vr)
    ur = None if untrim else (-size * rng.uniform(0.7, 2.5), size * rng.uniform(0.7, 2.5))
    vr = None if untrim else (-size * rng.uniform(0.7, 2.5), size * rng.uniform(0.7, 2.5))
    return make(k, frame, (), ur, vr)


def _bounded_kinds(k):
    return k in ("sphere", "torus")


def random_family(rng, per_pair=7):
    out = []
    for ka, kb in pairs():
        for i in range(per_pair):
            c1 = rng.uniform(-0.6, 0.6, 3)
            c2 = c1 + rng.normal(size=3) * rng.uniform(0.2, 0.9)
            a = random_surface(rng, ka, c1, rand_rot(rng), _bounded_kinds(kb))
            b = random_surface(rng, kb, c2, rand_rot(rng), _bounded_kinds(ka) or not _is_untrimmed(a))
            if not (_bounded(a) or _bounded(b)):
                b = random_surface(rng, kb, c2, rand_rot(rng), False)
            if i % 2:
                a, b = b, a
            out.append(Case(f"random/{ka}-{kb}/{i}", "random", a, b, scale=scene_scale(a, b)))
    return out


def _bounded(s):
    from tests.oracles.ssi import is_bounded
    return is_bounded(s)


def _is_untrimmed(s):
    return not _bounded(s)


def aligned_family(rng, per_pair=4):
    rots = aligned_rotations()
    out = []
    for ka, kb in pairs():
        for i in range(per_pair):
            def origin():
                return np.where(rng.random(3) < 0.5, 0.0, np.round(rng.uniform(-0.8, 0.8, 3), 3))
            a = random_surface(rng, ka, origin(), rots[rng.integers(len(rots))], _bounded_kinds(kb))
            b = random_surface(rng, kb, origin(), rots[rng.integers(len(rots))],
                               _bounded_kinds(ka) or _bounded(a))
            if not (_bounded(a) or _bounded(b)):
                b = random_surface(rng, kb, origin(), rots[rng.integers(len(rots))], False)
            if i % 2:
                a, b = b, a
            out.append(Case(f"aligned/{ka}-{kb}/{i}", "aligned", a, b, scale=scene_scale(a, b)))
    return out


def coaxial_surface(rng, k, o, Rm, other):
    """A surface of revolution about the axis (o, Rm[:, 2]) at a random axial offset (plane: perpendicular,
    untrimmed unless both are planes)."""
    w = Rm[:, 2]
    R = Rm @ rot_z(rng.uniform(0, 2 * np.pi))
    if rng.random() < 0.4:
        R = R @ FLIP
    if k == "sphere":
        return make(k, F(o + rng.uniform(-0.5, 0.5) * w, R), (rng.uniform(0.6, 1.5),))
    if k == "torus":
        big = rng.uniform(0.8, 1.5)
        return make(k, F(o + rng.uniform(-0.4, 0.4) * w, R), (big, big * rng.uniform(0.25, 0.5)))
    if k == "cylinder":
        trim = not _bounded_kinds(other) or rng.random() < 0.7
        vr = (-rng.uniform(0.6, 2.0), rng.uniform(0.6, 2.0)) if trim else None
        return make(k, F(o + rng.uniform(-0.3, 0.3) * w, R), (rng.uniform(0.3, 1.6),), v_range=vr)
    if k == "cone":
        trim = not _bounded_kinds(other) or rng.random() < 0.7
        vr = None
        if trim:
            vr = (-rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0)) if rng.random() < 0.6 else \
                (rng.uniform(0.05, 0.5), rng.uniform(1.0, 2.2))
        return make(k, F(o + rng.uniform(-1.0, 1.0) * w, R), (rng.uniform(20, 55) * DEG,), v_range=vr)
    trim = other == "plane"
    vr = ur = (-rng.uniform(0.5, 2), rng.uniform(0.5, 2)) if trim else None
    return make(k, F(o + rng.uniform(-0.8, 0.8) * w, R), (), ur, vr)


def coaxial_family(rng, per_pair=4):
    out = []
    for ka, kb in pairs():
        made = 0
        for attempt in range(400):
            if made == per_pair:
                break
            o = rng.uniform(-1, 1, 3)
            Rm = rand_rot(rng)
            a = coaxial_surface(rng, ka, o, Rm, kb)
            b = coaxial_surface(rng, kb, o, Rm, ka)
            if not (_bounded(a) or _bounded(b)):
                continue
            scale = scene_scale(a, b)
            tr = coaxial_truth(a, b, o, Rm[:, 2], scale)
            if tr["kind"] == "coincident" or tr["margin"] < 2e-3:
                continue
            if tr["count"] == 0 and rng.random() < 0.7 and ka != "plane" and not (ka == kb == "cylinder"):
                continue                  # mostly non-empty
            if any(p[0] <= 1e-9 * scale for p, _ in tr["points"]):
                continue                  # axis points belong to the designed families
            if made % 2:
                a, b = b, a
            out.append(finish(Case(f"coaxial/{ka}-{kb}/{made}", "coaxial", a, b, tr["count"], tr["kind"],
                                   tr["samples"], scale=scale)))
            made += 1
    return out


def scaled_family(bases, rng):
    out = []
    for base in bases:
        for tag, factor, shift in (("x1e-4", 1e-4, np.zeros(3)), ("x1e4", 1e4, np.zeros(3)),
                                   ("+1e5", 1.0, rng.normal(size=3))):
            if tag == "+1e5":
                shift = 1e5 * shift / np.linalg.norm(shift)
            a = transformed(base.a, factor, shift)
            b = transformed(base.b, factor, shift)
            out.append(Case(f"scaled/{base.name}/{tag}", "scaled", a, b, base.count, base.kind,
                            None if base.samples is None else factor * base.samples + shift,
                            scale=factor * base.scale, base=base.name, factor=factor, shift=shift))
    return out


# --- closed-form families ---------------------------------------------------------------------------------
def torus_sphere_truth(big, small, c, rho, n=4000):
    """Torus (big, small) about local z and sphere (centre c local, radius rho): count by the band of rho
    among the four critical distances, and exact points (solving per u and per v)."""
    rc = np.hypot(c[0], c[1])
    dmin, dmax = np.hypot(rc - big, c[2]), np.hypot(rc + big, c[2])
    crit = np.sort([abs(dmin - small), dmin + small, abs(dmax - small), dmax + small])
    tol = 1e-13 * (big + small)
    if rho < crit[0] - tol or rho > crit[3] + tol:
        count = 0
    elif crit[1] + tol < rho < crit[2] - tol:
        count = 2
    else:
        count = 1
    pts = []
    # |P - c|^2 = rho^2 with P((R + r cos v) cos u, (R + r cos v) sin u, r sin v):
    # per u: alpha cos v + beta sin v = gamma ; per v: alpha' cos u + beta' sin u = gamma'
    cc = float(c @ c)
    u = np.linspace(0, 2 * np.pi, n, endpoint=False)
    A = c[0] * np.cos(u) + c[1] * np.sin(u)
    pts += _trig_solve(2 * small * (big - A), -2 * small * c[2] * np.ones_like(u),
                       rho ** 2 - big ** 2 - small ** 2 - cc + 2 * big * A,
                       lambda v, k: _torus_pt(big, small, u[k], v))
    v = np.linspace(0, 2 * np.pi, n, endpoint=False)
    w = big + small * np.cos(v)
    pts += _trig_solve(-2 * w * c[0], -2 * w * c[1],
                       rho ** 2 - w ** 2 - small ** 2 * np.sin(v) ** 2 + 2 * small * np.sin(v) * c[2] - cc,
                       lambda uu, k: _torus_pt(big, small, uu, v[k]))
    return count, crit, (np.vstack(pts) if pts else np.zeros((0, 3)))


def _torus_pt(big, small, u, v):
    w = big + small * np.cos(v)
    return np.stack([w * np.cos(u), w * np.sin(u), small * np.sin(v)], axis=-1)


def _trig_solve(alpha, beta, gamma, point):
    """Points for the solutions x of alpha cos x + beta sin x = gamma (elementwise)."""
    amp = np.hypot(alpha, beta)
    ok = np.abs(gamma) <= amp
    k = np.nonzero(ok)[0]
    if len(k) == 0:
        return []
    base = np.arctan2(beta[k], alpha[k])
    spread = np.arccos(np.clip(gamma[k] / amp[k], -1, 1))
    return [point(base + spread, k), point(base - spread, k)]


def torus_plane_parallel_truth(big, small, c, n=6000):
    """Torus and the plane x = c (local): count and points."""
    ac = abs(c)
    tol = 1e-13 * (big + small)
    if ac > big + small + tol:
        count = 0
    elif ac < big - small - tol:
        count = 2
    else:
        count = 1
    v = np.linspace(0, 2 * np.pi, n, endpoint=False)
    w = big + small * np.cos(v)
    ok = np.abs(c) <= w
    pts = []
    if ok.any():
        uu = np.arccos(np.clip(c / w[ok], -1, 1))
        pts += [_torus_pt(big, small, uu, v[ok]), _torus_pt(big, small, -uu, v[ok])]
    u = np.linspace(-np.pi / 2, np.pi / 2, n)[1:-1]
    if c < 0:
        u = u + np.pi
    cv = (c / np.cos(u) - big) / small
    ok = np.abs(cv) <= 1
    if ok.any():
        vv = np.arccos(cv[ok])
        pts += [_torus_pt(big, small, u[ok], vv), _torus_pt(big, small, u[ok], -vv)]
    return count, (np.vstack(pts) if pts else np.zeros((0, 3)))


def sphere_cylinder_truth(R, r, d, n=6000):
    """Sphere (radius R at the origin) and the cylinder of radius r about the line x = d, y = 0 (parallel
    to z), untrimmed: count and points."""
    tol = 1e-13 * (R + r + d)
    if d < R:
        crit = (R - d, R + d)
        count = 2 if r < crit[0] - tol else (1 if r <= crit[1] + tol else 0)
    else:
        count = 0 if (r < d - R - tol or r > d + R + tol) else 1
    u = np.linspace(0, 2 * np.pi, n, endpoint=False)
    z2 = R * R - d * d - r * r - 2 * d * r * np.cos(u)
    ok = z2 >= 0
    pts = []
    if ok.any():
        x, y, z = d + r * np.cos(u[ok]), r * np.sin(u[ok]), np.sqrt(z2[ok])
        pts += [np.stack([x, y, z], -1), np.stack([x, y, -z], -1)]
    if d > 0 and r > 0:
        zz = np.linspace(-R, R, n)
        cu = (R * R - zz ** 2 - d * d - r * r) / (2 * d * r)
        ok = np.abs(cu) <= 1
        if ok.any():
            uu = np.arccos(cu[ok])
            for s in (1, -1):
                pts.append(np.stack([d + r * np.cos(s * uu), r * np.sin(s * uu), zz[ok]], -1))
    return count, (np.vstack(pts) if pts else np.zeros((0, 3)))


def perpendicular_cylinders_truth(r1, r2, d, n=6000):
    """Cylinder 1 x^2 + y^2 = r1^2 (axis z) and cylinder 2 (y - d)^2 + z^2 = r2^2 (axis x), untrimmed."""
    al, be = (d - r2) / r1, (d + r2) / r1
    tol = 1e-13
    if be < -1 - tol or al > 1 + tol:
        count = 0
    elif al <= -1 + tol and be >= 1 - tol:
        count = 1 if (abs(al + 1) <= tol or abs(be - 1) <= tol) else 2
    elif al <= -1 + tol or be >= 1 - tol:
        count = 1
    else:
        count = 2
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    z2 = r2 ** 2 - (r1 * np.sin(t) - d) ** 2
    ok = z2 >= 0
    pts = []
    if ok.any():
        x, y, z = r1 * np.cos(t[ok]), r1 * np.sin(t[ok]), np.sqrt(z2[ok])
        pts += [np.stack([x, y, z], -1), np.stack([x, y, -z], -1)]
    s = np.linspace(0, 2 * np.pi, n, endpoint=False)
    y, z = d + r2 * np.cos(s), r2 * np.sin(s)
    x2 = r1 ** 2 - y ** 2
    ok = x2 >= 0
    if ok.any():
        xx = np.sqrt(x2[ok])
        pts += [np.stack([xx, y[ok], z[ok]], -1), np.stack([-xx, y[ok], z[ok]], -1)]
    return count, (np.vstack(pts) if pts else np.zeros((0, 3)))


def _local_case(name, family, a, b, count, kind_, samples_local, ref, scale, note="", sample_tol=0.0):
    """A case whose samples are given in the local frame of surface `ref`."""
    samples = gpt(ref, samples_local) if samples_local is not None and len(samples_local) else np.zeros((0, 3))
    return finish(Case(name, family, a, b, count, kind_, samples, sample_tol, scale=scale, note=note))


def contact_family(rng):
    out = []
    signs = ((-1, "in"), (0, "at"), (1, "out"))
    # plane at distance R + g from a sphere centre
    for i, (sg, tag) in enumerate(signs):
        R = rng.uniform(0.7, 1.5)
        Rm = rand_rot(rng)
        o = rng.uniform(-1, 1, 3)
        sph = sk.Sphere(R, F(o, rand_rot(rng)))
        d = R + sg * EPS * R
        pl = sk.Plane(F(o + d * Rm[:, 2], Rm))
        rho = np.sqrt(max(R * R - d * d, 0.0))
        samples = circle_points(o + d * Rm[:, 2], Rm[:, 2], rho, 64) if sg < 0 else (
            (o + d * Rm[:, 2])[None] if sg == 0 else None)
        cnt = 1 if sg <= 0 else 0
        a, b = (sph, pl) if i % 2 == 0 else (pl, sph)
        out.append(finish(Case(f"contact/plane-sphere/{tag}", "contact", a, b, cnt,
                               "contact" if sg == 0 else "generic", samples, scale=R)))
    # sphere-sphere external / internal (coaxial closed form)
    for mode in ("ext", "int"):
        for sg, tag in signs:
            o = rng.uniform(-1, 1, 3)
            Rm = rand_rot(rng)
            R1, R2 = rng.uniform(0.8, 1.4), rng.uniform(0.3, 0.7)
            d = R1 + R2 + sg * EPS if mode == "ext" else R1 - R2 - sg * EPS
            a = sk.Sphere(R1, F(o, rand_rot(rng)))
            b = sk.Sphere(R2, F(o + d * Rm[:, 2], rand_rot(rng)))
            tr = coaxial_truth(a, b, o, Rm[:, 2], R2)
            out.append(finish(Case(f"contact/sphere-sphere/{mode}-{tag}", "contact", a, b, tr["count"],
                                   tr["kind"], tr["samples"], scale=R2)))
    # torus-sphere off the axis at the four critical radii
    big, small = 1.5, 0.5
    for k in range(4):
        for sg, tag in signs:
            Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
            c = np.array([rng.uniform(0.3, 1.8), rng.uniform(-0.3, 0.3), rng.uniform(-0.7, 0.7)])
            tor = sk.Torus(big, small, F(o, Rm))
            rho = torus_sphere_truth(big, small, c, 1.0)[1][k]
            rho = rho + sg * EPS
            cnt, _, pts = torus_sphere_truth(big, small, c, rho)
            sph = sk.Sphere(rho, F(gpt(tor, c), rand_rot(rng)))
            cp = _torus_sphere_critical_point(big, small, c, k)
            extra = np.zeros((0, 3))
            if k in (0, 3):                 # min / max: nothing, an exact contact point, or a loop round it
                if (k == 0 and sg < 0) or (k == 3 and sg > 0):
                    pts = np.zeros((0, 3))
                elif sg == 0:
                    pts = cp[None]
                else:
                    pts = np.zeros((0, 3))
                    extra = loop_samples(tor, sph, gpt(tor, cp))
            else:                           # saddles: the branches near the (near-)node
                extra = samples_near(tor, sph, gpt(tor, cp), np.sqrt(2 * EPS * big) + 1e-6, 24)
            case = _local_case(f"contact/sphere-torus/r{k}-{tag}", "contact", tor if k % 2 else sph,
                               sph if k % 2 else tor, cnt, "contact" if (sg == 0 and k in (0, 3)) else
                               ("node" if sg == 0 else "generic"), pts, tor, small)
            case.samples = np.vstack([case.samples, extra]) if len(extra) else case.samples
            out.append(case)
    # torus and plane x = R + r (elliptic point), x = R - r (saddle: near-node), z = r (tangent circle)
    for where in ("outer", "inner", "top"):
        for sg, tag in signs:
            Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            tor = sk.Torus(big, small, F(o, Rm))
            if where == "top":
                pl = sk.Plane(F(o + (small + sg * EPS) * Rm[:, 2], Rm @ rot_z(rng.uniform(0, 6))))
                tr = coaxial_truth(tor, pl, o, Rm[:, 2], small)
                out.append(finish(Case(f"contact/plane-torus/{where}-{tag}", "contact", pl, tor, tr["count"],
                                       tr["kind"], tr["samples"], scale=small)))
                continue
            c = (big + small if where == "outer" else big - small) + sg * EPS
            cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
            pl = sk.Plane(F(o + c * Rm[:, 0], cols))
            cnt, pts = torus_plane_parallel_truth(big, small, c)
            crit = np.array([big + small if where == "outer" else big - small, 0.0, 0.0])
            if where == "outer":
                pts = crit[None] if sg == 0 else np.zeros((0, 3))
                extra = loop_samples(tor, pl, gpt(tor, crit)) if sg < 0 else np.zeros((0, 3))
            else:
                extra = samples_near(tor, pl, gpt(tor, crit), np.sqrt(2 * EPS * big) + 1e-6, 24)
            case = _local_case(f"contact/plane-torus/{where}-{tag}", "contact", tor, pl, cnt,
                               "generic" if sg else ("contact" if where == "outer" else "node"), pts, tor, small)
            case.samples = np.vstack([case.samples, extra]) if len(extra) else case.samples
            out.append(case)
    # sphere and a parallel-axis cylinder at the critical radii
    for name, (R, d, which) in (("far", (1.0, 0.4, "R+d")), ("node", (1.0, 0.45, "R-d")),
                                ("outside", (0.8, 1.7, "d-R"))):
        for sg, tag in signs:
            Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
            r = {"R+d": R + d, "R-d": R - d, "d-R": d - R}[which] + sg * EPS
            sph = sk.Sphere(R, F(o, Rm @ rot_z(rng.uniform(0, 6))))
            cyl = sk.Cylinder(r, F(o + d * Rm[:, 0], Rm), v_range=(-1.6 * R, 1.7 * R))
            cnt, pts = sphere_cylinder_truth(R, r, d)
            crit = {"R+d": np.array([-R, 0, 0]), "R-d": np.array([R, 0, 0]), "d-R": np.array([R, 0, 0])}[which]
            ref = sk.Sphere(R, F(o, Rm))
            if which == "R-d":
                extra = samples_near(sph, cyl, gpt(ref, crit), np.sqrt(2 * EPS) + 1e-6, 24)
            else:                           # an exact contact point, or a loop round it
                if sg == 0:
                    pts = crit[None]
                extra = loop_samples(sph, cyl, gpt(ref, crit)) if cnt and sg != 0 else np.zeros((0, 3))
            kd = "generic" if sg else ("node" if which == "R-d" else "contact")
            case = _local_case(f"contact/sphere-cylinder/{name}-{tag}", "contact", cyl, sph, cnt, kd, pts, ref, min(R, r))
            case.samples = np.vstack([case.samples, extra]) if len(extra) else case.samples
            out.append(case)
    # plane parallel to a cylinder's axis at distance r + g: two lines / tangent line / nothing
    for sg, tag in signs:
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        r = rng.uniform(0.4, 1.0)
        cyl = sk.Cylinder(r, F(o, Rm), v_range=(-1.5, 1.2))
        c = r + sg * EPS
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        pl = sk.Plane(F(o + c * Rm[:, 0], cols))
        z = np.linspace(-1.5, 1.2, 400)
        pts = []
        if c <= r:
            yy = np.sqrt(max(r * r - c * c, 0.0))
            for s in ((1,) if yy == 0 else (1, -1)):
                pts.append(np.stack([np.full_like(z, c), np.full_like(z, s * yy), z], -1))
        cnt = 0 if sg > 0 else (1 if sg == 0 else 2)
        out.append(_local_case(f"contact/plane-cylinder/{tag}", "contact", pl, cyl, cnt,
                               "tangent" if sg == 0 else "generic", np.vstack(pts) if pts else None, cyl, r))
    # parallel cylinders: external / internal tangency
    for mode in ("ext", "int"):
        for sg, tag in signs:
            Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
            r1, r2 = rng.uniform(0.3, 0.6), rng.uniform(0.8, 1.2)
            D = r1 + r2 + sg * EPS if mode == "ext" else r2 - r1 + sg * EPS
            c1 = sk.Cylinder(r1, F(o, Rm @ rot_z(rng.uniform(0, 6))), v_range=(-1.0, 1.3))
            c2 = sk.Cylinder(r2, F(o + D * Rm[:, 0], Rm), v_range=(-1.4, 0.9))
            # circles |p| = r1 and |p - (D, 0)| = r2 in the cross-section
            x = (D * D + r1 * r1 - r2 * r2) / (2 * D)
            yy2 = r1 * r1 - x * x
            z = np.linspace(-1.0, 0.9, 400)
            if abs(yy2) <= 1e-12:
                cnt, ys = 1, [0.0]
            elif yy2 > 0:
                cnt, ys = 2, [np.sqrt(yy2), -np.sqrt(yy2)]
            else:
                cnt, ys = 0, []
            pts = [np.stack([np.full_like(z, x), np.full_like(z, y), z], -1) for y in ys]
            ref = sk.Cylinder(r1, F(o, Rm))
            out.append(_local_case(f"contact/cylinder-cylinder/{mode}-{tag}", "contact", c1, c2, cnt,
                                   "tangent" if cnt == 1 else "generic", np.vstack(pts) if pts else None, ref, r1))
    # perpendicular cylinders near the Steinmetz configuration
    for tag, (dr, d) in (("offset+", (0.0, EPS)), ("wider", (EPS, 0.0)), ("narrower", (-EPS, 0.0))):
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        r = rng.uniform(0.5, 1.0)
        c1 = sk.Cylinder(r, F(o, Rm), v_range=(-2 * r, 2.2 * r))
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        c2 = sk.Cylinder(r + dr, F(o + d * Rm[:, 1], cols), v_range=(-2.1 * r, 2 * r))
        cnt, pts = perpendicular_cylinders_truth(r, r + dr, d)
        out.append(_local_case(f"contact/cylinder-cylinder/steinmetz-{tag}", "contact", c1, c2, cnt, "generic",
                               pts, sk.Cylinder(r, F(o, Rm)), r))
    # sphere touching a cone ruling from outside (isolated contact), and a sphere in a cone (tangent circle)
    for sg, tag in signs:
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        a = rng.uniform(20, 40) * DEG
        cone = sk.Cone(a, F(o, Rm), v_range=(-1.0, 2.0))
        t0 = rng.uniform(0.9, 1.4)
        e = np.array([np.sin(a), 0, np.cos(a)])
        nrm = np.array([np.cos(a), 0, -np.sin(a)])
        R = 0.25 * t0 * np.sin(a)
        centre = t0 * e + (R + sg * EPS) * nrm
        sph = sk.Sphere(R, F(gpt(cone, centre), rand_rot(rng)))
        cnt = 1 if sg <= 0 else 0
        pts = (loop_samples(cone, sph, gpt(cone, t0 * e)) if sg < 0 else gpt(cone, t0 * e)[None]) if sg <= 0 else None
        out.append(finish(Case(f"contact/sphere-cone/ruling-{tag}", "contact", sph, cone, cnt,
                               "contact" if sg == 0 else "generic", pts, scale=R)))
        H = rng.uniform(0.8, 1.4)
        sph2 = sk.Sphere(H * np.sin(a) + sg * EPS, F(o + H * Rm[:, 2], rand_rot(rng)))
        tr = coaxial_truth(cone, sph2, o, Rm[:, 2], H * np.sin(a))
        out.append(finish(Case(f"contact/sphere-cone/circle-{tag}", "contact", cone, sph2, tr["count"],
                               tr["kind"], tr["samples"], scale=H * np.sin(a))))
    # plane tangent to a cone along a ruling, offset by g (parabola on one nappe), one-nappe trim
    for sg, tag in signs:
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        a = rng.uniform(20, 40) * DEG
        h = 1.5
        cone = sk.Cone(a, F(o, Rm), v_range=(0.0, h))
        e1 = np.array([np.sin(a), 0, np.cos(a)])
        e2 = np.array([0.0, 1.0, 0.0])
        nrm = np.array([np.cos(a), 0, -np.sin(a)])
        delta = sg * EPS
        pl = sk.Plane(F(gpt(cone, delta * nrm), Rm @ np.column_stack([e2, e1, nrm])))
        if sg == 0:
            pts, cnt = np.outer(np.linspace(0, h / np.cos(a), 600), e1), 1
        else:
            s = np.concatenate([-np.geomspace(1e-12, h / np.cos(a) * 1.1, 800), np.geomspace(1e-12, h / np.cos(a) * 1.1, 800)])
            w2 = -2 * delta * np.tan(a) * s - delta ** 2 * np.cos(2 * a) / np.cos(a) ** 2
            ok = w2 >= 0
            ww = np.sqrt(w2[ok])
            pts = np.vstack([delta * nrm + s[ok, None] * e1 + sgn * ww[:, None] * e2 for sgn in (1, -1)])
            pts = pts[(pts[:, 2] >= 0) & (pts[:, 2] <= h)]
            cnt = 1 if sg < 0 else 0
        out.append(_local_case(f"contact/plane-cone/ruling-{tag}", "contact", cone, pl, cnt,
                               "tangent" if sg == 0 else "generic", pts, cone, 1.0))
    # coaxial tangencies of tori with cylinders, cones and tori
    for sg, tag in signs:
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        big, small = rng.uniform(1.2, 1.8), rng.uniform(0.3, 0.5)
        tor = sk.Torus(big, small, F(o, Rm @ rot_z(1.0)))
        w = Rm[:, 2]
        for which, r in (("outer", big + small), ("inner", big - small)):
            cyl = sk.Cylinder(r + sg * EPS, F(o, Rm), v_range=(-1.0, 1.0))
            tr = coaxial_truth(tor, cyl, o, w, small)
            out.append(finish(Case(f"contact/cylinder-torus/{which}-{tag}", "contact", cyl, tor, tr["count"],
                                   tr["kind"], tr["samples"], scale=small)))
        a = rng.uniform(25, 45) * DEG
        za = (small + sg * EPS - big * np.cos(a)) / np.sin(a)
        cone = sk.Cone(a, F(o + za * w, Rm), v_range=(0.0, 3.0))
        tr = coaxial_truth(tor, cone, o, w, small)
        out.append(finish(Case(f"contact/cone-torus/{tag}", "contact", tor, cone, tr["count"], tr["kind"],
                               tr["samples"], scale=small)))
        tor2 = sk.Torus(big + 2 * small + 0.3 + sg * EPS, 0.3, F(o, Rm @ rot_z(2.0)))
        tr = coaxial_truth(tor, tor2, o, w, 0.3)
        out.append(finish(Case(f"contact/torus-torus/{tag}", "contact", tor2, tor, tr["count"], tr["kind"],
                               tr["samples"], scale=0.3)))
    # two patches: the line of the other plane at the edge of a patch
    for sg, tag in signs:
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        pa = sk.Plane(F(o, Rm), u_range=(0.0, 1.0), v_range=(0.0, 1.0))
        x = 1.0 + sg * EPS
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        pb = sk.Plane(F(o + x * Rm[:, 0], cols), u_range=(-0.5, 1.5), v_range=(-1.0, 1.0))
        pts = np.stack([np.full(300, x), np.linspace(0, 1, 300), np.zeros(300)], -1) if sg <= 0 else None
        out.append(_local_case(f"contact/plane-plane/edge-{tag}", "contact", pb, pa, 1 if sg <= 0 else 0,
                               "generic", pts, pa, 1.0))
    return out


def _torus_sphere_critical_point(big, small, c, k):
    """The critical point of the distance to c on the torus that belongs to sorted critical radius k."""
    ang = np.arctan2(c[1], c[0])
    cands = []
    for side in (1, -1):
        core = np.array([side * big * np.cos(ang), side * big * np.sin(ang), 0.0])
        dv = c - core
        dn = np.linalg.norm(dv)
        for s in (1, -1):
            p = core + s * small * dv / dn
            cands.append((np.linalg.norm(p - c), p))
    cands.sort(key=lambda x: x[0])
    return cands[k][1]


def tiny_family(rng, sizes=(1e-6, 1e-5, 1e-4, 1e-3)):
    out = []
    for rho in sizes:
        tag = f"{rho:.0e}"
        # plane cutting a sphere cap of radius rho
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        R = rng.uniform(0.7, 1.5)
        d = np.sqrt(R * R - (rho * R) ** 2)
        sph = sk.Sphere(R, F(o, rand_rot(rng)))
        pl = sk.Plane(F(o + d * Rm[:, 2], Rm))
        r_true = np.sqrt((R - d) * (R + d))
        out.append(finish(Case(f"tiny/plane-sphere/{tag}", "tiny", pl, sph, 1, "generic",
                               circle_points(o + d * Rm[:, 2], Rm[:, 2], r_true, 64), scale=R)))
        # loops round a contact point: (a, b, contact point, scale)
        big, small = rng.uniform(1.2, 1.8), rng.uniform(0.3, 0.6)
        delta = (rho * small) ** 2 / (2 * small)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        tor = sk.Torus(big, small, F(o, Rm))
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        c = big + small - delta
        pl = sk.Plane(F(o + c * Rm[:, 0], cols))
        cases = [("plane-torus", tor, pl, o + (big + small) * Rm[:, 0], small)]
        # sphere-sphere (coaxial closed form)
        R1, R2 = rng.uniform(0.8, 1.4), rng.uniform(0.4, 0.8)
        dl = (rho * R2) ** 2 * (R1 + R2) / (2 * R1 * R2)
        o, w = rng.uniform(-1, 1, 3), rand_rot(rng)[:, 2]
        a = sk.Sphere(R1, F(o, rand_rot(rng)))
        b = sk.Sphere(R2, F(o + (R1 + R2 - dl) * w, rand_rot(rng)))
        tr = coaxial_truth(a, b, o, w, R2)
        out.append(finish(Case(f"tiny/sphere-sphere/{tag}", "tiny", b, a, tr["count"], tr["kind"], tr["samples"],
                               scale=R2)))
        # sphere outside a cylinder
        R, r = rng.uniform(0.5, 1.0), rng.uniform(0.4, 0.9)
        s_ = min(R, r)
        dl = (rho * s_) ** 2 / (2 * s_)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        cyl = sk.Cylinder(r, F(o, Rm), v_range=(-1.0, 1.1))
        sph = sk.Sphere(R, F(o + (R + r - dl) * Rm[:, 0], rand_rot(rng)))
        cases.append(("sphere-cylinder", sph, cyl, o + r * Rm[:, 0], s_))
        # sphere outside a torus at its outer equator
        big, small = rng.uniform(1.2, 1.8), rng.uniform(0.3, 0.6)
        Rs = rng.uniform(0.3, 0.8)
        s_ = min(small, Rs)
        dl = (rho * s_) ** 2 / (2 * s_)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        tor = sk.Torus(big, small, F(o, Rm))
        sph = sk.Sphere(Rs, F(o + (big + small + Rs - dl) * Rm[:, 0], rand_rot(rng)))
        cases.append(("sphere-torus", tor, sph, o + (big + small) * Rm[:, 0], s_))
        # perpendicular cylinders at axis distance r1 + r2 - delta
        r1, r2 = rng.uniform(0.4, 0.9), rng.uniform(0.4, 0.9)
        s_ = min(r1, r2)
        dl = (rho * s_) ** 2 / (2 * s_)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        c1 = sk.Cylinder(r1, F(o, Rm), v_range=(-1.0, 1.0))
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        c2 = sk.Cylinder(r2, F(o + (r1 + r2 - dl) * Rm[:, 1], cols), v_range=(-1.0, 1.0))
        cases.append(("cylinder-cylinder", c1, c2, o + r1 * Rm[:, 1], s_))
        # coplanar tori touching at their outer equators
        b1, s1, b2, s2 = rng.uniform(1.0, 1.5), rng.uniform(0.3, 0.5), rng.uniform(0.8, 1.2), rng.uniform(0.3, 0.5)
        s_ = min(s1, s2)
        dl = (rho * s_) ** 2 / (2 * s_)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        t1 = sk.Torus(b1, s1, F(o, Rm))
        t2 = sk.Torus(b2, s2, F(o + (b1 + s1 + b2 + s2 - dl) * Rm[:, 0], Rm @ rot_z(0.7)))
        cases.append(("torus-torus", t2, t1, o + (b1 + s1) * Rm[:, 0], s_))
        # sphere just into a cone ruling
        a_ = rng.uniform(20, 40) * DEG
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        cone = sk.Cone(a_, F(o, Rm), v_range=(-1.0, 2.0))
        t0 = rng.uniform(0.9, 1.4)
        e = np.array([np.sin(a_), 0, np.cos(a_)])
        nrm = np.array([np.cos(a_), 0, -np.sin(a_)])
        Rs = 0.25 * t0 * np.sin(a_)
        dl = (rho * Rs) ** 2 / (2 * Rs)
        sph = sk.Sphere(Rs, F(gpt(cone, t0 * e + (Rs - dl) * nrm), rand_rot(rng)))
        cases.append(("sphere-cone", cone, sph, gpt(cone, t0 * e), Rs))
        # cylinder parallel to a torus axis, outside it
        big, small = rng.uniform(1.2, 1.8), rng.uniform(0.3, 0.6)
        rc = rng.uniform(0.3, 0.7)
        s_ = min(small, rc)
        dl = (rho * s_) ** 2 / (2 * s_)
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        tor = sk.Torus(big, small, F(o, Rm))
        cyl = sk.Cylinder(rc, F(o + (big + small + rc - dl) * Rm[:, 0], Rm @ rot_z(0.3)), v_range=(-1.0, 1.0))
        cases.append(("cylinder-torus", cyl, tor, o + (big + small) * Rm[:, 0], s_))
        for name, a, b, cp, sc in cases:
            pts = loop_samples(a, b, cp, 32)
            out.append(finish(Case(f"tiny/{name}/{tag}", "tiny", a, b, 1, "generic", pts, scale=sc)))
        # a tiny circle round a cone's apex (plane perpendicular to the axis)
        a_ = rng.uniform(20, 50) * DEG
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        cone = sk.Cone(a_, F(o, Rm), v_range=(-1.0, 1.5))
        pl = sk.Plane(F(o + (rho / np.tan(a_)) * Rm[:, 2], Rm))
        tr = coaxial_truth(cone, pl, o, Rm[:, 2], 1.0)
        out.append(finish(Case(f"tiny/plane-cone/{tag}", "tiny", pl, cone, tr["count"], tr["kind"], tr["samples"],
                               scale=1.0)))
    return out


def villarceau_family(rng, n=6):
    out = []
    for i in range(n):
        big = rng.uniform(1.0, 2.0)
        small = big * rng.uniform(0.2, 0.6)
        Rm, o = rand_rot(rng), rng.uniform(-2, 2, 3)
        tor = sk.Torus(big, small, F(o, Rm))
        th = np.arcsin(small / big)
        ey = np.array([0.0, 1.0, 0.0])
        e2 = np.array([np.cos(th), 0.0, np.sin(th)])
        nrm = np.array([-np.sin(th), 0.0, np.cos(th)])
        ur = vr = None
        if i % 3 == 2:
            ur = vr = (-3 * big, 3 * big)
        pl = sk.Plane(F(o, Rm @ np.column_stack([e2, ey, nrm])), u_range=ur, v_range=vr)
        t = np.linspace(0, 2 * np.pi, 720, endpoint=False)
        pts = np.vstack([np.outer(np.ones_like(t), s * small * ey) + big * (np.cos(t)[:, None] * ey +
                                                                           np.sin(t)[:, None] * e2)
                         for s in (1, -1)])
        a, b = (tor, pl) if i % 2 == 0 else (pl, tor)
        out.append(_local_case(f"villarceau/plane-torus/{i}", "villarceau", a, b, 1, "node", pts, tor, small))
    return out


def steinmetz_family(rng):
    out = []
    for i in range(3):
        r = rng.uniform(0.4, 1.2)
        Rm, o = rand_rot(rng), rng.uniform(-2, 2, 3)
        c1 = sk.Cylinder(r, F(o, Rm @ rot_z(rng.uniform(0, 6))), v_range=(-2 * r, 1.8 * r))
        cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
        c2 = sk.Cylinder(r, F(o, cols), v_range=(-1.9 * r, 2.1 * r))
        cnt, pts = perpendicular_cylinders_truth(r, r, 0.0)
        ref = sk.Cylinder(r, F(o, Rm))
        a, b = (c1, c2) if i % 2 == 0 else (c2, c1)
        out.append(_local_case(f"steinmetz/cylinder-cylinder/perpendicular-{i}", "steinmetz", a, b, cnt, "node", pts,
                               ref, r))
    for i in range(2):
        r = rng.uniform(0.4, 1.2)
        phi = rng.uniform(50, 80) * DEG
        Rm, o = rand_rot(rng), rng.uniform(-2, 2, 3)
        w1 = np.array([0.0, 0.0, 1.0])
        w2 = np.array([np.sin(phi), 0.0, np.cos(phi)])
        nn = np.cross(w1, w2)
        nn /= np.linalg.norm(nn)                      # common perpendicular (local y)
        ext = 1.5 * r * (1 + 1 / (1 - np.cos(phi)))
        c1 = sk.Cylinder(r, F(o, Rm), v_range=(-ext, ext))
        e1b = np.cross(nn, w2)
        c2 = sk.Cylinder(r, F(o, Rm @ np.column_stack([e1b, nn, w2])), v_range=(-ext, 1.1 * ext))
        t = np.linspace(0, 2 * np.pi, 1500, endpoint=False)
        e1 = np.cross(nn, w1)
        pts = []
        for sgn in (1, -1):
            z = sgn * r * np.cos(t) * (e1 @ w2) / (1 - sgn * (w1 @ w2))
            pts.append(r * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * nn) + z[:, None] * w1)
        out.append(_local_case(f"steinmetz/cylinder-cylinder/oblique-{i}", "steinmetz", c1, c2, 1, "node",
                               np.vstack(pts), c1, r))
    r = 0.8
    Rm, o = rand_rot(rng), rng.uniform(-2, 2, 3)
    c1 = sk.Cylinder(r, F(o, Rm), v_range=(-2, 2))
    cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
    c2 = sk.Cylinder(1.1 * r, F(o, cols), v_range=(-2, 2))
    cnt, pts = perpendicular_cylinders_truth(r, 1.1 * r, 0.0)
    out.append(_local_case("steinmetz/cylinder-cylinder/unequal", "steinmetz", c2, c1, cnt, "generic", pts, c1, r))
    return out


def viviani_family(rng, n=4):
    out = []
    for i in range(n):
        R = rng.uniform(0.5, 2.0)
        Rm, o = rand_rot(rng), rng.uniform(-2, 2, 3)
        sph = sk.Sphere(R, F(o, Rm @ rot_z(rng.uniform(0, 6)) if i % 2 else rand_rot(rng)))
        cyl = sk.Cylinder(R / 2, F(o + (R / 2) * Rm[:, 0], Rm), v_range=(-1.5 * R, 1.4 * R) if i < 2 else None)
        t = np.linspace(0, 2 * np.pi, 1500, endpoint=False)
        pts = np.stack([R * np.cos(t) ** 2, R * np.cos(t) * np.sin(t), R * np.sin(t)], -1)
        a, b = (sph, cyl) if i % 2 == 0 else (cyl, sph)
        out.append(_local_case(f"viviani/sphere-cylinder/{i}", "viviani", a, b, 1, "node", pts,
                               sk.Sphere(R, F(o, Rm)), R / 2))
    return out


def trimmed_family(rng):
    out = []

    def add(name, a, b, curves, scale, tries, extra=None):
        cnt, pts, robust = clipped(a, b, curves, scale)
        if not robust:
            return False
        if extra is not None:
            pts = np.vstack([pts, extra[margins(a, b, extra) >= 0]])
        out.append(finish(Case(f"trimmed/{name}", "trimmed", a, b, cnt, "generic", pts, scale=scale)))
        return True

    def rect(c, half):
        return (c[0] - half[0], c[0] + half[0]), (c[1] - half[1], c[1] + half[1])

    def perpendicular_patch(o, Rm, spin, c, radius):
        """A random rectangle (sides and centre in units of radius) in the plane z = c of the frame (o, Rm), and
        the circle of that radius about the z axis in it (closed)."""
        half = rng.uniform(0.2, 1.2, 2) * radius
        centre = rng.uniform(-1.2, 1.2, 2) * radius
        ur, vr = rect(centre, half)
        pl = sk.Plane(F(o + c * Rm[:, 2], spin), u_range=ur, v_range=vr)
        return pl, [(circle_points(o + c * Rm[:, 2], Rm[:, 2], radius, 20000), True)]

    made = {}

    def want(key, n):
        return made.get(key, 0) < n

    for attempt in range(3000):
        kind_ = ["torus-perp", "torus-axial", "sphere", "cyl-perp", "cyl-par", "cone-perp", "planes",
                 "sphere-trimcyl"][attempt % 8]
        if not want(kind_, 4):
            continue
        Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
        spin = Rm @ rot_z(rng.uniform(0, 6))
        if kind_ == "torus-perp":
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            tor = sk.Torus(big, small, F(o, Rm))
            c = rng.uniform(-0.9, 0.9) * small
            half = rng.uniform(0.3, 1.5, 2) * big
            centre = rng.uniform(-1.5, 1.5, 2) * big
            ur, vr = rect(centre, half)
            pl = sk.Plane(F(o + c * Rm[:, 2], Rm), u_range=ur, v_range=vr)
            curves = [(circle_points(o + c * Rm[:, 2], Rm[:, 2], big + s * np.sqrt(small ** 2 - c ** 2), 20000), True)
                      for s in (1, -1)]
            ok = add(f"plane-torus/perp-{made.get(kind_, 0)}", pl, tor, curves, small, attempt)
        elif kind_ == "torus-axial":
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            tor = sk.Torus(big, small, F(o, Rm))
            cols = np.column_stack([Rm[:, 0], Rm[:, 2], -Rm[:, 1]])       # plane containing the axis
            half = rng.uniform(0.3, 1.2, 2) * np.array([big, small * 2])
            centre = np.array([rng.uniform(-1.5, 1.5) * big, rng.uniform(-1, 1) * small])
            ur, vr = rect(centre, half)
            pl = sk.Plane(F(o, cols), u_range=ur, v_range=vr)
            curves = [(circle_points(o + s * big * Rm[:, 0], Rm[:, 1], small, 20000), True) for s in (1, -1)]
            ok = add(f"plane-torus/axial-{made.get(kind_, 0)}", tor, pl, curves, small, attempt)
        elif kind_ == "sphere":
            R = rng.uniform(0.6, 1.5)
            sph = sk.Sphere(R, F(o, rand_rot(rng)))
            c = rng.uniform(-0.9, 0.9) * R
            half = rng.uniform(0.2, 1.2, 2) * R
            centre = rng.uniform(-1.2, 1.2, 2) * R
            ur, vr = rect(centre, half)
            pl = sk.Plane(F(o + c * Rm[:, 2], spin), u_range=ur, v_range=vr)
            curves = [(circle_points(o + c * Rm[:, 2], Rm[:, 2], np.sqrt(R * R - c * c), 20000), True)]
            ok = add(f"plane-sphere/{made.get(kind_, 0)}", pl, sph, curves, R, attempt)
        elif kind_ == "cyl-perp":
            r = rng.uniform(0.4, 1.2)
            cyl = sk.Cylinder(r, F(o, Rm), v_range=(-1.0, 1.0))
            c = rng.uniform(-0.9, 0.9)
            pl, curves = perpendicular_patch(o, Rm, spin, c, r)
            ok = add(f"plane-cylinder/perp-{made.get(kind_, 0)}", cyl, pl, curves, r, attempt)
        elif kind_ == "cyl-par":
            r = rng.uniform(0.4, 1.2)
            lo, hi = -rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5)
            cyl = sk.Cylinder(r, F(o, Rm), v_range=(lo, hi))
            c = rng.uniform(-0.9, 0.9) * r
            cols = np.column_stack([Rm[:, 1], Rm[:, 2], Rm[:, 0]])
            half = np.array([rng.uniform(0.2, 1.2) * r, rng.uniform(0.3, 1.5)])
            centre = np.array([rng.uniform(-1.2, 1.2) * r, rng.uniform(-1.5, 1.5)])
            ur, vr = rect(centre, half)
            pl = sk.Plane(F(o + c * Rm[:, 0], cols), u_range=ur, v_range=vr)
            yy = np.sqrt(r * r - c * c)
            z = np.linspace(lo - 0.5, hi + 0.5, 20000)
            curves = [(gpt(sk.Cylinder(r, F(o, Rm)), np.stack([np.full_like(z, c), np.full_like(z, s * yy), z], -1)),
                       False) for s in (1, -1)]
            ok = add(f"plane-cylinder/parallel-{made.get(kind_, 0)}", pl, cyl, curves, r, attempt)
        elif kind_ == "cone-perp":
            a_ = rng.uniform(20, 50) * DEG
            cone = sk.Cone(a_, F(o, Rm), v_range=(-1.5, 1.5))
            c = rng.uniform(0.3, 1.3) * rng.choice([-1, 1])
            rr = abs(c) * np.tan(a_)
            pl, curves = perpendicular_patch(o, Rm, spin, c, rr)
            ok = add(f"plane-cone/perp-{made.get(kind_, 0)}", pl, cone, curves, rr, attempt)
        elif kind_ == "planes":
            R2 = rand_rot(rng)
            pa = sk.Plane(F(o, Rm), u_range=(-rng.uniform(0.3, 1), rng.uniform(0.3, 1)),
                          v_range=(-rng.uniform(0.3, 1), rng.uniform(0.3, 1)))
            pb = sk.Plane(F(o + rng.uniform(-0.5, 0.5, 3), R2), u_range=(-rng.uniform(0.3, 1), rng.uniform(0.3, 1)),
                          v_range=(-rng.uniform(0.3, 1), rng.uniform(0.3, 1)))
            na, nb = Rm[:, 2], R2[:, 2]
            dirn = np.cross(na, nb)
            dirn /= np.linalg.norm(dirn)
            A = np.array([na, nb, dirn])
            p0 = np.linalg.solve(A, [na @ o, nb @ frame_of(pb)[0], dirn @ o])
            t = np.linspace(-4, 4, 40000)
            curves = [(p0 + t[:, None] * dirn, False)]
            ok = add(f"plane-plane/{made.get(kind_, 0)}", pa, pb, curves, 0.5, attempt)
        else:
            R = rng.uniform(0.8, 1.5)
            d = rng.uniform(0.1, 0.6) * R
            r = rng.uniform(0.2, 0.9) * (R - d) if rng.random() < 0.5 else rng.uniform(1.05, 1.5) * (R - d)
            lo, hi = sorted(rng.uniform(-1.1, 1.1, 2) * R)
            sph = sk.Sphere(R, F(o, spin))
            cyl = sk.Cylinder(r, F(o + d * Rm[:, 0], Rm), v_range=(lo, hi))
            u = np.linspace(0, 2 * np.pi, 20000, endpoint=False)
            z2 = R * R - d * d - r * r - 2 * d * r * np.cos(u)
            ref = sk.Sphere(R, F(o, Rm))
            if np.all(z2 > 0):
                curves = [(gpt(ref, np.stack([d + r * np.cos(u), r * np.sin(u), s * np.sqrt(z2)], -1)), True)
                          for s in (1, -1)]
            elif np.any(z2 > 0):
                # one loop: z = +sqrt on the allowed u arc and back along -sqrt (arc round the seam of z2 >= 0)
                uu = u[z2 >= 0]
                k0 = np.argmax(np.diff(np.concatenate([uu, uu[:1] + 2 * np.pi])))
                uu = np.roll(uu, -(k0 + 1))
                zz = np.sqrt(np.maximum(R * R - d * d - r * r - 2 * d * r * np.cos(uu), 0))
                loop = np.concatenate([np.stack([d + r * np.cos(uu), r * np.sin(uu), zz], -1),
                                       np.stack([d + r * np.cos(uu), r * np.sin(uu), -zz], -1)[::-1]])
                curves = [(gpt(ref, loop), True)]
            else:
                continue
            extra = gpt(ref, sphere_cylinder_truth(R, r, d)[1])
            ok = add(f"sphere-cylinder/trimmed-{made.get(kind_, 0)}", cyl, sph, curves, min(r, R), attempt, extra)
        if ok:
            made[kind_] = made.get(kind_, 0) + 1
    # patches that miss the curves entirely (one far beside the torus, one over its hole)
    out.append(finish(Case("trimmed/plane-torus/miss-far", "trimmed", sk.Torus(2.0, 0.5),
                           sk.Plane(u_range=(5, 6), v_range=(5, 6)), 0, "generic", None, scale=0.5)))
    out.append(finish(Case("trimmed/plane-torus/miss-hole", "trimmed", sk.Plane(u_range=(-1, 1), v_range=(-1, 1)),
                           sk.Torus(2.0, 0.5), 0, "generic", None, scale=0.5)))
    # sphere cut by the plane z = 0.5 (circle of radius 0.866) and a patch beyond the circle, turned as a whole
    Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
    out.append(finish(Case("trimmed/plane-sphere/miss", "trimmed", sk.Sphere(1.0, F(o, rand_rot(rng))),
                           sk.Plane(F(o + 0.5 * Rm[:, 2], Rm), u_range=(0.9, 2.0), v_range=(-0.5, 0.5)),
                           0, "generic", None, scale=1.0)))
    return out


def face_family(rng, per_kind=4):
    """CAD faces (angular ranges of cylinders, cones, spheres and tori, a sphere's zone, a plane's disc or
    annulus) cut by a second surface along closed-form circles and ellipses: the truth is the curves clipped by
    the oracle's face margins (atan2 angles, independent of spatialkin's half-planes); cases whose curve grazes
    an edge or passes near a corner are skipped (clipped's robust flag)."""
    out, made = [], {}

    def turn(lo_width=0.4, hi_width=2 * np.pi - 0.4):
        lo = rng.uniform(-np.pi, np.pi)
        return lo, lo + rng.uniform(lo_width, hi_width)

    def frame():
        return rand_rot(rng), rng.uniform(-1, 1, 3)

    for attempt in range(4000):
        name = ["sphere-face/plane", "torus-face/perp-plane", "half-cylinder/perp-plane", "cylinder-strip/plane",
                "cone-face/perp-plane", "disc/sphere", "disc/cylinder", "annulus/torus", "sphere-zone/sphere",
                "cylinder-strip/sphere", "cone-face/sphere", "torus-face/meridian-plane"][attempt % 12]
        if made.get(name, 0) >= per_kind:
            continue
        Rm, o = frame()
        z = Rm[:, 2]
        if name == "sphere-face/plane":
            R = rng.uniform(0.5, 2.0)
            zone = np.sort(rng.uniform(-np.pi / 2, np.pi / 2, 2)) if rng.uniform() < 0.7 else (-np.pi / 2, 1.0)
            a = sk.Sphere(R, F(o, Rm), u_range=turn(), v_range=tuple(zone))
            n = rand_rot(rng)[:, 2]
            d = rng.uniform(-0.9, 0.9) * R
            b = sk.Plane(F(o + d * n, _frame_with_z(n)))
            curves = [(circle_points(o + d * n, n, np.sqrt(R ** 2 - d ** 2), 20000), True)]
            scale = R
        elif name == "torus-face/perp-plane":
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            a = sk.Torus(big, small, F(o, Rm), u_range=turn(), v_range=turn() if rng.uniform() < 0.7 else None)
            c = rng.uniform(-0.9, 0.9) * small
            b = sk.Plane(F(o + c * z, Rm @ rot_z(rng.uniform(0, 6))))
            curves = [(circle_points(o + c * z, z, big + sg * np.sqrt(small ** 2 - c ** 2), 20000), True)
                      for sg in (1, -1)]
            scale = small
        elif name == "half-cylinder/perp-plane":
            r = rng.uniform(0.5, 1.5)
            a = sk.Cylinder(r, F(o, Rm), v_range=(-2.0, 2.0), u_range=turn())
            c = rng.uniform(-1.5, 1.5)
            b = sk.Plane(F(o + c * z, Rm @ rot_z(rng.uniform(0, 6))))
            curves = [(circle_points(o + c * z, z, r, 20000), True)]
            scale = r
        elif name == "cylinder-strip/plane":
            r = rng.uniform(0.5, 1.5)
            a = sk.Cylinder(r, F(o, Rm), v_range=(-4.0, 4.0), u_range=turn())
            tilt = rng.uniform(0.1, 0.9)
            n_loc = np.array([np.sin(tilt), 0.0, np.cos(tilt)]) @ rot_z(rng.uniform(0, 6)).T
            c = rng.uniform(-1.0, 1.0)
            t = np.linspace(0.0, 2 * np.pi, 20000, endpoint=False)
            zz = c - (n_loc[0] * r * np.cos(t) + n_loc[1] * r * np.sin(t)) / n_loc[2]
            local = np.stack([r * np.cos(t), r * np.sin(t), zz], axis=1)
            b = sk.Plane(F(o + c * z, _frame_with_z(Rm @ n_loc)))
            curves = [(o + local @ Rm.T, True)]
            scale = r
        elif name == "cone-face/perp-plane":
            half = rng.uniform(0.3, 1.0)
            a = sk.Cone(half, F(o, Rm), v_range=(-2.0, 2.0), u_range=turn())
            h = rng.choice([-1.0, 1.0]) * rng.uniform(0.3, 1.8)
            b = sk.Plane(F(o + h * z, Rm @ rot_z(rng.uniform(0, 6))))
            curves = [(circle_points(o + h * z, z, abs(h) * np.tan(half), 20000), True)]
            scale = abs(h) * np.tan(half)
        elif name == "disc/sphere":
            radius = rng.uniform(0.5, 1.5)
            inner = rng.uniform(0.1, 0.8) * radius if rng.uniform() < 0.5 else None
            a = sk.Plane(F(o, Rm), radius=radius, inner_radius=inner)
            off = np.array([*rng.uniform(-1, 1, 2) * radius, rng.uniform(-0.5, 0.5)])
            rho = rng.uniform(abs(off[2]) + 0.2, 2.0 * radius + abs(off[2]))
            b = sk.Sphere(rho, F(o + Rm @ off, rand_rot(rng)))
            foot = o + Rm @ np.array([off[0], off[1], 0.0])
            curves = [(circle_points(foot, z, np.sqrt(rho ** 2 - off[2] ** 2), 20000), True)]
            scale = radius
        elif name == "disc/cylinder":
            radius = rng.uniform(0.5, 1.5)
            a = sk.Plane(F(o, Rm), radius=radius, inner_radius=rng.uniform(0.1, 0.6) * radius)
            off = np.array([*rng.uniform(-1, 1, 2) * radius, 0.0])
            r = rng.uniform(0.2, 1.5) * radius
            b = sk.Cylinder(r, F(o + Rm @ off, Rm @ rot_z(rng.uniform(0, 6))), v_range=(-1.0, 1.0))
            curves = [(circle_points(o + Rm @ off, z, r, 20000), True)]
            scale = min(radius, r)
        elif name == "annulus/torus":
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            c = rng.uniform(-0.9, 0.9) * small
            cut = np.sqrt(small ** 2 - c ** 2)
            outer = rng.uniform(0.3, 1.0) * (big + 1.5 * cut)
            a = sk.Plane(F(o + c * z, Rm), radius=outer, inner_radius=rng.uniform(0.0, 0.9) * outer)
            b = sk.Torus(big, small, F(o, Rm @ rot_z(rng.uniform(0, 6))))
            curves = [(circle_points(o + c * z, z, big + sg * cut, 20000), True) for sg in (1, -1)]
            scale = small
        elif name == "cylinder-strip/sphere":           # off the axis, holding it: two loops z = cz +- sqrt(...)
            r = rng.uniform(0.5, 1.0)
            rho = rng.uniform(1.3, 2.0) * r
            cxy = rng.uniform(-1, 1, 2) * (rho - r) * 0.6
            cz = rng.uniform(-0.5, 0.5)
            a = sk.Cylinder(r, F(o, Rm), v_range=(-4.0, 4.0), u_range=turn())
            b = sk.Sphere(rho, F(o + Rm @ np.array([*cxy, cz]), rand_rot(rng)))
            t = np.linspace(0.0, 2 * np.pi, 20000, endpoint=False)
            h = np.sqrt(rho ** 2 - (r * np.cos(t) - cxy[0]) ** 2 - (r * np.sin(t) - cxy[1]) ** 2)
            curves = [(o + np.stack([r * np.cos(t), r * np.sin(t), cz + sg * h], axis=1) @ Rm.T, True)
                      for sg in (1, -1)]
            scale = r
        elif name == "cone-face/sphere":                 # the sphere holds the apex: one loop on each nappe
            half = rng.uniform(0.3, 1.0)
            ta = np.tan(half)
            c = rng.uniform(-0.3, 0.3, 3)
            rho = rng.uniform(0.6, 1.2)
            a = sk.Cone(half, F(o, Rm), v_range=(-3.0, 3.0), u_range=turn())
            b = sk.Sphere(rho, F(o + Rm @ c, rand_rot(rng)))
            t = np.linspace(0.0, 2 * np.pi, 20000, endpoint=False)
            qa, qb, qc = 1 + ta ** 2, -2 * (ta * (c[0] * np.cos(t) + c[1] * np.sin(t)) + c[2]), c @ c - rho ** 2
            disc = np.sqrt(qb ** 2 - 4 * qa * qc)
            curves = []
            for sg in (1, -1):
                v = (-qb + sg * disc) / (2 * qa)
                curves.append((o + np.stack([v * ta * np.cos(t), v * ta * np.sin(t), v], axis=1) @ Rm.T, True))
            scale = rho
        elif name == "torus-face/meridian-plane":        # a plane through the axis: the two tube circles
            big, small = rng.uniform(1.2, 2.0), rng.uniform(0.3, 0.6)
            a = sk.Torus(big, small, F(o, Rm), u_range=turn(), v_range=turn() if rng.uniform() < 0.5 else None)
            phi = rng.uniform(0, 2 * np.pi)
            e = Rm @ np.array([np.cos(phi), np.sin(phi), 0.0])
            n = np.cross(z, e)
            b = sk.Plane(F(o + rng.uniform(-1, 1) * z, _frame_with_z(n)))
            curves = [(circle_points(o + sg * big * e, n, small, 20000), True) for sg in (1, -1)]
            scale = small
        else:                                            # sphere-zone/sphere
            R = rng.uniform(0.5, 2.0)
            a = sk.Sphere(R, F(o, Rm), u_range=turn() if rng.uniform() < 0.5 else None,
                          v_range=tuple(np.sort(rng.uniform(-np.pi / 2, np.pi / 2, 2))))
            n = rand_rot(rng)[:, 2]
            d = rng.uniform(0.3, 1.5) * R
            rho = rng.uniform(abs(R - d) + 0.05 * R, R + d - 0.05 * R)
            b = sk.Sphere(rho, F(o + d * n, rand_rot(rng)))
            x = (d ** 2 + R ** 2 - rho ** 2) / (2 * d)          # the plane of the circle, from a's centre
            curves = [(circle_points(o + x * n, n, np.sqrt(R ** 2 - x ** 2), 20000), True)]
            scale = min(R, rho)
        cnt, pts, robust = clipped(a, b, curves, scale)
        if not robust:
            continue
        out.append(finish(Case(f"face/{name}-{made.get(name, 0)}", "face", a, b, cnt, "generic", pts, scale=scale)))
        made[name] = made.get(name, 0) + 1
    return out


def _frame_with_z(n):
    """A rotation (3, 3) whose third column is the unit vector n."""
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    e1 = np.cross(n, [1.0, 0.0, 0.0])
    if np.linalg.norm(e1) < 0.5:
        e1 = np.cross(n, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    return np.column_stack([e1, np.cross(n, e1), n])


def tangent_family(rng):
    """Tangency along a curve (and a few isolated contacts), from the coaxial closed form."""
    out = []
    e = np.eye(3)

    def coax(name, a, b, o, w, scale, expect=None):
        tr = coaxial_truth(a, b, np.asarray(o, float), np.asarray(w, float), scale)
        if expect is not None:
            assert tr["count"] == expect, (name, tr["count"], expect)
        out.append(finish(Case(f"tangent/{name}", "tangent", a, b, tr["count"], tr["kind"], tr["samples"],
                               scale=scale)))

    z = (0, 0, 0)
    coax("plane-torus/top", sk.Torus(2.0, 0.5), sk.Plane(F((0, 0, 0.5))), z, e[2], 0.5, 1)
    coax("plane-torus/bottom", sk.Plane(F((0, 0, -0.5), FLIP)), sk.Torus(2.0, 0.5), z, e[2], 0.5, 1)
    Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
    coax("plane-torus/rotated", sk.Torus(1.5, 0.4, F(o, Rm)), sk.Plane(F(o + 0.4 * Rm[:, 2], Rm)), o, Rm[:, 2], 0.4, 1)
    coax("sphere-cylinder/equator", sk.Sphere(1.5), sk.Cylinder(1.5, v_range=(-1, 1)), z, e[2], 1.5, 1)
    coax("sphere-cylinder/equator-untrimmed", sk.Cylinder(1.5), sk.Sphere(1.5), z, e[2], 1.5, 1)
    coax("sphere-cylinder/trimmed-away", sk.Sphere(1.5), sk.Cylinder(1.5, v_range=(0.25, 1)), z, e[2], 1.5, 0)
    Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
    coax("sphere-cylinder/rotated", sk.Sphere(0.75, F(o, rand_rot(rng))), sk.Cylinder(0.75, F(o, Rm), v_range=(-1, 0.5)),
         o, Rm[:, 2], 0.75, 1)
    coax("sphere-torus/inner", sk.Sphere(1.5), sk.Torus(2.0, 0.5), z, e[2], 0.5, 1)
    coax("sphere-torus/outer", sk.Torus(2.0, 0.5), sk.Sphere(2.5), z, e[2], 0.5, 1)
    coax("cylinder-torus/inner", sk.Cylinder(1.5, v_range=(-1, 1)), sk.Torus(2.0, 0.5), z, e[2], 0.5, 1)
    coax("cylinder-torus/outer", sk.Torus(2.0, 0.5), sk.Cylinder(2.5, v_range=(-1, 1)), z, e[2], 0.5, 1)
    coax("torus-torus/side", sk.Torus(2.0, 0.5), sk.Torus(3.0, 0.5), z, e[2], 0.5, 1)
    coax("torus-torus/stacked", sk.Torus(2.0, 0.5), sk.Torus(2.0, 0.5, F((0, 0, 1.0))), z, e[2], 0.5, 1)
    a_ = np.radians(30)
    coax("sphere-cone/inscribed", sk.Cone(a_, v_range=(-1, 3)), sk.Sphere(2.0 * np.sin(a_), F((0, 0, 2.0))), z, e[2],
         1.0, 1)
    coax("sphere-sphere/internal-point", sk.Sphere(1.0), sk.Sphere(0.5, F((0, 0, 0.5))), z, e[2], 0.5, 1)
    coax("plane-sphere/pole-point", sk.Sphere(1.0), sk.Plane(F((0, 0, 1.0))), z, e[2], 1.0, 1)
    coax("plane-cone/apex-point", sk.Cone(a_, v_range=(-1, 1)), sk.Plane(F((0, 0, 0))), z, e[2], 1.0, 1)
    # cylinder on a plane along a line, and along part of a patch
    for k, (ur, vr) in enumerate(((None, None), ((-3, 3), (-0.5, 0.7)))):
        cols = np.column_stack([e[1], e[2], e[0]])
        cyl = sk.Cylinder(1.0, v_range=(-2, 2))
        pl = sk.Plane(F((1.0, 0, 0), cols), u_range=ur, v_range=vr)
        zz = np.linspace(-2, 2, 800)
        pts = np.stack([np.ones_like(zz), np.zeros_like(zz), zz], -1)
        pts = pts[margins(cyl, pl, pts) >= 0]
        out.append(finish(Case(f"tangent/plane-cylinder/line-{k}", "tangent", pl if k else cyl, cyl if k else pl, 1,
                               "tangent", pts, scale=1.0)))
    # parallel cylinders touching along a line (outside, inside)
    for k, (r1, r2, D) in enumerate(((0.5, 0.75, 1.25), (0.5, 1.25, 0.75))):
        c1 = sk.Cylinder(r1, v_range=(-1, 1))
        c2 = sk.Cylinder(r2, F((D, 0, 0)), v_range=(-0.5, 1.5))
        zz = np.linspace(-0.5, 1, 600)
        x = r1 if k == 0 else -r1
        pts = np.stack([np.full_like(zz, x), np.zeros_like(zz), zz], -1)
        out.append(finish(Case(f"tangent/cylinder-cylinder/line-{k}", "tangent", c1, c2, 1, "tangent", pts, scale=r1)))
    # a plane tangent to a cone along a ruling (the full line through the apex)
    e1 = np.array([np.sin(a_), 0, np.cos(a_)])
    nrm = np.array([np.cos(a_), 0, -np.sin(a_)])
    pl = sk.Plane(F(z, np.column_stack([e[1], e1, nrm])))
    cone = sk.Cone(a_, v_range=(-1.0, 1.5))
    t = np.linspace(-1.0 / np.cos(a_), 1.5 / np.cos(a_), 900)
    out.append(finish(Case("tangent/plane-cone/ruling", "tangent", pl, cone, 1, "tangent", np.outer(t, e1), scale=1.0)))
    return out


def simple_family():
    out = []
    z, e = np.zeros(3), np.eye(3)

    def coax(name, a, b, scale, expect):
        tr = coaxial_truth(a, b, z, e[2], scale)
        assert tr["count"] == expect and tr["kind"] != "coincident", (name, tr)
        out.append(finish(Case(f"simple/{name}", "simple", a, b, tr["count"], tr["kind"], tr["samples"], scale=scale)))

    coax("sphere10-cylinder5", sk.Sphere(10.0), sk.Cylinder(5.0, v_range=(-12, 12)), 5.0, 2)
    coax("sphere10-plane-z3", sk.Sphere(10.0), sk.Plane(F((0, 0, 3))), 10.0, 1)
    coax("cone30-sphere5", sk.Cone(np.radians(30), v_range=(0, 10)), sk.Sphere(5.0), 5.0, 1)
    coax("sphere1-plane-z0.3", sk.Sphere(1.0), sk.Plane(F((0, 0, 0.3))), 1.0, 1)
    coax("equal-spheres-stacked", sk.Sphere(1.0), sk.Sphere(1.0, F((0, 0, 1.0))), 1.0, 1)
    coax("cone1-cylinder0.5", sk.Cone(1.0), sk.Cylinder(0.5, v_range=(-3, 3)), 0.5, 2)
    coax("torus-plane-z0.5", sk.Torus(2.0, 0.5), sk.Plane(F((0, 0, 0.5))), 0.5, 1)
    coax("sphere1.5-cylinder1.5", sk.Sphere(1.5), sk.Cylinder(1.5), 1.5, 1)
    out.append(Case("simple/same-sphere", "simple", sk.Sphere(10.0), sk.Sphere(10.0), None, "coincident", scale=10.0))
    out.append(Case("simple/same-torus", "simple", sk.Torus(2.0, 0.5), sk.Torus(2.0, 0.5), None, "coincident",
                    scale=0.5))
    out.append(finish(Case("simple/torus-patch-miss", "simple", sk.Torus(2.0, 0.5),
                           sk.Plane(u_range=(5, 6), v_range=(5, 6)), 0, "generic", None, scale=0.5)))
    return out


def special_family(rng):
    out = []
    Rm, o = rand_rot(rng), rng.uniform(-1, 1, 3)
    out.append(Case("special/cone-cone/same", "special", sk.Cone(0.5, F(o, Rm), v_range=(-1, 1)),
                    sk.Cone(0.5, F(o, Rm @ rot_z(0.3)), v_range=(-1, 1)), None, "coincident"))
    out.append(Case("special/cylinder-cylinder/coaxial-equal", "special", sk.Cylinder(0.7, F(o, Rm), v_range=(-1, 1)),
                    sk.Cylinder(0.7, F(o + 0.5 * Rm[:, 2], Rm @ rot_z(1.0)), v_range=(-1, 1)), None, "coincident"))
    out.append(Case("special/plane-plane/coplanar", "special", sk.Plane(F(o, Rm), (-1, 1), (-1, 1)),
                    sk.Plane(F(o + 0.5 * Rm[:, 0], Rm @ rot_z(0.4)), (-1, 1), (-1, 1)), None, "coincident"))
    out.append(Case("special/torus-torus/turned", "special", sk.Torus(1.5, 0.4, F(o, Rm)),
                    sk.Torus(1.5, 0.4, F(o, Rm @ rot_z(0.8))), None, "coincident", scale=0.4))
    out.append(Case("special/sphere-sphere/turned", "special", sk.Sphere(0.9, F(o, Rm)),
                    sk.Sphere(0.9, F(o, rand_rot(rng))), None, "coincident", scale=0.9))
    out.append(Case("special/plane-cylinder/unbounded", "special", sk.Plane(F(o, Rm)), sk.Cylinder(0.5, F(o, rand_rot(rng))),
                    None, "unbounded"))
    out.append(Case("special/plane-plane/unbounded", "special", sk.Plane(F(o, Rm)), sk.Plane(F(o, rand_rot(rng))),
                    None, "unbounded"))
    out.append(Case("special/cone-cylinder/unbounded", "special", sk.Cone(0.6, F(o, Rm)),
                    sk.Cylinder(0.3, F(o, rand_rot(rng))), None, "unbounded"))
    return out


def all_cases():
    """Every case, in a fixed order (each family has its own seeded generator)."""
    cases = []
    rnd = random_family(np.random.default_rng(1401))
    coax = coaxial_family(np.random.default_rng(1402))
    cases += rnd + aligned_family(np.random.default_rng(1403)) + coax
    by_pair = {}
    for c in rnd:
        by_pair.setdefault(("random", c.pair), c)
    for c in coax:
        by_pair.setdefault(("coaxial", c.pair), c)
    bases = [by_pair[k] for k in sorted(by_pair)]
    cases += scaled_family(bases, np.random.default_rng(1404))
    cases += contact_family(np.random.default_rng(1405))
    cases += tiny_family(np.random.default_rng(1406))
    cases += villarceau_family(np.random.default_rng(1407))
    cases += steinmetz_family(np.random.default_rng(1408))
    cases += viviani_family(np.random.default_rng(1409))
    cases += trimmed_family(np.random.default_rng(1410))
    cases += face_family(np.random.default_rng(1413))
    cases += tangent_family(np.random.default_rng(1411))
    cases += simple_family()
    cases += special_family(np.random.default_rng(1412))
    names = [c.name for c in cases]
    assert len(names) == len(set(names)), "case names must be unique"
    return cases


# ----------------------------------------------------------------------------------------------------------
# truth for a case, and the oracle self-check
# ----------------------------------------------------------------------------------------------------------
def truth_of(case, by_name, cache):
    """dict(count, samples, kind, sample_tol, source) for a case (cached by name)."""
    if case.name in cache:
        return cache[case.name]
    if case.base is not None:
        base = truth_of(by_name[case.base], by_name, cache)
        tr = dict(base)
        tr["samples"] = case.factor * base["samples"] + case.shift
        tr["source"] = "similarity of " + base["source"]
    elif case.count is not None or case.kind in ("coincident", "unbounded"):
        tr = dict(count=case.count, samples=case.samples if case.samples is not None else np.zeros((0, 3)),
                  kind=case.kind or "generic", sample_tol=case.sample_tol, source="closed form")
    else:
        bf = brute_force(case.a, case.b)
        tr = dict(count=bf["count"], samples=bf["samples"], kind=bf["kind"], sample_tol=0.0, source="brute force")
    cache[case.name] = tr
    return tr


def self_check(cases=None, n=600, verbose=True):
    """Brute force against every closed-form case; returns (agree, total, disagreements, worst raw residual)."""
    cases = all_cases() if cases is None else cases
    agree = total = 0
    bad = []
    worst = (0.0, "")
    per_family = {}
    t0 = time.perf_counter()
    for c in cases:
        if c.raw_residual > worst[0]:
            worst = (c.raw_residual, c.name)
        if c.count is None or c.base is not None:
            continue
        bf = brute_force(c.a, c.b, n=n)
        total += 1
        ok = bf["count"] == c.count
        agree += ok
        fam = per_family.setdefault(c.family, [0, 0])
        fam[0] += ok
        fam[1] += 1
        if not ok:
            bad.append((c.name, c.count, bf["count"]))
            if verbose:
                print(f"  DISAGREE {c.name}: closed form {c.count}, brute force {bf['count']} ({bf['kind']})")
    for c in cases:
        if c.kind == "coincident" and c.base is None:
            bf = brute_force(c.a, c.b, n=n)
            total += 1
            ok = bf["kind"] == "coincident"
            agree += ok
            fam = per_family.setdefault(c.family, [0, 0])
            fam[0] += ok
            fam[1] += 1
            if not ok:
                bad.append((c.name, "coincident", bf["count"]))
                if verbose:
                    print(f"  DISAGREE {c.name}: coincident, brute force {bf['kind']} {bf['count']}")
    if verbose:
        print(f"brute force agrees with {agree}/{total} closed forms ({time.perf_counter() - t0:.1f} s); "
              f"per family: " + ", ".join(f"{k} {v[0]}/{v[1]}" for k, v in per_family.items()))
        print(f"closed-form samples before polishing: worst {worst[0]:.2e} x scale off a surface ({worst[1]})")
    return agree, total, bad, worst


def consistency_check(cases=None, verbose=True):
    """For brute-force cases: the count with the grid on the other surface (when both are bounded) and
    with a finer grid; disagreements are cases where the oracle itself is in doubt."""
    from tests.oracles.ssi import grid_roles, is_bounded
    cases = all_cases() if cases is None else cases
    doubts = []
    n = 0
    for c in cases:
        if c.count is not None or c.base is not None or c.kind in ("coincident", "unbounded"):
            continue
        n += 1
        ref = brute_force(c.a, c.b)
        counts = {"600": ref["count"], "900": brute_force(c.a, c.b, n=900)["count"]}
        if is_bounded(c.a) and is_bounded(c.b):
            A, B = grid_roles(c.a, c.b)
            counts["swapped"] = brute_force(c.a, c.b, roles=(B, A))["count"]
        if len(set(counts.values())) > 1:
            doubts.append((c.name, counts))
            if verbose:
                print(f"  DOUBT {c.name}: {counts}")
    if verbose:
        print(f"brute-force consistency: {n - len(doubts)}/{n} cases agree across grid roles and resolutions")
    return doubts


if __name__ == "__main__":
    t = time.perf_counter()
    cs = all_cases()
    fams = {}
    for c in cs:
        fams[c.family] = fams.get(c.family, 0) + 1
    print(f"{len(cs)} cases generated in {time.perf_counter() - t:.1f} s: {fams}")
    self_check(cs)
    if "--consistency" in sys.argv:
        consistency_check(cs)
