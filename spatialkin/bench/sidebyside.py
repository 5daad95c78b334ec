"""Per pair kind: where the time of sk.intersect goes (the stage profile) and sk.intersect beside OpenCascade's
GeomAPI_IntSS, both measured in this process, interleaved round by round (OCC twice, ours twice, ours with the
points read: each side's first call cold, right after the other's, its second warm), then in loops (blocks of calls
back to back, the two sides' blocks in turn), medians, so that the ratios do not depend on the machine's mood;
errors are measured distances of the returned points and dense samples to both surfaces (exact distance functions,
surface.distance).
"""
import statistics
import time
from dataclasses import dataclass

import numpy as np

from .._lib import stages, warm
from ..tracing.components import intersect
from . import baselines
from .kinds import occ_surface, pair_kind_cases, special_cases
from .runner import curve_error, kernel_seconds, points_error

#: Accuracy asked of sk.intersect (relative to the scene scale): the library's default.
OUR_TOL = 1e-10
#: Rounds of timed calls per pair kind (full run, --quick), after one untimed call of each side: each round times
#: OCC twice (cold, then warm), ours twice (cold, then warm), then ours with the points read.
CALLS = 30
QUICK_CALLS = 5
#: Blocks of back-to-back calls per side (full run, --quick), each at least LOOP_CALLS calls and LOOP_SECONDS long:
#: a call in a loop, its code and data in the caches from the call before (a sweep of many pairs).
LOOP_BLOCKS, QUICK_LOOP_BLOCKS = 7, 2
LOOP_CALLS, LOOP_SECONDS, QUICK_LOOP_SECONDS = 3, 0.02, 0.005
#: Profiled calls per pair kind (the profile is their mean; the stage timer is on only for them).
PROFILE_CALLS = 10
QUICK_PROFILE_CALLS = 3
#: Dense evaluations per curve of ours, and samples per OCC result curve (evenly in its parameter), measured.
OUR_SAMPLES = 1000
OCC_SAMPLES = 2000
QUICK_OCC_SAMPLES = 500


@dataclass
class KindRow:
    """One pair kind measured side by side.

    Attributes
    ----------
    kind : str
        'plane-sphere', ...
    ours, occ : float
        Median wall time of one sk.intersect call (tol OUR_TOL) and one GeomAPI_IntSS call (its default
        tolerance), each the second call in a row (warm: right after the same call, itself right after the other
        side's), seconds; nan for OCC when it is not installed.
    our_error, occ_error : float
        Largest measured distance to either surface of the returned points and dense samples (length units).
    our_curves, occ_curves : int
        Components returned (OCC splits a loop into several lines).
    profile : stages.StageProfile
        Mean stage profile of one sk.intersect call.
    kernel : float
        Seconds per call spent inside the compiled kernels (spatialkin.kernels, their own time from cProfile):
        what remains of a call if every line of Python around them went.
    ours_points : float
        Median wall time of one sk.intersect call followed by reading every returned curve's points, s and params
        (a closed form samples them on first read; OCC's result curves are not sampled either), warm, seconds.
    ours_cold, occ_cold : float
        As ours and occ, each call made right after the other side's calls (cold: its code and data have left the
        caches meanwhile, as a call among other work meets them), seconds.
    ours_loop, occ_loop : float
        As ours and occ, per call in a block of calls back to back (median over the blocks), seconds.
    """
    kind: str
    ours: float
    occ: float
    our_error: float
    occ_error: float
    our_curves: int
    occ_curves: int
    profile: stages.StageProfile
    kernel: float = float("nan")
    ours_points: float = float("nan")
    ours_cold: float = float("nan")
    occ_cold: float = float("nan")
    ours_loop: float = float("nan")
    occ_loop: float = float("nan")

    @property
    def ratio(self):
        """OCC's time over ours, warm (above 1: sk.intersect is faster)."""
        return self.occ / self.ours

    @property
    def cold_ratio(self):
        """OCC's time over ours, cold."""
        return self.occ_cold / self.ours_cold

    @property
    def loop_ratio(self):
        """OCC's time over ours, in loops."""
        return self.occ_loop / self.ours_loop


def occ_points(inter, samples):
    """Each result line of a GeomAPI_IntSS sampled evenly in its parameter: list of (samples, 3)."""
    out = []
    for i in range(1, inter.NbLines() + 1):
        line = inter.Line(i)
        ts = np.linspace(line.FirstParameter(), line.LastParameter(), samples)
        out.append(np.array([[p.X(), p.Y(), p.Z()] for p in (line.Value(float(t)) for t in ts)]))
    return out


def profile_of(pair, calls):
    """Mean stage profile of one sk.intersect call over `calls` profiled calls."""
    with stages.profiled() as prof:
        for _ in range(calls):
            intersect(*pair, tol=OUR_TOL)
    return prof.scaled(1.0 / calls)


