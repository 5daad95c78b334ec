"""Stress: torus ∩ sphere over 1000+ random configurations, near-critical and critical ones included.

Each configuration checks the component count against the topology by critical radii, closure, and every
returned point and 200 dense evaluations per curve against the exact distance functions. The report (how
many ran, how many failed and why) is printed in pytest's terminal summary.
"""
import time

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests.oracles.closed_forms import random_rotation, sphere_distance, torus_distance, torus_sphere_critical_radii

import spatialkin as sk

CONFIGURATIONS = 1000
TOL = 1e-10


def configuration(rng, kind):
    """(big, small, origin, rot, centre_local, rho, expected components) of one random configuration.
    kind: 'generic' (inside a band), 'near' (1e-7..1e-3 relative from a critical radius), 'critical'."""
    big = rng.uniform(0.5, 20.0)
    small = big * rng.uniform(0.1, 0.9)
    c = rng.uniform(-1, 1, 3) * np.array([big + small, big + small, 1.5 * small])
    radii = torus_sphere_critical_radii(big, small, c)
    if kind == "generic":
        band = rng.integers(0, 3)
        rho = radii[band] + rng.uniform(0.02, 0.98) * (radii[band + 1] - radii[band])
        expected = 2 if band == 1 else 1
    elif kind == "near":
        k = rng.integers(0, 4)
        side = rng.choice([-1.0, 1.0])
        rho = radii[k] * (1 + side * 10 ** rng.uniform(-7, -3))
        inside = (radii[0] < rho < radii[3])
        expected = 0 if not inside else (2 if radii[1] < rho < radii[2] else 1)
    else:
        k = rng.integers(0, 4)
        rho = radii[k]
        expected = 1                      # a contact point (k = 0, 3) or a figure-eight (k = 1, 2)
    return big, small, rng.uniform(-50, 50, 3), random_rotation(rng), c, rho, expected


def check(big, small, origin, rot, c, rho, expected):
    """'' if the configuration passes, else the reason."""
    torus = sk.Torus(big, small, sk.Frame(origin, rot))
    centre = origin + rot @ c
    try:
        curves = sk.intersect(torus, sk.Sphere(rho, sk.Frame(centre, rot.T)), tol=TOL)
    except Exception as err:          # noqa: BLE001 - the stress test reports every kind of failure
        return f"raised {type(err).__name__}: {err}"
    if len(curves) != expected:
        return f"{len(curves)} components, expected {expected}"
    for curve in curves:
        if curve.status not in ("closed", "contact"):
            return f"status {curve.status}: {curve.message}"
        pts = curve.points if curve.length == 0 else np.vstack([curve.points, curve(np.linspace(0, curve.length, 200))])
        worst = max(torus_distance((pts - origin) @ rot, big, small).max(), sphere_distance(pts, centre, rho).max())
        if worst > curve.tolerance:
            return f"a point {worst:.3g} off the surfaces (tolerance {curve.tolerance:.3g})"
    return ""


def test_stress_report(stress_report):
    rng = np.random.default_rng(20261121)
    kinds = ["generic"] * 6 + ["near"] * 3 + ["critical"]
    t0 = time.perf_counter()
    failures = {}
    counts = {}
    for i in range(CONFIGURATIONS):
        kind = kinds[i % len(kinds)]
        counts[kind] = counts.get(kind, 0) + 1
        reason = check(*configuration(rng, kind))
        if reason:
            failures.setdefault(kind, []).append((i, reason))
    elapsed = time.perf_counter() - t0
    total_failed = sum(len(v) for v in failures.values())
    stress_report.append(f"torus ∩ sphere stress: {CONFIGURATIONS} configurations "
                         f"({', '.join(f'{v} {k}' for k, v in counts.items())}), {total_failed} failed, "
                         f"{elapsed:.1f} s")
    for kind, items in failures.items():
        for i, reason in items[:5]:
            stress_report.append(f"  {kind} #{i}: {reason}")
    assert total_failed == 0, stress_report


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2 ** 32 - 1), kind=st.sampled_from(["generic", "near", "critical"]))
def test_stress_hypothesis(seed, kind):
    """The same check under hypothesis (shrinks a failing seed)."""
    assert check(*configuration(np.random.default_rng(seed), kind)) == ""


def test_near_tangent_loop_at_round_off():
    """A configuration (seed, kind) whose tiny near-tangent loop takes Newton steps down to round-off (seed 789,
    'near'): it closes on both surfaces, as in test_stress_report."""
    for seed, kind in [(789, "near")]:
        assert check(*configuration(np.random.default_rng(seed), kind)) == ""
