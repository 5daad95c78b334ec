"""The stress cases run with certify=True: per pair kind, how many answers are fully proven, and that every proven
answer has the oracle's number of components (``python -m tests.oracles.certified_stress`` prints the table).

A proven answer with the wrong count is a lie; the table counts them (there must be none).
"""
import collections
import sys
import time

import statistics

import spatialkin as sk
from spatialkin._lib import jit
from tests.oracles.ssi import curve_components, dense_points, kind
from tests.oracles.ssi_cases import all_cases, truth_of

JOIN = 2e-6                 # x scale: returned curves this close are one component (as the stress test)


def run(cases=None, echo=print):
    """Rows {pair kind: Counter(cases, proven, lies, refused)} and the per-case ratios of certified to plain time
    {pair kind: [ratio]}; echo the table (the kernels compiled first, so that no call runs them as plain Python)."""
    jit.use(jit.COMPILED)
    every = all_cases()
    cases = every if cases is None else cases
    ratios = collections.defaultdict(list)
    by_name = {c.name: c for c in every}           # (a scaled case's truth is its base case's)
    cache = {}
    rows = collections.defaultdict(collections.Counter)
    for case in cases:
        pair = "-".join(sorted((kind(case.a), kind(case.b))))
        row = rows[pair]
        truth = truth_of(case, by_name, cache)
        if truth["kind"] in ("coincident", "unbounded"):
            continue
        row["cases"] += 1
        t0 = time.perf_counter()
        try:
            sk.intersect(case.a, case.b)
        except Exception:         # noqa: BLE001 - the plain call's refusals are the stress test's business
            pass
        t1 = time.perf_counter()
        try:
            curves = sk.intersect(case.a, case.b, certify=True)
        except (sk.TopologyError, ValueError):
            row["refused"] += 1
            continue
        t2 = time.perf_counter()
        ratios[pair].append((t2 - t1) / (t1 - t0))
        if curves.certificate.proven:
            row["proven"] += 1
            dense = [dense_points(c, case.scale) for c in curves]
            count, _ = curve_components(curves, case.scale, JOIN, dense)
            if truth["count"] is not None and count != truth["count"]:
                row["lies"] += 1
                echo(f"LIE: {case.name}: {count} components proven, the truth is {truth['count']}")
    total = collections.Counter()
    echo(f"{'pair kind':18s} {'cases':>5s} {'proven':>7s} {'share':>6s} {'lies':>5s} {'refused':>8s} "
         f"{'certified/plain (median)':>25s}")
    for pair in sorted(rows):
        r = rows[pair]
        total.update(r)
        ratio = statistics.median(ratios[pair]) if ratios[pair] else float("nan")
        echo(f"{pair:18s} {r['cases']:5d} {r['proven']:7d} {r['proven'] / max(r['cases'], 1):6.0%} {r['lies']:5d} "
             f"{r['refused']:8d} {ratio:25.1f}")
    echo(f"{'all':18s} {total['cases']:5d} {total['proven']:7d} {total['proven'] / max(total['cases'], 1):6.0%} "
         f"{total['lies']:5d} {total['refused']:8d}")
    return rows, ratios


if __name__ == "__main__":
    rows, _ = run()
    sys.exit(1 if any(r["lies"] for r in rows.values()) else 0)