def measure(kind, a, b, calls, profile_calls, occ_samples, blocks=LOOP_BLOCKS, block_seconds=LOOP_SECONDS):
    """The KindRow of one pair: interleaved timings (OCC twice, ours twice, ours with the points read, ...: each
    side's first call cold, its second warm; then `blocks` blocks of calls back to back per side, in turn, each
    at least block_seconds long), errors and the profile."""
    pair = (a, b)
    curves = intersect(*pair, tol=OUR_TOL)          # untimed: first-call work done, results kept for the error
    has_occ = baselines.occ_available()
    if has_occ:
        from OCP.GeomAPI import GeomAPI_IntSS
        geoms = (occ_surface(a), occ_surface(b))
        inter = GeomAPI_IntSS(*geoms, baselines.OCC_DEFAULT_TOL)
        if not inter.IsDone():
            raise RuntimeError(f"GeomAPI_IntSS did not finish on {kind}")
    def timed(call):
        t0 = time.perf_counter()
        call()
        return time.perf_counter() - t0

    def ours():
        intersect(*pair, tol=OUR_TOL)

    def ours_read():
        read_points(intersect(*pair, tol=OUR_TOL))

    def occ():
        GeomAPI_IntSS(*geoms, baselines.OCC_DEFAULT_TOL)

    times = {name: [] for name in ("ours", "occ", "ours_cold", "occ_cold", "ours_points", "ours_loop", "occ_loop")}
    for _ in range(calls):
        # cold: each side's first call right after the other side's calls (its working set has left the caches
        # meanwhile); warm: its next call, right after its own; the points read last, warm
        if has_occ:
            times["occ_cold"].append(timed(occ))
            times["occ"].append(timed(occ))
        times["ours_cold"].append(timed(ours))
        times["ours"].append(timed(ours))
        times["ours_points"].append(timed(ours_read))
    for _ in range(blocks):
        if has_occ:
            times["occ_loop"].append(looped(occ, block_seconds))
        times["ours_loop"].append(looped(ours, block_seconds))
    median = {name: statistics.median(t) if t else np.nan for name, t in times.items()}
    occ_error, occ_curves = np.nan, 0
    if has_occ:
        occ_error = points_error(occ_points(inter, occ_samples), pair)
        occ_curves = inter.NbLines()
    kernel, _ = kernel_seconds(lambda: [intersect(*pair, tol=OUR_TOL) for _ in range(profile_calls)])
    return KindRow(kind, median["ours"], median["occ"], curve_error(curves, pair, OUR_SAMPLES), occ_error,
                   len(curves), occ_curves, profile_of(pair, profile_calls), kernel / profile_calls,
                   median["ours_points"], median["ours_cold"], median["occ_cold"], median["ours_loop"],
                   median["occ_loop"])


def looped(call, seconds):
    """Seconds per call of `call` made back to back, at least LOOP_CALLS times and for at least `seconds`."""
    count = 0
    t0 = time.perf_counter()
    while count < LOOP_CALLS or time.perf_counter() - t0 < seconds:
        call()
        count += 1
    return (time.perf_counter() - t0) / count


def read_points(curves):
    """Every curve's stored points, arc lengths and parameters read (a closed form makes them on first read)."""
    return [(c.points, c.s, c.params) for c in curves]


def kind_rows(quick=False, echo=print, cases=None):
    """A KindRow for each of the 15 pair kinds (spatialkin.bench.kinds), or for the given [(name, a, b)]."""
    calls, profile_calls, samples, blocks, seconds = (
        (QUICK_CALLS, QUICK_PROFILE_CALLS, QUICK_OCC_SAMPLES, QUICK_LOOP_BLOCKS, QUICK_LOOP_SECONDS) if quick
        else (CALLS, PROFILE_CALLS, OCC_SAMPLES, LOOP_BLOCKS, LOOP_SECONDS))
    rows = []
    for kind, a, b in pair_kind_cases() if cases is None else cases:
        echo(f"... {kind}")
        rows.append(measure(kind, a, b, calls, profile_calls, samples, blocks, seconds))
    return rows


