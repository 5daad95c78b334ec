"""``spatialkin bench``: speed against error (presentation layer).

For several torus–sphere cases and the looper drive it measures the maximum distance of the results to the exact curve
(exact distance functions of both surfaces, closed forms) and the wall time per curve, for every solve_ivp method and
a range of tolerances, beside OpenCascade's GeomAPI_IntSS (optional ``cadquery-ocp``), the closed form and a per-angle
scipy root solve; prints the table and the ratios against those peers, and writes a CSV and a log–log PNG. Then, per
pair kind of plane, sphere, cylinder, cone and torus (spatialkin.bench.sidebyside): the stage profile of sk.intersect
and sk.intersect against GeomAPI_IntSS, interleaved in this process (written to bench_kinds.csv and bench_kinds.png);
and sk.intersect_many on a sweep of the looper pair against the compiled kernels' own time and the closed form
(spatialkin.bench.batch).
"""
import os
from importlib.metadata import entry_points

from .._lib import warm
from . import batch

from . import runner

from . import loads, sidebyside
from .kinds_report import plot_kinds, write_kinds_csv
from .runner import best_time
from .report import comparison_lines, machine, plot, table, write_csv

__all__ = ["run", "best_time"]
#: Entry-point group of bench plug-ins: callables (quick, echo) that print their own cases.
PLUGIN_GROUP = "spatialkin.bench"


def run(out_dir=None, quick=False, echo=print):
    """Run the bench, print the table and the ratios against the peers; with out_dir, write bench.csv and
    bench.png there.

    Returns
    -------
    rows : list of runner.Row
    comparisons : runner.Comparisons
    """
    echo(f"machine: {machine()}")
    warm.compiled_for_timing(echo)
    if not runner.baselines.occ_available():
        echo("OpenCascade (cadquery-ocp): not installed -- pip install '.[bench]' for the side-by-side run")
    rows, comparisons = runner.run_all(quick=quick, echo=echo)
    for line in table(rows) + [""] + comparison_lines(comparisons, runner) + [""]:
        echo(line)
    kind_rows = sidebyside.run(quick=quick, echo=echo)
    echo("")
    batch.run(quick=quick, echo=echo)
    loads.run(quick=quick, echo=echo)
    for plugin in entry_points(group=PLUGIN_GROUP):      # e.g. planar's cases (spatialkin never imports planar)
        plugin.load()(quick=quick, echo=echo)
    if out_dir is not None:
        os.makedirs(out_dir, exist_ok=True)
        paths = [os.path.join(out_dir, name) for name in ("bench.csv", "bench.png", "bench_kinds.csv",
                                                           "bench_kinds.png")]
        write_csv(rows, paths[0])
        plot(rows, paths[1], machine())
        write_kinds_csv(kind_rows, paths[2])
        plot_kinds(kind_rows, paths[3], f"sk.intersect vs OpenCascade per pair kind, one process, interleaved; "
                                        f"{machine()}")
        echo(f"wrote {', '.join(paths)}")
    return rows, comparisons
