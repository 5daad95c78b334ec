"""Planes just below a bitangent plane of a ring torus, run with certify=True: how many answers have both loops of
the quadrature's lengths (right: within LENGTH_TOL; rough: within ROUGH_TOL, two closed loops whose lengths carry
the round-off of coordinates far from the origin), how many are wrong (a lie where certified) and how many are
refused (``python -m tests.oracles.bitangent_hunt`` prints the counts).

Each placing (seeded): R = 1 and r in [0.2, 0.7], scaled by 1e-3 to 1e3; the tilt asin(r / R - delta), delta from 1e-13
to 1e-5 (the loops pass 2 sqrt(r^2 - R^2 sin^2 tilt) apart at two points); a random rotation, and half of the placings
moved 1 to 1e6 from the origin; both argument orders. Oracle: tests.oracles.closed_forms.bitangent_loops.
"""
import collections
import math
import sys

import numpy as np

import spatialkin as sk
from spatialkin._lib import jit
from tests.oracles.closed_forms import bitangent_loops, random_rotation

SEEDS = (1, 2, 3, 4)
PLACINGS = 15
#: Relative length error within which a loop is right ...
LENGTH_TOL = 1e-9
#: ... and within which the two loops are the right ones, their lengths rough (see the module docstring).
ROUGH_TOL = 1e-6


def placings(seed, count=PLACINGS):
    """(torus, plane, delta) of `count` seeded placings."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        share = rng.uniform(0.2, 0.7)
        delta = 10.0 ** rng.uniform(-13, -5)
        scale = 10.0 ** rng.uniform(-3, 3)
        far = 10.0 ** rng.uniform(0, 6) * rng.choice([0, 1])
        rot = random_rotation(rng)
        origin = rng.normal(size=3)
        origin *= far / np.linalg.norm(origin)
        out.append(bitangent_pair(share, delta, scale, origin, rot) + (delta,))
    return out


def bitangent_pair(share, delta, scale, origin, rotation):
    """(torus, plane): a ring torus (R = scale, r = share * scale) at the origin (3,), turned by the rotation (3, 3),
    and a plane through its centre tilted asin(share - delta) about its local x axis (just below the bitangent tilt
    for small delta > 0), trimmed to 3 scales each way."""
    torus = sk.Torus(scale, share * scale, sk.Frame(origin, rotation))
    plane = sk.Plane(sk.Frame(origin, rotation @ sk.rotation_about((1.0, 0.0, 0.0), math.asin(share - delta))),
                     u_range=(-3.0 * scale, 3.0 * scale), v_range=(-3.0 * scale, 3.0 * scale))
    return torus, plane


def run(seeds=SEEDS, echo=print):
    """Counter of the answers: right, rough, wrong, refused, proven, lies; echo the rough and wrong ones (their
    distance from the origin in scales, the torus's major radius) and the counts."""
    jit.use(jit.COMPILED)
    counts = collections.Counter()
    for seed in seeds:
        for torus, plane, delta in placings(seed):
            _, exact = bitangent_loops(torus, plane)
            for pair in ((torus, plane), (plane, torus)):
                counts["answers"] += 1
                try:
                    curves = sk.intersect(*pair, certify=True)
                except sk.TopologyError:
                    counts["refused"] += 1
                    continue
                got = sorted(c.length for c in curves)
                loops = len(curves) == 2 and all(c.closed for c in curves)
                error = max((abs(g - e) / e for g, e in zip(got, exact)), default=math.inf) if loops else math.inf
                verdict = "right" if error <= LENGTH_TOL else "rough" if error <= ROUGH_TOL else "wrong"
                proven = curves.certificate.proven
                counts["proven"] += proven
                counts[verdict] += 1
                counts["lies"] += proven and verdict != "right"
                if verdict != "right":
                    far = float(np.linalg.norm(torus.frame.origin)) / torus.major_radius
                    echo(f"{verdict}: seed {seed}, delta {delta:.1e}, {far:.2g} scales from the origin, scale "
                         f"{torus.major_radius:.2g}: lengths / scale {[round(g / torus.major_radius, 9) for g in got]}, "
                         f"quadrature {[round(e / torus.major_radius, 9) for e in exact]}, relative error {error:.1e}, "
                         f"proven {proven}")
    echo(", ".join(f"{k} {counts[k]}" for k in ("answers", "right", "rough", "wrong", "refused", "proven", "lies")))
    return counts


if __name__ == "__main__":
    sys.exit(1 if run()["lies"] else 0)