def occ_table(rows, calls, summary=True):
    """The side-by-side table as text lines (with summary, the ratios' medians and extremes: warm, cold, loop)."""
    head = (f"{'pair kind':<18} {'ours ms':>8} {'OCC ms':>8} {'OCC/ours':>8} {'cold':>8} {'OCC cold':>8} "
            f"{'OCC/ours':>8} {'loop':>8} {'OCC loop':>8} {'OCC/ours':>8} {'+points':>8} {'OCC/that':>8} "
            f"{'our error':>9} {'OCC error':>9} {'curves':>7}")
    lines = [f"sk.intersect (tol {OUR_TOL:g}) vs GeomAPI_IntSS (tol {baselines.OCC_DEFAULT_TOL:g}), interleaved, "
             f"median of {calls} calls each; warm: each side's second call in a row (right after the same call, "
             "itself right after the other library's); cold: its first (right after the other library's calls); "
             "loop: per call in blocks of calls back to back; error: largest distance to either surface of the "
             "returned points and dense samples; +points: ours (warm) with every curve's points, s and params read "
             "(closed forms sample them on first read)", head, "-" * len(head)]
    for r in rows:
        lines.append(f"{r.kind:<18} {1e3 * r.ours:>8.3f} {1e3 * r.occ:>8.3f} {r.ratio:>8.2f} "
                     f"{1e3 * r.ours_cold:>8.3f} {1e3 * r.occ_cold:>8.3f} {r.cold_ratio:>8.2f} "
                     f"{1e3 * r.ours_loop:>8.3f} {1e3 * r.occ_loop:>8.3f} {r.loop_ratio:>8.2f} "
                     f"{1e3 * r.ours_points:>8.3f} {r.occ / r.ours_points:>8.2f} {r.our_error:>9.1e} "
                     f"{r.occ_error:>9.1e} {r.our_curves:>3}/{r.occ_curves:<3}")
    for label, ratios in (("warm", [r.ratio for r in rows]), ("cold", [r.cold_ratio for r in rows]),
                          ("loop", [r.loop_ratio for r in rows])):
        ratios = np.array(ratios)
        if summary and np.all(np.isfinite(ratios)):
            lines.append(f"OCC/ours {label}: median {np.median(ratios):.2f}, min {ratios.min():.2f} "
                         f"({rows[int(np.argmin(ratios))].kind}), max {ratios.max():.2f} "
                         f"({rows[int(np.argmax(ratios))].kind})")
    return lines


def profile_table(rows):
    """The stage profile per pair kind as text lines: ms and % of the call per stage, and all kinds together."""
    head = (f"{'pair kind':<18} {'ms/call':>8}" + "".join(f" {stages.LABELS[s]:>13}" for s in stages.STAGES)
            + f" {'compiled':>13}")
    lines = ["sk.intersect stage profile (mean of the profiled calls; ms and % of the call per stage; "
             "spatialkin._lib.stages; compiled: own time inside spatialkin.kernels, cProfile, across the stages)",
             head, "-" * len(head)]
    total = stages.StageProfile({s: 0.0 for s in stages.STAGES}, 0.0)
    kernel = 0.0
    for r in rows:
        p = r.profile
        lines.append(_profile_line(r.kind, p, r.kernel))
        total.seconds = {s: total.seconds[s] + p.seconds[s] for s in stages.STAGES}
        total.total += p.total
        kernel += r.kernel
    lines.append(_profile_line("all kinds (sum)", total, kernel))
    return lines


def _profile_line(name, p, kernel):
    share = p.shares()
    return f"{name:<18} {1e3 * p.total:>8.3f}" + "".join(
        f" {1e3 * p.seconds[s]:>6.2f} ({100 * share[s]:>2.0f}%)" for s in stages.STAGES) + (
        f" {1e3 * kernel:>6.2f} ({100 * kernel / p.total:>2.0f}%)" if p.total > 0 else "")


def run(quick=False, echo=print):
    """Measure every pair kind, print both tables; returns the KindRows."""
    warm.compiled_for_timing(echo)
    echo("per pair kind: sk.intersect profile and OpenCascade side by side")
    rows = kind_rows(quick=quick, echo=echo)
    for line in profile_table(rows) + [""]:
        echo(line)
    if baselines.occ_available():
        for line in occ_table(rows, QUICK_CALLS if quick else CALLS):
            echo(line)
        special = kind_rows(quick=quick, echo=echo, cases=special_cases())
        echo("special placements (not in the medians above): " + "; ".join(
            f"{r.kind}: ours {1e3 * r.ours:.3f} ms, OCC {1e3 * r.occ:.3f} ms, OCC/ours {r.ratio:.2f} (cold: "
            f"{1e3 * r.ours_cold:.3f} ms, {1e3 * r.occ_cold:.3f} ms, {r.cold_ratio:.2f}; loop: "
            f"{1e3 * r.ours_loop:.3f} ms, {1e3 * r.occ_loop:.3f} ms, {r.loop_ratio:.2f}), "
            f"errors {r.our_error:.1e} / {r.occ_error:.1e}, curves {r.our_curves}/{r.occ_curves}" for r in special))
    else:
        echo("OpenCascade (cadquery-ocp) not installed: the side-by-side table is skipped")
    return rows
