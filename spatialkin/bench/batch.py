"""The batch entry ``sk.intersect_many`` on a sweep of the looper's pair: cost per configuration against the pure
kernel cost, and points per second against the closed form's.

The sweep varies the looper sphere's radius by up to +-SPREAD (two loops throughout). In one run, interleaved
(A B C A B C ...): a Python loop of ``sk.intersect``, ``intersect_many`` in this process and on two workers (their
pool made and warmed before the timing: intersect_many keeps it for the next batches). The
pure kernel cost is the time spent inside the compiled kernels (spatialkin.kernels: the topology search, the
Runge–Kutta engine, Newton) of the same batch, read from cProfile's own-time of those functions (their calls are
few, so the profiler's overhead on them is small; it inflates only the Python, which is not counted). The closed
form (spatialkin.bench.cases.torus_sphere_closed_form, numpy, per torus angle) is the limit for this pair.
"""
import statistics
import time
from dataclasses import dataclass

import numpy as np

from ..mechanisms.looper.reference import looper_pair
from ..geometry.surfaces import Sphere
from ..tracing.batch import intersect_many
from ..tracing.components import intersect
from .cases import torus_sphere_closed_form
from .runner import DENSE_SAMPLES, best_time, kernel_seconds

#: Configurations of the sweep (full run, --quick), and the relative spread of the sphere radius.
CONFIGS = 128
QUICK_CONFIGS = 32
SPREAD = 0.02
#: Interleaved rounds (the median is kept).
ROUNDS = 5
QUICK_ROUNDS = 2
#: Torus angles of one closed-form evaluation (two points per angle where the meridian meets the sphere).
CLOSED_FORM_ANGLES = 100_000
#: Worker processes of the parallel row.
WORKERS = 2


@dataclass
class BatchRow:
    """One way of running the sweep: seconds per configuration, points returned per second."""
    label: str
    per_config: float
    points_per_second: float


def looper_configs(n):
    """n (torus, sphere) pairs: the looper's, its sphere radius scaled by 1 + SPREAD x t, t evenly in [-1, 1]."""
    torus, sphere = looper_pair()
    return [(torus, Sphere(sphere.radius * (1.0 + SPREAD * t), sphere.frame)) for t in np.linspace(-1.0, 1.0, n)]


def closed_form_rate(torus, sphere, angles=CLOSED_FORM_ANGLES):
    """Points per second of the closed form of torus ∩ sphere (best of 3 evaluations at `angles` angles)."""
    centre = torus.frame.to_local(sphere.frame.origin)
    phi = np.linspace(-np.pi, np.pi, angles, endpoint=False)

    def evaluate():
        pts, _ = torus_sphere_closed_form(torus.major_radius, torus.minor_radius, centre, sphere.radius, phi)
        return torus.frame.to_global(pts.reshape(-1, 3))
    best, pts = best_time(evaluate, 3)
    return len(pts) / best


def measure(quick=False):
    """(rows, kernel seconds per configuration, closed-form points per second, dense points per second)."""
    n, rounds = (QUICK_CONFIGS, QUICK_ROUNDS) if quick else (CONFIGS, ROUNDS)
    pairs = looper_configs(n)
    ways = {"loop of sk.intersect": lambda: [intersect(a, b) for a, b in pairs],
            "intersect_many": lambda: intersect_many(pairs),
            f"intersect_many, {WORKERS} workers": lambda: intersect_many(pairs, workers=WORKERS)}
    results = intersect_many(pairs, workers=WORKERS)       # warm: numba cache, first-call work, the kept pool
    times = {label: [] for label in ways}
    for _ in range(rounds):
        for label, func in ways.items():
            t0 = time.perf_counter()
            results = func()
            times[label].append(time.perf_counter() - t0)
    points = sum(len(c.points) for curves in results for c in curves)
    rows = [BatchRow(label, statistics.median(t) / n, points / statistics.median(t)) for label, t in times.items()]
    kernel, _ = kernel_seconds(ways["intersect_many"])
    curves = [c for found in results for c in found]
    t0 = time.perf_counter()
    for c in curves:
        c(np.linspace(0.0, c.length, DENSE_SAMPLES))
    dense_rate = len(curves) * DENSE_SAMPLES / (time.perf_counter() - t0)
    return rows, kernel / n, closed_form_rate(*pairs[n // 2]), dense_rate


def run(quick=False, echo=print):
    """Measure and print the batch table; returns its rows."""
    rows, kernel, closed_rate, dense_rate = measure(quick)
    n = QUICK_CONFIGS if quick else CONFIGS
    echo(f"sk.intersect_many on {n} configurations of the looper pair (sphere radius +-{100 * SPREAD:g}%), "
         "interleaved, medians; kernel = own time inside spatialkin.kernels (cProfile)")
    head = f"{'way':<28} {'ms/config':>10} {'x kernel':>9} {'points/s':>10} {'x closed form':>14}"
    echo(head)
    echo("-" * len(head))
    for r in rows:
        echo(f"{r.label:<28} {1e3 * r.per_config:>10.3f} {r.per_config / kernel:>9.2f} "
             f"{r.points_per_second:>10.3g} {r.points_per_second / closed_rate:>14.2e}")
    echo(f"{'compiled kernels alone':<28} {1e3 * kernel:>10.3f} {1.0:>9.2f}")
    echo(f"{'closed form (numpy)':<28} {'':>10} {'':>9} {closed_rate:>10.3g} {1.0:>14.2e}")
    echo(f"{'dense output of the curves':<28} {'':>10} {'':>9} {dense_rate:>10.3g} {dense_rate / closed_rate:>14.2e}")
    return rows
