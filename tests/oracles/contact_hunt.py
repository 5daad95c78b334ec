"""Random near-tangent contacts of every pair kind, each answer set against itself swapped, scaled and moved away
(``python -m tests.oracles.contact_hunt [seed count lo hi]`` prints the pairs whose answers differ, and the counts).

Each pair (seeded): two surfaces of random kinds, sizes and trims (random_surface); the second placed touching the first
at a random point of each, from outside or inside, turned at random about the common normal, then moved along it by
eps x the scene's scale, |eps| from 10^lo to 10^hi of either sign (touching). Its answer (the curves' count, statuses
and lengths) is compared with the same pair in the other argument order, and scaled by 1e-3 and by 1e3 and moved 1e2
to 1e4 scales from the origin: the intersection does not depend on any of these. Counts and statuses must agree;
lengths within LENGTH_RTOL (a loop of size sqrt(eps) moved far away carries the placement's round-off over 2 eps,
relative). A refusal (sk.TopologyError) is counted apart. No spatialkin internals: public surfaces and sk.intersect.
"""
import collections
import sys

import numpy as np

import spatialkin as sk
from tests.oracles.ssi import scene_scale
from tests.oracles.ssi_cases import F, make, rand_rot, transformed

KINDS = ("plane", "sphere", "cylinder", "cone", "torus")
#: Relative length difference within which two answers agree.
LENGTH_RTOL = 1e-4
#: Scales of the similar copies, and their distances from the origin (in the copy's scales, log10 range).
FACTORS = (1e-3, 1e3)
FAR = (2.0, 3.0)


def random_surface(rng, kind):
    """A surface of the kind, placed within 0.8 of the origin and turned at random: a plane and a cylinder trimmed
    to random ranges, a cone trimmed across its apex or off it, a ring torus."""
    frame = F(rng.uniform(-0.8, 0.8, 3), rand_rot(rng))
    if kind == "plane":
        return make(kind, frame, (), tuple(sorted(rng.uniform(-2, 2, 2))), tuple(sorted(rng.uniform(-2, 2, 2))))
    if kind == "sphere":
        return make(kind, frame, (rng.uniform(0.5, 1.8),))
    if kind == "cylinder":
        return make(kind, frame, (rng.uniform(0.3, 1.3),), v_range=tuple(sorted(rng.uniform(-2, 2, 2))))
    if kind == "cone":
        lo, hi = sorted(rng.uniform(-2.5, 2.5, 2))
        if rng.random() < 0.5:                         # (one nappe, off the apex)
            lo = abs(lo) * 0.3 + 0.1
            hi = lo + 0.3 + abs(hi)
        return make(kind, frame, (rng.uniform(0.25, 1.1),), v_range=(lo, hi))
    big = rng.uniform(0.8, 1.8)
    return make(kind, frame, (big, rng.uniform(0.15, 0.7) * big))


def _interior(rng, surface):
    """Parameters (u, v) inside the surface's trims (their middle 60%), or anywhere on an untrimmed range."""
    (u0, u1), (v0, v1) = surface.bounds
    if np.isfinite(u0) and np.isfinite(u1) and u1 - u0 < 2 * np.pi:
        u = rng.uniform(u0 + 0.2 * (u1 - u0), u1 - 0.2 * (u1 - u0))
    else:
        u = rng.uniform(-np.pi, np.pi)
    if np.isfinite(v0) and np.isfinite(v1) and not (surface.kind == "torus"):
        v = rng.uniform(v0 + 0.2 * (v1 - v0), v1 - 0.2 * (v1 - v0))
    else:
        v = rng.uniform(-1.2, 1.2) if surface.kind == "sphere" else rng.uniform(-np.pi, np.pi)
    return u, v


