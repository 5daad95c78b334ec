"""The bench's measurements against independent oracles (tests/spatialkin/oracles.py, numpy only): the errors
it reports are recomputed from the returned points, its closed forms agree with the oracle's, and the command
writes its table, CSV and PNG. No timing is asserted."""
import csv
import functools

import numpy as np
import pytest

from spatialkin.bench import baselines, runner, sidebyside
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.bench.cases import looper_closed_form, torus_sphere_cases
from spatialkin.cli import main
from spatialkin.mechanisms import LooperDrive
from spatialkin.tracing.intersect import intersect
from spatialkin.tracing.trace import trace

from oracles import sphere_distance, torus_distance, torus_sphere_closed_form, torus_sphere_components

#: Agreement of two computations of the same distance (round-off of 100 mm coordinates).
DISTANCE_AGREEMENT = 1e-13


def oracle_error(case, points):
    """Largest distance of points (N, 3) to torus and sphere by the oracle's formulas."""
    local = case.torus.frame.to_local(points)
    return max(torus_distance(local, case.torus.major_radius, case.torus.minor_radius).max(),
               sphere_distance(points, case.sphere.frame.origin, case.sphere.radius).max())


@pytest.fixture(scope="module")
def cases():
    return {c.name: c for c in torus_sphere_cases()}


def test_cases_topology_and_closed_form(cases):
    """Each case's expected component count is the oracle's, and its exact points lie on both surfaces."""
    for case in cases.values():
        c = case.centre_local
        assert case.components == torus_sphere_components(case.torus.major_radius, case.torus.minor_radius, c,
                                                          case.sphere.radius) or case.name == "looper"
        pts = case.exact_points(360)
        assert len(pts) > 0
        ref, _ = torus_sphere_closed_form(case.torus.major_radius, case.torus.minor_radius, c, case.sphere.radius,
                                          np.linspace(-np.pi, np.pi, 360, endpoint=False))
        np.testing.assert_allclose(pts, case.torus.frame.to_global(ref.reshape(-1, 3)), atol=1e-12)
        assert oracle_error(case, pts) < 1e-12


def test_reported_error_is_the_measured_distance(cases):
    """tracer_rows reports the largest distance of the traced points and dense samples; recomputing it with the
    oracle from curves traced the same way gives the same number."""
    case = cases["ring-2"]
    rows = runner.tracer_rows(case, rtols=(1e-6,), repeats=1, methods=("RK45",))
    assert len(rows) == 1 and rows[0].curves == case.components
    starts = [c.points[0] for c in intersect(case.torus, case.sphere)]
    curves = [trace(case.torus, case.sphere, p, tol=runner.TRACE_TOL, method="RK45", rtol=1e-6) for p in starts]
    worst = max(oracle_error(case, np.vstack([c.points, c.sample(runner.DENSE_SAMPLES)])) for c in curves)
    assert abs(rows[0].error - worst) < DISTANCE_AGREEMENT
    assert rows[0].error < 1e-12 * case.torus.size


def test_looper_rows_against_the_closed_form():
    """The looper rows' errors are measured against the closed form; the closed form itself matches 5-point
    differences of its positions (velocity, acceleration) to 1e-7 relative."""
    drive = LooperDrive.reference()
    rows = {r.solver: r for r in runner.looper_rows(repeats=1, n=181)}
    assert rows["closed form"].error == 0.0
    assert rows["LooperDrive"].error < 1e-9 and rows["scipy root"].error < 1e-9
    u, h, omega = np.linspace(0.3, 6.0, 40), 1e-3, 2.0
    c = [looper_closed_form(drive, u + k * h, omega)[0] for k in (-2, -1, 0, 1, 2)]
    d1 = (c[0] - 8 * c[1] + 8 * c[3] - c[4]) / (12 * h)
    d2 = (-c[0] + 16 * c[1] - 30 * c[2] + 16 * c[3] - c[4]) / (12 * h * h)
    _, vel, acc = looper_closed_form(drive, u, omega)
    assert np.max(np.abs(vel - omega * d1)) < 1e-7 * np.max(np.abs(vel))
    assert np.max(np.abs(acc - omega ** 2 * d2)) < 1e-7 * np.max(np.abs(acc))


@pytest.mark.skipif(not baselines.occ_available(), reason="cadquery-ocp (optional bench extra) not installed")
def test_occ_rows_measure_their_curves(cases):
    """OCC's curves are sampled and measured with the exact distance functions (oracle recomputation)."""
    case = cases["looper"]
    _, curves = baselines.occ_intersect(case.torus, case.sphere, baselines.OCC_DEFAULT_TOL, 1)
    row = runner.occ_rows(case, 1, tols=(baselines.OCC_DEFAULT_TOL,))[0]
    assert row.curves == len(curves) == case.components
    assert abs(row.error - max(oracle_error(case, p) for p in curves)) < DISTANCE_AGREEMENT


def test_bench_quick_command(tmp_path, capsys, monkeypatch):
    """`spatialkin bench --quick --out DIR` runs (cut to one case and one method here), prints the goal ratios
    and writes a CSV whose errors agree with the printed rows."""
    monkeypatch.setattr(runner, "torus_sphere_cases", lambda: torus_sphere_cases()[1:2])
    monkeypatch.setattr(runner, "tracer_rows", functools.partial(runner.tracer_rows, methods=("DOP853",)))
    monkeypatch.setattr(runner, "looper_rows", functools.partial(runner.looper_rows, n=91))
    monkeypatch.setattr(sidebyside, "pair_kind_cases", lambda: pair_kind_cases()[:2])   # the 15 in test_sidebyside
    assert main(["bench", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "goal 1" in out and "goal 2" in out and "goal 3" in out
    assert "sk.intersect stage profile" in out and "plane-sphere" in out
    with open(tmp_path / "bench.csv") as f:
        rows = list(csv.DictReader(f))
    traced = [r for r in rows if r["solver"] == "trace"]
    assert traced and all(float(r["error"]) < 1e-12 * 30 for r in traced)
    assert (tmp_path / "bench.png").stat().st_size > 0



def test_length_error_against_a_circle():
    """The geometric length (Richardson chord sums) of sphere ∩ plane matches the circle's 2 pi r to 1e-12
    relative, whatever the solver's s; the reported length error is |length - 2 pi r| / 2 pi r to 1e-12 and
    shrinks with rtol (what the tolerance buys)."""
    import spatialkin as sk
    sphere, plane = sk.Sphere(5.0), sk.Plane(sk.Frame((0.0, 0.0, 3.0)))
    exact = 2 * np.pi * 4.0
    errs = []
    for rtol in (1e-5, 1e-10):
        c = trace(sphere, plane, (4.0, 0.0, 3.0), rtol=rtol, method="RK45")
        assert abs(runner.geometric_length(c) - exact) < 1e-12 * exact
        errs.append(runner.length_error([c]))
        assert abs(errs[-1] - abs(c.length - exact) / exact) < 1e-12
    assert errs[1] < 1e-9 and errs[1] < errs[0]
