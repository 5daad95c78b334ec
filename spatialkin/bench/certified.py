"""certify=True per pair kind, and on CAD faces: its time beside the plain call's (interleaved, medians, as
ratios), what it proves, how (by the topology search, or in closed form), and the proven distance bound (``python -m
spatialkin.bench.certified``)."""
import statistics
import time

from .._lib import warm
from ..tracing.components import intersect
from .kinds import face_cases, pair_kind_cases

#: Calls of each kind, alternating plain and certified.
REPEATS = 5


def median_pair(a, b, repeats):
    """(plain seconds, certified seconds, the certified answer): medians of interleaved calls."""
    plain, certified = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        intersect(a, b)
        t1 = time.perf_counter()
        answer = intersect(a, b, certify=True)
        t2 = time.perf_counter()
        plain.append(t1 - t0)
        certified.append(t2 - t1)
    return statistics.median(plain), statistics.median(certified), answer


def run(repeats=REPEATS, echo=print):
    """Print the table, the pair kinds then CAD faces (kinds.face_cases); returns its rows (name, plain ms,
    certified ms, ratio, proven, not proven claims, bound, how: 'search' or 'closed form')."""
    rows = []
    warm.compiled_for_timing(echo)
    echo("certify=True per pair kind (median of interleaved calls); not proven: the claims that failed; distance: "
         "the proven bound from the curves' points and dense samples to the true curve (proven in closed form: "
         "of the whole dense output, both ways)")
    echo(f"{'pair kind':22s} {'plain ms':>9s} {'cert. ms':>9s} {'ratio':>6s} {'proven':>7s} {'how':>12s} "
         f"{'distance':>9s}  not proven")
    kinds = pair_kind_cases()
    for k, (name, a, b) in enumerate(kinds + face_cases()):
        if k == len(kinds):
            echo("CAD faces (angular ranges, latitudes, an annulus: the arcs inside both faces)")
        plain, certified, answer = median_pair(a, b, repeats)
        cert = answer.certificate
        bound = max(cert.distance_bounds, default=0.0)
        failed = ", ".join(c.name for c in cert.failed) or "-"
        how = "closed form" if cert.mode == "closed form" else "search"
        rows.append((name, 1e3 * plain, 1e3 * certified, certified / plain, cert.proven, failed, bound, how))
        echo(f"{name:22s} {1e3 * plain:9.3f} {1e3 * certified:9.3f} {certified / plain:6.1f} "
             f"{'yes' if cert.proven else 'no':>7s} {how:>12s} {bound:9.1e}  {failed}")
    ratios = sorted(r[3] for r in rows)
    echo(f"certified/plain: median {statistics.median(ratios):.1f}, max {ratios[-1]:.1f}; fully proven "
         f"{sum(r[4] for r in rows)}/{len(rows)} cases")
    return rows


if __name__ == "__main__":
    run()