def touching(rng, a, b, eps, inside):
    """b moved rigidly so that a random point of it touches a random point of a, from outside (normals opposite) or
    inside (normals alike), turned at random about the normal, then moved by eps along a's unit normal there."""
    ua, va = _interior(rng, a)
    ub, vb = _interior(rng, b)
    p, n = np.asarray(a.point(ua, va), dtype=float).reshape(3), np.asarray(a.normal(ua, va), dtype=float).reshape(3)
    q, m = np.asarray(b.point(ub, vb), dtype=float).reshape(3), np.asarray(b.normal(ub, vb), dtype=float).reshape(3)
    n, m = n / np.linalg.norm(n), m / np.linalg.norm(m)
    target = n if inside else -n
    # (m onto target: m to the local z of one rotation, that z to target by another; then a random turn about it)
    turn = sk.rotation_about(target, rng.uniform(0.0, 2.0 * np.pi)) @ sk.rotation_to_z(target) @ sk.rotation_to_z(m).T
    origin = turn @ (np.asarray(b.frame.origin) - q) + p + eps * n
    return b.with_frame(sk.Frame(origin, turn @ np.asarray(b.frame.rotation)))


def answer(a, b):
    """(count, sorted statuses, sorted lengths) of sk.intersect(a, b), or ('refused',)."""
    try:
        curves = sk.intersect(a, b)
    except sk.TopologyError:
        return ("refused",)
    return len(curves), tuple(sorted(c.status for c in curves)), sorted(c.length for c in curves)


def agree(first, other, factor=1.0, rtol=LENGTH_RTOL):
    """True where the answers agree: the same count and statuses, each length (the other's over factor) within rtol
    of the first's, relative, plus 1e-12 (the scenes' lengths are of order 1)."""
    if first[:2] != other[:2]:
        return False
    return all(abs(y / factor - x) <= rtol * x + 1e-12 for x, y in zip(first[2], other[2]))


def pairs(seed, count, lo, hi):
    """(a, b, eps) of `count` seeded near-tangent pairs, |eps| (of the scale) from 10^lo to 10^hi."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        ka, kb = rng.choice(KINDS, 2)
        a, b = random_surface(rng, ka), random_surface(rng, kb)
        eps = float(rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(lo, hi)) * scene_scale(a, b)
        out.append((a, touching(rng, a, b, eps, bool(rng.random() < 0.5)), eps, rng.normal(size=(len(FACTORS), 3)),
                    rng.uniform(*FAR, len(FACTORS))))
    return out


def run(seeds=(1,), count=100, lo=-9.0, hi=-5.0, echo=print):
    """Counter of the pairs (pairs: all, differ: some copy's answer differs, refused: some answer is a refusal); echo
    the pairs that differ (their answers and surfaces) and the counts."""
    counts = collections.Counter()
    for seed in seeds:
        for a, b, eps, directions, far in pairs(seed, count, lo, hi):
            counts["pairs"] += 1
            first = answer(a, b)
            copies = [("swapped", 1.0, answer(b, a))]
            for factor, d, exponent in zip(FACTORS, directions, far):
                shift = d / np.linalg.norm(d) * factor * scene_scale(a, b) * 10.0 ** exponent
                copies.append((f"x{factor:g}, {10.0 ** exponent:.0e} scales out", factor,
                               answer(transformed(a, factor, shift), transformed(b, factor, shift))))
            if first[0] == "refused" or any(got[0] == "refused" for _, _, got in copies):
                counts["refused"] += 1
                continue
            differ = [(name, got) for name, factor, got in copies if not agree(first, got, factor)]
            if differ:
                counts["differ"] += 1
                echo(f"differ: {a.kind}-{b.kind}, eps {eps:.1e}: {first} | "
                     + " | ".join(f"{name}: {got}" for name, got in differ) + f"\n  a = {a!r}\n  b = {b!r}")
    echo(", ".join(f"{k} {counts[k]}" for k in ("pairs", "differ", "refused")))
    return counts


if __name__ == "__main__":
    arguments = sys.argv[1:]
    if arguments:
        run((int(arguments[0]),), int(arguments[1]), float(arguments[2]), float(arguments[3]))
    else:
        run()
