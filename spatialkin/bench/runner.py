"""Measurements of the bench: error (measured distances, exact distance functions) and wall time per curve
for every solve_ivp method and tolerance, OpenCascade beside them, the looper drive against the closed form
and a per-angle root solve, and the start-up time of a fresh process.
"""
import cProfile
import os
import pstats
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass

import numpy as np

from ..mechanisms import LooperDrive
from ..mechanisms.looper.reference import looper_pair
from ..tracing.components import intersect
from ..tracing.march.start import scene_scale
from ..tracing.search.topology import topology
from ..tracing.march.trace import DEFAULT_METHOD, METHODS
from ..tracing.single import trace
from . import baselines
from .cases import looper_closed_form, torus_sphere_cases

#: solve_ivp relative tolerances of the work–precision table (full run, quick run).
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
QUICK_RTOLS = (1e-6, 1e-10)
#: Accuracy asked of the traced points (relative to the scene scale), the library's default.
TRACE_TOL = 1e-10
#: Timed repetitions of each measurement (the best is kept: the machine is shared and noisy).
REPEATS = 3
QUICK_REPEATS = 1
#: A run whose right-hand-side evaluations per curve would exceed this is skipped (RK23 at tight tolerances
#: takes seconds and says nothing new).
MAX_NFEV_PER_CURVE = 40_000
#: Dense evaluations per traced curve whose distances to both surfaces enter the error.
DENSE_SAMPLES = 1000
#: Chord-sum samples per closed curve for its geometric length (and twice as many, Richardson-extrapolated).
LENGTH_SAMPLES = 8192
#: Crank angles of the looper's full turn (0.1 degree steps) and the crank rate.
LOOPER_ANGLES = 3601
LOOPER_OMEGA = 1.0
#: Start-up runs of a fresh interpreter (after one that fills numba's cache), the median is reported.
STARTUP_RUNS = 3
#: The comparison with GeomAPI_IntSS times the fastest tracer setting whose loops lie within this distance of both
#: surfaces (length units) and that finds every component of every case.
COMPARE_ERROR = 1e-10
#: The first result a user sees: import and intersect the looper's pair, in a fresh interpreter.
STARTUP_SCRIPT = ("import spatialkin as sk; from spatialkin.mechanisms.looper.reference import looper_pair; "
                  "c = sk.intersect(*looper_pair()); assert len(c) == 2")


@dataclass
class Row:
    """One line of the work–precision table.

    Attributes
    ----------
    case : str
        Case name ('looper', 'ring-2', ..., or 'looper drive' for the mechanism rows).
    solver : str
        'trace', 'intersect', 'OCC IntSS', 'LooperDrive', 'closed form', 'scipy root'.
    method : str
        solve_ivp method, or '-'.
    rtol : float
        solve_ivp rtol, or the OCC tolerance, or nan.
    curves : int
        Components returned (expected count in `expected`).
    expected : int
    seconds : float
        Best wall time of the whole call.
    per_curve : float
        seconds / curves.
    error : float
        Largest measured distance of the returned points and dense samples to either surface (length units);
        for the looper rows the largest position error against the closed form.
    nfev : int
        Right-hand-side evaluations (tracer rows), else 0.
    extra : str
        Further measured errors (looper: velocity and acceleration, relative).
    length_error : float
        Largest relative error of the curves' arc length (the solver's s) against their geometric length
        (tracer rows; nan elsewhere): what the solver's tolerance buys, as positions are exact regardless.
    """
    case: str
    solver: str
    method: str
    rtol: float
    curves: int
    expected: int
    seconds: float
    per_curve: float
    error: float
    nfev: int = 0
    extra: str = ""
    length_error: float = np.nan


def kernel_seconds(func):
    """(seconds of own time inside spatialkin.kernels functions while func() runs, func's result)."""
    prof = cProfile.Profile()
    out = prof.runcall(func)
    marker = os.sep + os.path.join("spatialkin", "kernels") + os.sep
    stats = pstats.Stats(prof).stats
    return sum(tt for (path, _, _), (_, _, tt, _, _) in stats.items() if marker in path), out


def best_time(func, repeats):
    """(best wall time in seconds, the last result) of `repeats` calls of func(), after one untimed call (numba's
    cache loaded, first-call work done: warm timings)."""
    best, out = np.inf, func()
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        out = func()
        best = min(best, time.perf_counter() - t0)
    return best, out


