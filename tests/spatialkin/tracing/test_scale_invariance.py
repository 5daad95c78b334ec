"""sk.intersect does not depend on the scene's scale: stress cases scaled by exact powers of two (2^-27, 2^27: the
scaled scene is similar to the bit) give the same curves, statuses and counts, lengths within 1e-8 relative.

Each case below depends on a tolerance being relative to the scale; in absolute units it would change under such a
scaling:

- contact/sphere-cylinder/far-at, contact/sphere-cone/ruling-at: the contact point would be lost (topology.classify:
  the Hessian's metric tested for degeneracy in mixed units; critical_point's stop and move tests absolute in a
  length parameter);
- contact/sphere-cylinder/node-at, viviani/sphere-cylinder/3: the node would not be recognised (the same), the
  figure-eight traced to max_length or as a wrong loop;
- contact/plane-cone/ruling-in: the rings round the cone's apex at absolute offsets of its length v;
- scaled/coaxial/cone-cone/0/x1e-4: parallels taken for the apex (an absolute 1e-12 in a cone's v);
- tiny/plane-torus/1e-06: a tiny loop ending 'singular' (the Newton systems' pivot test across columns of
  lengths and of numbers);
- contact/sphere-cylinder/outside-out: a loop of 1e-4 of the scale, whose first step, in absolute units, would
  pass it whole at 2^-27;
- scaled/random/cylinder-cone/0/+1e5: a start on a trim edge, 2e-13 of the scale past it, where the curve leaves
  the surface: the test of whether it leaves compares the edge parameter's rate with the speed of both
  parameters, an angle's and a length's, which differ by the scale unless each is read in its unit (at 2^-27 the
  march went on round a loop instead of ending there).

The march itself is the same at every power-of-two scale: the near-tangent pair below (a sphere and a cylinder 1e-9
of the scale from internal tangency, on either side) gives the same stored points, scaled, and certify=True proves
the same answer.
"""
import numpy as np
import pytest
from tests.oracles.ssi_cases import all_cases, transformed

import spatialkin as sk

CASES = ("contact/sphere-cylinder/far-at", "contact/sphere-cone/ruling-at", "contact/sphere-cylinder/node-at",
         "viviani/sphere-cylinder/3", "contact/plane-cone/ruling-in", "scaled/coaxial/cone-cone/0/x1e-4",
         "tiny/plane-torus/1e-06", "contact/sphere-cylinder/outside-out", "scaled/random/cylinder-cone/0/+1e5")
FACTORS = (2.0 ** -27, 2.0 ** 27)
LENGTH_RTOL = 1e-8


@pytest.fixture(scope="module")
def cases():
    return {c.name: c for c in all_cases() if c.name in CASES}


def summary(curves, factor):
    return sorted((c.status, c.closed, c.length / factor) for c in curves)


@pytest.mark.parametrize("name", CASES)
def test_scaled_scene_same_curves(cases, name):
    case = cases[name]
    base = summary(sk.intersect(case.a, case.b), 1.0)
    for factor in FACTORS:
        a, b = transformed(case.a, factor, np.zeros(3)), transformed(case.b, factor, np.zeros(3))
        got = summary(sk.intersect(a, b), factor)
        assert [(s, c) for s, c, _ in got] == [(s, c) for s, c, _ in base], (name, factor, got, base)
        for (_, _, x), (_, _, y) in zip(got, base):
            assert abs(x - y) <= LENGTH_RTOL * max(y, case.scale), (name, factor, x, y)


def near_tangent_pair(eps, scale):
    """A sphere of radius scale and a cylinder of radius scale / 2 whose axis lies (1 + eps) scale / 2 from the
    sphere's centre: internally tangent at eps = 0, two loops for eps < 0, one for eps > 0."""
    sphere = sk.Sphere(scale, sk.Frame((0.1 * scale, -0.2 * scale, 0.3 * scale)))
    cylinder = sk.Cylinder(0.5 * scale, sk.Frame((0.1 * scale + 0.5 * (1.0 + eps) * scale, -0.2 * scale, 0.3 * scale)),
                           v_range=(-3.0 * scale, 3.0 * scale))
    return sphere, cylinder


@pytest.mark.parametrize("eps, count", [(-1e-9, 2), (1e-9, 1)])
def test_the_march_is_the_same_at_every_scale(eps, count):
    """Scaled by 2^-20 to 2^20, the near-tangent pair gives the same curves, each with as many stored points, those
    points the scaled ones to 1e-12 of the scale (a similarity: the oracle is the unscaled answer) and the same
    number of right-hand side evaluations: every step of the march, the first one of each segment included, scales
    with the scene."""
    base = sk.intersect(*near_tangent_pair(eps, 1.0))
    assert len(base) == count
    for k in (-20, -7, 7, 20):
        scale = 2.0 ** k
        got = sk.intersect(*near_tangent_pair(eps, scale))
        assert [(c.status, len(c.points), c.nfev) for c in got] == [(c.status, len(c.points), c.nfev) for c in base]
        for c, b in zip(got, base):
            assert np.max(np.abs(c.points / scale - b.points)) <= 1e-12, (k, eps)
            assert abs(c.length / scale - b.length) <= 1e-12 * b.length


@pytest.mark.parametrize("eps", [-1e-9, 1e-9])
def test_certify_proves_the_same_answer_at_every_scale(eps):
    """certify=True on the near-tangent pair scaled by 1e-6, 1, 1e3 and 1e6 (not powers of two): proven at every
    scale, with the right count, the proven distance bound within a factor 2 of scale times the unscaled one."""
    base = sk.intersect(*near_tangent_pair(eps, 1.0), certify=True)
    assert base.certificate.proven and len(base) == (2 if eps < 0 else 1), base.certificate
    for scale in (1e-6, 1e3, 1e6):
        got = sk.intersect(*near_tangent_pair(eps, scale), certify=True)
        assert got.certificate.proven and len(got) == len(base), (scale, got.certificate)
        for c, b in zip(got, base):
            bound, ref = c.certificate.distance_bound / scale, b.certificate.distance_bound
            assert 0.5 * ref <= bound <= 2.0 * ref, (scale, bound, ref)


def test_random_contacts_answer_alike_swapped_scaled_and_moved():
    """Thirty random near-tangent contacts of every pair kind (tests.oracles.contact_hunt: one surface placed touching
    the other at a random point, from outside or inside, then moved 1e-8 to 1e-6 of the scale along the normal; a
    loop there is 1e-4 to 1e-3 of the scale): each answer is the same in the other argument order and scaled by 1e-3
    and 1e3 and moved 1e2 to 1e3 scales from the origin, counts and statuses exactly, lengths within 1e-4 (relative:
    the conditioning of a small loop far away), and none is refused."""
    from tests.oracles.contact_hunt import run
    lines = []
    counts = run(seeds=(5, 6, 7), count=10, lo=-8.0, hi=-6.0, echo=lines.append)
    assert counts["pairs"] == 30 and counts["differ"] == 0 and counts["refused"] == 0, "\n".join(lines)
