"""Every curve sk.intersect returns runs along N_a x N_b, the direction of Dragilev's Cauchy problem (dM/ds = N_a x
N_b / |N_a x N_b|): traced curves, closed-form conics, circles about a common axis (in closed form, or found by the
coaxial search) and their arcs inside CAD faces alike, whichever surface the search reads as its chart. Oracle: the
surfaces' own normals S_u x S_v (Surface.normal) at the curve's parameters, against its unit tangent (the dense
output's derivatives), on every stress case in both argument orders, and on moved copies of the coaxial ones (a move
of 1e-9 of the scale, with a scale factor 1 + 1e-9, that changes only the round-off)."""
import numpy as np
import pytest
from tests.oracles.ssi_cases import all_cases, transformed

import spatialkin as sk

#: Arc lengths read per curve (evenly inside it) ...
READS = 5
#: ... where the normals' sine is at least this (a point clear of a node or a tangency).
CLEAR_SINE = 1e-3


def senses(a, b, curve):
    """The signs of N_a x N_b . C'(s) at READS arc lengths of the curve where the normals are clear of parallel."""
    s = np.linspace(0.0, curve.length, READS + 2)[1:-1]
    tangents = curve.derivatives(s)[1]
    out = []
    for (u1, v1, u2, v2), tangent in zip(curve.parameters(s), tangents):
        cross = np.cross(a.normal(u1, v1), b.normal(u2, v2))
        if np.linalg.norm(cross) >= CLEAR_SINE:
            out.append(float(np.sign(cross @ tangent)))
    return out


def cases():
    return [c for c in all_cases() if c.kind not in ("coincident", "unbounded") and c.family != "special"]


@pytest.mark.slow
def test_every_curve_runs_along_the_normals_cross_product():
    """Each curve without nodes (past a node N_a x N_b turns against the branch) and of positive length, not a
    tangency: every clear reading agrees with its tangent. About 1150 curves."""
    wrong, read = [], 0
    for case in cases():
        for a, b in ((case.a, case.b), (case.b, case.a)):
            try:
                curves = sk.intersect(a, b)
            except (sk.TopologyError, sk.TracingError, sk.CoincidentSurfacesError):
                continue
            for curve in curves:
                if curve.length == 0 or curve.status == "tangent" or len(curve.nodes):
                    continue
                signs = senses(a, b, curve)
                read += bool(signs)
                if signs and min(signs) < 0:
                    wrong.append((case.name, a is case.b, curve.status, type(curve._result.sol).__name__))
    assert read > 1000
    assert not wrong, wrong


def test_coaxial_circles_run_along_the_normals_cross_product_whatever_the_round_off():
    """The coaxial pairs moved 1e5 away (whose search reads either surface as its chart as the round-off falls):
    both argument orders, unmoved and moved by 1e-9 of the scale with a scale factor 1 + 1e-9."""
    chosen = [c for c in cases() if c.name.startswith("scaled/coaxial/") and c.name.endswith("+1e5")]
    assert len(chosen) >= 10
    rng = np.random.default_rng(5)
    for case in chosen:
        shift = rng.normal(size=3)
        shift *= 1e-9 * case.scale / np.linalg.norm(shift)
        pairs = [(case.a, case.b), (transformed(case.a, 1.0 + 1e-9, shift), transformed(case.b, 1.0 + 1e-9, shift))]
        for a, b in pairs + [(b, a) for a, b in pairs]:
            for curve in sk.intersect(a, b):
                if curve.length > 0 and curve.status != "tangent" and not len(curve.nodes):
                    assert min(senses(a, b, curve), default=1.0) > 0, (case.name, curve.status)