def curve_error(curves, surfaces, samples=DENSE_SAMPLES):
    """Largest exact distance to either surface of the curves' points and of `samples` dense evaluations each."""
    worst = 0.0
    for c in curves:
        pts = [c.points] + ([c.sample(samples)] if c.length > 0 else [])
        for p in pts:
            worst = max(worst, max(float(np.max(s.distance(p))) for s in surfaces))
    return worst


def geometric_length(curve, n=LENGTH_SAMPLES):
    """Length of a closed curve's point set, independent of its arc-length parameter: chord sums of n and 2n
    dense points (each exact on both surfaces), Richardson-extrapolated (error O(n^-4))."""
    sums = [float(np.sum(np.linalg.norm(np.diff(curve(np.linspace(0.0, curve.length, m + 1)), axis=0), axis=1)))
            for m in (n, 2 * n)]
    return (4.0 * sums[1] - sums[0]) / 3.0


def length_error(curves):
    """Largest relative error of the closed curves' length (the integrated arc length) against
    geometric_length; nan if there is no closed curve."""
    errs = [abs(c.length - geo) / geo for c in curves if c.closed and c.length > 0
            for geo in (geometric_length(c),)]
    return max(errs) if errs else np.nan


def points_error(point_sets, surfaces):
    """Largest exact distance to either surface over arrays of points (M, 3)."""
    return max((float(np.max(s.distance(p))) for p in point_sets for s in surfaces), default=0.0)


