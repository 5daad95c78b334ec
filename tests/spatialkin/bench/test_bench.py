"""The bench's measurements against independent oracles (tests/oracles/closed_forms.py, numpy only): the errors
it reports are recomputed from the returned points, its closed forms agree with the oracle's, and the command
writes its table, CSV and PNG. No timing is asserted."""
import csv
import math
import functools

import numpy as np
import pytest

from spatialkin.bench import baselines, report, runner, sidebyside
from spatialkin.bench.kinds import pair_kind_cases
from spatialkin.bench.cases import looper_closed_form, torus_sphere_cases
from spatialkin.cli import main
from spatialkin.mechanisms import LooperDrive
from spatialkin.tracing.components import intersect
from spatialkin.tracing.single import trace

from tests.oracles.closed_forms import sphere_distance, torus_distance, torus_sphere_closed_form, torus_sphere_components

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
    """`spatialkin bench --quick --out DIR` runs (cut to one case and one method here), prints the measurement
    table (one line per row, every column), the ratios against the peers and the start-up line, and writes a
    CSV whose rows are the printed ones, with errors within the tracer's tolerance."""
    monkeypatch.setattr(runner, "torus_sphere_cases", lambda: torus_sphere_cases()[1:2])
    monkeypatch.setattr(runner, "tracer_rows", functools.partial(runner.tracer_rows, methods=("DOP853",)))
    monkeypatch.setattr(runner, "looper_rows", functools.partial(runner.looper_rows, n=91))
    monkeypatch.setattr(sidebyside, "pair_kind_cases", lambda: pair_kind_cases()[:2])   # the 15 in test_sidebyside
    assert main(["bench", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("case "))
    for column in ("case", "solver", "method", "rtol/tol", "curves", "ms/call", "ms/curve", "max error", "len err",
                   "nfev", "notes"):
        assert column in lines[head]
    with open(tmp_path / "bench.csv") as f:
        rows = list(csv.DictReader(f))
    printed = lines[head + 2:head + 2 + len(rows)]
    assert all(line.startswith(f"{r['case']:<13} {r['solver']:<11} {r['method']:<7} ")
               for line, r in zip(printed, rows))
    assert all(float(line[len(lines[head].split("max error")[0]):].split()[0]) == pytest.approx(float(r["error"]),
                                                                                             rel=0.06)
               for line, r in zip(printed, rows))
    assert {"trace", "intersect", "LooperDrive", "closed form", "scipy root"} <= {r["solver"] for r in rows}
    assert any(line.startswith("vs per-angle root solve: looper full turn, 91 crank angles") for line in lines)
    assert any(line.startswith("vs OpenCascade: closed loop within 1e-10") for line in lines)
    assert "start-up: import + first intersect in a fresh process (warm numba cache): not measured (--quick)" in lines
    assert "goal" not in out.lower() and "reached" not in out
    assert "sk.intersect stage profile" in out and "plane-sphere" in out
    traced = [r for r in rows if r["solver"] == "trace"]
    assert traced and all(float(r["error"]) < 1e-12 * 30 for r in traced)
    assert (tmp_path / "bench.png").stat().st_size > 0


def _row(case, solver, method, rtol, per_curve, error, curves=2, expected=2):
    return runner.Row(case, solver, method, rtol, curves, expected, per_curve * curves, per_curve, error)


def test_comparisons_are_the_rows_ratios():
    """The ratio against OpenCascade is OCC's time per curve (default tolerance) over the fastest tracer setting
    that is within COMPARE_ERROR and finds every component in every case (a setting failing in another case is
    not picked); the looper's is the root solve's time over LooperDrive's. Oracle: the same quotients of the
    synthetic rows' times, by hand."""
    tol = baselines.OCC_DEFAULT_TOL
    rows = [_row("looper", "trace", "DOP853", 1e-8, 4e-3, 1e-12),
            _row("looper", "trace", "RK45", 1e-6, 1e-3, 1e-11),          # fastest, but misses a loop elsewhere
            _row("ring-2", "trace", "RK45", 1e-6, 1e-3, 1e-11, curves=1),
            _row("ring-2", "trace", "DOP853", 1e-8, 4e-3, 1e-12),
            _row("looper", "trace", "RK23", 1e-4, 5e-4, 1e-7),           # faster, but not within COMPARE_ERROR
            _row("looper", "OCC IntSS", "-", tol, 2e-2, 3e-8),
            runner.Row("looper drive", "LooperDrive", "-", np.nan, 91, 91, 0.01, 0.01 / 91, 1e-13),
            runner.Row("looper drive", "closed form", "-", np.nan, 91, 91, 1e-4, 1e-4 / 91, 0.0),
            runner.Row("looper drive", "scipy root", "-", np.nan, 91, 91, 0.25, 0.25 / 91, 1e-13)]
    c = runner.comparisons(rows, startup=np.nan)
    assert c.occ_ratio == pytest.approx(2e-2 / 4e-3) and "trace DOP853 rtol 1e-08" in c.occ_detail
    assert c.looper_ratio == pytest.approx(25.0)
    lines = report.comparison_lines(c, runner)
    assert lines[0].startswith("vs OpenCascade: ") and lines[0].endswith(c.occ_detail) and "5.0x; " in lines[0]
    assert lines[1].startswith("vs per-angle root solve: looper full turn, 91 crank angles") and "25.0x; " in lines[1]
    assert lines[2].endswith("not measured (--quick)")
    missing = runner.comparisons([r for r in rows if r.solver != "OCC IntSS"], startup=1.25)
    assert np.isnan(missing.occ_ratio)
    assert report.comparison_lines(missing, runner)[0].endswith(": OCP not installed")
    assert report.comparison_lines(missing, runner)[2].endswith(": 1.25 s")



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


def _leaf(x):
    return len(x)


def _branch(n):
    return [_leaf([k]) for k in range(n)] + [abs(-n)]


def test_calls_counted_by_function_kind():
    """calls_of counts a call tree known by construction: _branch(3) calls itself, its list comprehension and _leaf
    three times (5 Python functions), and len three times and abs once (9 in all); the bench's line reports the
    looper pair's count."""
    from spatialkin.bench import report, runner
    assert runner.calls_of(_branch, 3) == (5, 9)
    assert runner.calls_of(_branch, 0) == (2, 3)
    c = runner.Comparisons(np.nan, "-", np.nan, "-", 0, np.nan, (378, 917))
    line = report.comparison_lines(c, runner)[3]
    assert line == ("calls: one sk.intersect of the looper's pair calls 378 Python functions, each compiled kernel one "
                    "of them (917 with C builtins; cProfile)")
    assert len(report.comparison_lines(runner.Comparisons(np.nan, "-", np.nan, "-", 0, np.nan), runner)) == 3


def test_the_figure_plots_length_error_above_and_distances_below(tmp_path, monkeypatch):
    """bench.png: per case, the methods' arc-length errors over the tolerances (above) and the points' distances
    with OpenCascade's and the proven bound (below); the drive's exact zero at the floor, marked. Oracle: the rows."""
    import matplotlib.figure
    seen = {}
    real = matplotlib.figure.Figure.savefig
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig",
                        lambda fig, *a, **k: (seen.setdefault("fig", fig), real(fig, *a, **k))[1])
    rows = [runner.Row("looper", "trace", "RK45", rtol, 2, 2, 2 * t, t, 1e-14, 10, "", err)
            for rtol, t, err in ((1e-4, 1e-3, 3e-6), (1e-8, 4e-3, 5e-9), (1e-12, 2e-2, 5e-13))]
    rows += [runner.Row("looper", "intersect", "compiled", np.nan, 2, 2, 8e-4, 4e-4, 1.8e-14, 400, "", 1e-11),
             runner.Row("looper", "certified", "compiled", np.nan, 2, 2, 2e-3, 1e-3, 1.8e-14, 0,
                        "2x intersect; proven, distance <= 6.7e-13"),
             runner.Row("looper", "OCC IntSS", "-", 1e-7, 2, 2, 6e-3, 3e-3, 6e-8),
             runner.Row("looper drive", "closed form", "-", np.nan, 10, 10, 1e-6, 1e-7, 0.0)]
    report.plot(rows, str(tmp_path / "bench.png"), "machine")
    assert (tmp_path / "bench.png").stat().st_size > 0
    top, drive, bottom = seen["fig"].axes[:3]
    assert top.get_ylabel() == "arc length s: relative error" and bottom.get_ylabel().startswith("points: distance")
    line = next(ln for ln in top.get_lines() if ln.get_label().startswith("trace RK45"))
    assert list(line.get_xdata()) == [1e-3, 4e-3, 2e-2] and list(line.get_ydata()) == [3e-6, 5e-9, 5e-13]
    below = {tuple(ln.get_ydata()) for ln in bottom.get_lines()}
    assert (6e-8,) in below and (6.7e-13,) in below and (1.8e-14,) in below
    assert [t.get_text() for t in drive.texts] == ["exact (0)"]
    assert list(drive.get_lines()[0].get_ydata()) == [report.PLOT_ERROR_FLOOR]
    assert report.proven_bound("3x intersect; not proven, distance <= inf") == math.inf
    assert report.proven_bound("no bound here") is None
