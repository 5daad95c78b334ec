"""The per-pair-kind section of the bench (spatialkin.bench.sidebyside, spatialkin.bench.kinds): 15 pair kinds,
OpenCascade's surfaces are the same surfaces (oracle: points of both parametrisations), the errors reported are
the measured distances, the ratios are finite when OpenCascade is installed. No timing is asserted."""
import itertools

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.bench import baselines, sidebyside
from spatialkin.bench.kinds import KINDS, STEINMETZ_ANGLE, occ_surface, pair_kind_cases, special_cases
from spatialkin.geometry.surfaces import Cone
from spatialkin._lib import stages
from spatialkin.tracing.components import intersect

#: Agreement of the same point from spatialkin's and OpenCascade's parametrisations (round-off of unit-sized
#: coordinates).
SAME_POINT = 1e-12
#: Two computations of the same distance agree to this (the same points, the same distance functions).
DISTANCE_AGREEMENT = 1e-15
needs_occ = pytest.mark.skipif(not baselines.occ_available(),
                               reason="cadquery-ocp (test/bench extra) not installed")


@pytest.fixture(scope="module")
def rows():
    """One timed call per side and pair kind (the section as --quick runs it, fewer calls)."""
    return sidebyside.kind_rows(quick=True, echo=lambda *_: None)


def test_fifteen_pair_kinds_all_bounded():
    cases = pair_kind_cases()
    assert [name for name, _, _ in cases] == [f"{p}-{q}" for p, q in
                                              itertools.combinations_with_replacement(KINDS, 2)]
    assert len(cases) == 15
    for _, a, b in cases:
        for s in (a, b):
            assert np.isfinite(s.traits.extent(s))          # trimmed where the kind is unbounded


def test_special_case_is_a_steinmetz_pair():
    """The bench's special placement: two equal cylinders whose axes cross (at their origins, at STEINMETZ_ANGLE),
    met in closed form in two ellipses through two nodes, within round-off of both surfaces."""
    (name, a, b), = special_cases()
    assert a.radius == b.radius and np.allclose(a.frame.origin, b.frame.origin)
    cosine = abs(a.frame.rotation[:, 2] @ b.frame.rotation[:, 2])
    assert abs(cosine - np.cos(STEINMETZ_ANGLE)) < 1e-15
    curves = sk.intersect(a, b)
    assert len(curves) == 2 and all(c.nfev == 0 and len(c.nodes) == 2 for c in curves)
    assert max(c.max_distance for c in curves) < 1e-14


@needs_occ
def test_occ_surfaces_are_the_same_surfaces():
    """OpenCascade's surface at the matching (u, v) is spatialkin's point (the cone's v along the slant)."""
    uv = np.array([[0.3, 0.5], [-2.0, 1.2], [2.9, 2.5]])
    for kind in KINDS:
        _, a, _ = next(c for c in pair_kind_cases() if c[0] == f"{kind}-{kind}")
        geom = occ_surface(a)
        for u, v in uv:
            v = min(max(v, a.v_range[0]), a.v_range[1]) if np.isfinite(a.v_range[0]) else v
            v_occ = v / np.cos(a.half_angle) if isinstance(a, Cone) else v
            p = geom.Value(float(u), float(v_occ))
            np.testing.assert_allclose([p.X(), p.Y(), p.Z()], a.point(u, v), atol=SAME_POINT)


def test_rows_and_profile(rows):
    """15 rows; our errors are the measured distances of the returned points and dense samples; every profile
    sums to its call, and the compiled kernels' own time is measured (zero for a closed form)."""
    assert len(rows) == 15
    for r, (name, a, b) in zip(rows, pair_kind_cases()):
        assert r.kind == name and r.our_curves >= 1
        curves = intersect(a, b)
        pts = np.vstack([c.points for c in curves] + [c.sample(sidebyside.OUR_SAMPLES) for c in curves
                                                      if c.length > 0])
        worst = max(float(np.max(a.distance(pts))), float(np.max(b.distance(pts))))
        assert abs(r.our_error - worst) <= DISTANCE_AGREEMENT
        assert r.our_error <= 1e-10 * 10
        assert set(r.profile.seconds) == set(stages.STAGES)
        assert r.profile.covered <= r.profile.total * (1 + 1e-12)
        assert r.profile.covered >= 0.5 * r.profile.total
        # the compiled kernels' own time (none in a closed form: sk.intersect returns its curves before their
        # points, which are sampled, in compiled code, when first read); it is timed in other calls than the
        # profile (cProfile would slow the Python down), so it is not compared with the profile's total
        closed_form = all(c.topology.mode == "closed_form" for c in curves)
        assert 0.0 <= r.kernel if closed_form else 0.0 < r.kernel
        assert np.isfinite(r.ours_points) and r.ours_points > 0.0        # timed with the points read (no bound)
        for (points, s, params), c in zip(sidebyside.read_points(curves), curves):
            assert points.shape == (len(s), 3) and params.shape == (len(s), 4) and s[-1] == c.length
    lines = sidebyside.profile_table(rows)
    assert len(lines) == 3 + 15 + 1


@needs_occ
def test_ratios_finite_and_occ_errors_measured(rows):
    """With OpenCascade: finite positive ratios; its error recomputed from its own sampled curves."""
    from OCP.GeomAPI import GeomAPI_IntSS
    assert all(np.isfinite(q) and q > 0 for r in rows for q in (r.ratio, r.cold_ratio, r.loop_ratio))
    assert all(r.occ_curves >= 1 and np.isfinite(r.occ_error) for r in rows)
    name, a, b = pair_kind_cases()[4]
    inter = GeomAPI_IntSS(occ_surface(a), occ_surface(b), baselines.OCC_DEFAULT_TOL)
    pts = np.vstack(sidebyside.occ_points(inter, sidebyside.QUICK_OCC_SAMPLES))
    worst = max(float(np.max(a.distance(pts))), float(np.max(b.distance(pts))))
    assert abs(rows[4].occ_error - worst) <= DISTANCE_AGREEMENT
    table = sidebyside.occ_table(rows, sidebyside.QUICK_CALLS)
    assert len(table) == 3 + 15 + 3