def tracer_rows(case, rtols, repeats, methods=METHODS):
    """Work–precision rows of sk.trace for one case: each component traced from a point on it."""
    a, b = case.torus, case.sphere
    starts = [c.points[0] for c in intersect(a, b)]
    rows = []
    for method in methods:
        for rtol in rtols:
            probe = [trace(a, b, p, tol=TRACE_TOL, method=method, rtol=rtol) for p in starts]
            nfev = sum(c.nfev for c in probe) // max(1, len(starts))
            if nfev > MAX_NFEV_PER_CURVE:     # shown, not timed: tight RK23, or a loop missed at loose rtol
                rows.append(Row(case.name, "trace", method, rtol, sum(c.closed for c in probe), case.components,
                                np.nan, np.nan, curve_error(probe, (a, b)), nfev,
                                extra=f"not timed: {nfev} rhs evaluations per curve; " + ", ".join(
                                    sorted({c.status for c in probe}))))
                continue
            seconds, curves = best_time(
                lambda: [trace(a, b, p, tol=TRACE_TOL, method=method, rtol=rtol) for p in starts], repeats)
            n = sum(c.closed for c in curves)
            rows.append(Row(case.name, "trace", method, rtol, n, case.components, seconds,
                            seconds / max(1, len(curves)), curve_error(curves, (a, b)),
                            sum(c.nfev for c in curves) // max(1, len(curves)), length_error=length_error(curves)))
    return rows


def intersect_rows(case, repeats):
    """sk.intersect at its defaults (every component, the topology stage included; its share in the notes),
    and with certify=True (every claim of the answer proven or not; the proven distance of the curve's points and
    dense samples to the true curve)."""
    pair = (case.torus, case.sphere)
    seconds, curves = best_time(lambda: intersect(*pair, tol=TRACE_TOL), repeats)
    found = curves[0].topology if curves else None
    topo_seconds, _ = best_time(lambda: topology(*pair, scene_scale(*pair), TRACE_TOL * scene_scale(*pair)),
                                repeats)
    note = f"topology {1e3 * topo_seconds:.2f} ms ({100 * topo_seconds / seconds:.0f}%)"
    if found is not None:
        note += f", {found.boxes} boxes"
    rows = [Row(case.name, "intersect", DEFAULT_METHOD, np.nan, len(curves), case.components, seconds,
                seconds / max(1, len(curves)), curve_error(curves, pair),
                sum(c.nfev for c in curves) // max(1, len(curves)), length_error=length_error(curves), extra=note)]
    c_seconds, c_curves = best_time(lambda: intersect(*pair, tol=TRACE_TOL, certify=True), repeats)
    bound = max(c_curves.certificate.distance_bounds, default=np.nan)
    state = "proven" if c_curves.certificate.proven else "not proven"
    rows.append(Row(case.name, "certified", DEFAULT_METHOD, np.nan, len(c_curves), case.components, c_seconds,
                    c_seconds / max(1, len(c_curves)), curve_error(c_curves, pair), 0,
                    extra=f"{c_seconds / seconds:.0f}x intersect; {state}, distance <= {bound:.1e}"))
    return rows


def spline_rows(case):
    """B-splines of the components: OpenCascade's (GeomAPI_IntSS at its default tolerance: poles, measured
    error) beside curve.to_bspline at the same deviation (control points, measured deviation, time)."""
    if not baselines.occ_available():
        return []
    pair = (case.torus, case.sphere)
    curves = intersect(*pair, tol=TRACE_TOL)
    occ = baselines.occ_splines(*pair, baselines.OCC_DEFAULT_TOL)
    scale = scene_scale(*pair)
    rows = []
    for poles, degree, pts in occ:
        error = points_error([pts], pair)
        curve = min(curves, key=lambda c: float(np.min(c.closest(pts[:8])[1])))
        seconds, spline = best_time(lambda: curve.to_bspline(error / scale), 1)
        rows.append(Row(case.name, "B-spline", "-", error / scale, len(spline.c), poles, seconds, seconds,
                        spline.deviation, extra=f"ours {len(spline.c)} control points (degree 5) at "
                        f"{spline.deviation:.1e} vs OCC {poles} poles (degree {degree}) at {error:.1e}"))
    return rows


def occ_rows(case, repeats, tols=(baselines.OCC_DEFAULT_TOL, baselines.OCC_TIGHT_TOL)):
    """GeomAPI_IntSS at its default and a tight tolerance (empty when OCP is not installed)."""
    if not baselines.occ_available():
        return []
    rows = []
    for tol in tols:
        seconds, curves = baselines.occ_intersect(case.torus, case.sphere, tol, repeats)
        rows.append(Row(case.name, "OCC IntSS", "-", tol, len(curves), case.components, seconds,
                        seconds / max(1, len(curves)), points_error(curves, (case.torus, case.sphere))))
    return rows


def looper_rows(repeats, n=LOOPER_ANGLES, omega=LOOPER_OMEGA):
    """The looper's full turn at n crank angles with velocities and accelerations: spatialkin (a fresh
    LooperDrive each time, the intersection traced inside), the closed form, and scipy's root per angle."""
    u1 = np.linspace(0.0, 2 * np.pi, n)
    drive = LooperDrive.reference()
    exact = looper_closed_form(drive, u1, omega)

    def ours():
        m = LooperDrive.reference().solve(u1, omega=omega)
        return m.ball_center, m.ball_velocity, m.ball_acceleration

    def by_root():
        start = drive.assemble(u1[0], branch=0)[1:]
        return baselines.looper_by_root(drive, u1, omega, start)

    rows = []
    for name, func in (("LooperDrive", ours), ("closed form", lambda: looper_closed_form(drive, u1, omega)),
                       ("scipy root", by_root)):
        seconds, (c, v, a) = best_time(func, repeats)
        vel = np.max(np.abs(v - exact[1])) / np.max(np.abs(exact[1]))
        acc = np.max(np.abs(a - exact[2])) / np.max(np.abs(exact[2]))
        on = points_error([c], (drive.torus, drive.sphere))
        rows.append(Row("looper drive", name, "-", np.nan, n, n, seconds, seconds / n,
                        float(np.max(np.abs(c - exact[0]))),
                        extra=f"vel {vel:.1e} acc {acc:.1e} on-surf {on:.1e}"))
    return rows


def startup_seconds(runs=STARTUP_RUNS):
    """Median wall time of a fresh interpreter importing spatialkin and intersecting the looper's pair (numba's
    cache warmed by one run first), measured as a whole process."""
    cmd = [sys.executable, "-c", STARTUP_SCRIPT]
    subprocess.run(cmd, check=True, capture_output=True)
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def calls_of(func, *args):
    """(Python functions, all functions with C builtins) that one call func(*args) makes, func's own call included,
    counted by cProfile (a compiled kernel counts as a Python function: each is a call from Python)."""
    prof = cProfile.Profile()
    prof.runcall(func, *args)
    stats = pstats.Stats(prof).stats
    calls = [(path, count) for (path, _, name), (_, count, _, _, _) in stats.items()
             if "_lsprof.Profiler" not in name]                  # (not the profiler's own disable)
    return sum(count for path, count in calls if path != "~"), sum(count for _, count in calls)


def intersect_calls(pair):
    """calls_of one sk.intersect of the pair after three warm calls."""
    for _ in range(3):
        intersect(*pair)
    return calls_of(intersect, *pair)


@dataclass
class Comparisons:
    """The ratios against the peers and the start-up time, with what they compare.

    Attributes
    ----------
    occ_ratio : float
        GeomAPI_IntSS's time per curve (its default tolerance) over the tracer's (the fastest setting within
        COMPARE_ERROR that finds every component of every case); nan without OpenCascade.
    occ_detail : str
        Both sides' settings, times and errors.
    looper_ratio : float
        The per-angle scipy root solve's time over LooperDrive's for the looper's full turn; nan if not measured.
    looper_detail : str
        Both sides' times and errors.
    looper_angles : int
        Crank angles of the looper's turn (0 if not measured).
    startup : float
        Seconds of a fresh process importing spatialkin and intersecting the looper's pair; nan with --quick.
    calls : tuple of int
        Python functions (then all functions) one sk.intersect of the looper's pair calls (intersect_calls); () if
        not counted.
    """
    occ_ratio: float
    occ_detail: str
    looper_ratio: float
    looper_detail: str
    looper_angles: int
    startup: float
    calls: tuple = ()


def comparisons(rows, startup, calls=()):
    """The ratios against the peers from the measured rows (nan where a side is missing); calls: intersect_calls'
    count, passed through."""
    occ = [r for r in rows if r.case == "looper" and r.solver == "OCC IntSS"
           and r.rtol == baselines.OCC_DEFAULT_TOL]
    # settings that found every component within COMPARE_ERROR in every case (no setting picked for one case)
    traced = [r for r in rows if r.solver == "trace"]
    failed = {(r.method, r.rtol) for r in traced
              if not (r.error <= COMPARE_ERROR and r.curves == r.expected and np.isfinite(r.seconds))}
    fits = [r for r in traced if r.case == "looper" and (r.method, r.rtol) not in failed]
    occ_ratio = np.nan
    if not occ:
        occ_detail = "OCP not installed"
    elif not fits:
        occ_detail = f"no trace setting found every component of every case within {COMPARE_ERROR:g}"
    else:
        best = min(fits, key=lambda r: r.per_curve)
        occ_ratio = occ[0].per_curve / best.per_curve
        occ_detail = (f"OCC IntSS tol {occ[0].rtol:g}: {1e3 * occ[0].per_curve:.2f} ms/curve (error "
                      f"{occ[0].error:.1e}) vs trace {best.method} rtol {best.rtol:g}: "
                      f"{1e3 * best.per_curve:.2f} ms/curve (error {best.error:.1e}; the fastest setting "
                      "that found every component of every case)")
    by = {r.solver: r for r in rows if r.case == "looper drive"}
    looper_ratio, looper_detail, looper_angles = np.nan, "not measured", 0
    if "LooperDrive" in by and "scipy root" in by:
        ours, root = by["LooperDrive"], by["scipy root"]
        looper_ratio, looper_angles = root.seconds / ours.seconds, ours.curves
        looper_detail = (f"scipy root {1e3 * root.seconds:.1f} ms (error {root.error:.1e}) vs LooperDrive "
                         f"{1e3 * ours.seconds:.1f} ms (error {ours.error:.1e})")
    return Comparisons(occ_ratio, occ_detail, looper_ratio, looper_detail, looper_angles, startup, tuple(calls))


def run_all(quick=False, echo=print):
    """Every measurement of the bench; returns (rows, comparisons)."""
    rtols = QUICK_RTOLS if quick else RTOLS
    repeats = QUICK_REPEATS if quick else REPEATS
    cases = torus_sphere_cases()[:2] if quick else torus_sphere_cases()
    rows = []
    for case in cases:
        echo(f"... {case.name}")
        rows += tracer_rows(case, rtols, repeats)
        rows += intersect_rows(case, repeats)
        rows += spline_rows(case)
        rows += occ_rows(case, repeats)
    echo("... looper drive")
    rows += looper_rows(repeats)
    startup = np.nan if quick else startup_seconds()
    return rows, comparisons(rows, startup, intersect_calls(looper_pair()))
