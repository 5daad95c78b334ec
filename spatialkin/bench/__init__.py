"""``spatialkin bench``: speed against error (presentation layer).

For several torus–sphere cases and the looper drive it measures the maximum distance of the results to the
exact curve (exact distance functions of both surfaces, closed forms) and the wall time per curve, for every
solve_ivp method and a range of tolerances, beside OpenCascade's GeomAPI_IntSS (optional ``cadquery-ocp``),
the closed form and a per-angle scipy root solve; prints the table and the goal ratios, and writes a CSV
and a log–log PNG. Then, per pair kind of plane, sphere, cylinder, cone and torus (spatialkin.bench.sidebyside):
the stage profile of sk.intersect and sk.intersect against GeomAPI_IntSS, interleaved in this process.
"""
import os
from importlib.metadata import entry_points

from . import runner, sidebyside
from .runner import best_time
from .report import goal_lines, machine, plot, table, write_csv

__all__ = ["run", "best_time"]
#: Entry-point group of bench plug-ins: callables (quick, echo) that print their own cases.
PLUGIN_GROUP = "spatialkin.bench"


def run(out_dir=None, quick=False, echo=print):
    """Run the bench, print the table and the goal ratios; with out_dir, write bench.csv and bench.png there.

    Returns
    -------
    rows : list of runner.Row
    goals : runner.Goals
    """
    echo(f"machine: {machine()}")
    if not runner.baselines.occ_available():
        echo("OpenCascade (cadquery-ocp): not installed -- pip install '.[bench]' for the side-by-side run")
    rows, goals = runner.run_all(quick=quick, echo=echo)
    for line in table(rows) + [""] + goal_lines(goals, runner) + [""]:
        echo(line)
    sidebyside.run(quick=quick, echo=echo)
    for plugin in entry_points(group=PLUGIN_GROUP):      # e.g. planar's cases (spatialkin never imports planar)
        plugin.load()(quick=quick, echo=echo)
    if out_dir is not None:
        os.makedirs(out_dir, exist_ok=True)
        write_csv(rows, os.path.join(out_dir, "bench.csv"))
        plot(rows, os.path.join(out_dir, "bench.png"), machine())
        echo(f"wrote {os.path.join(out_dir, 'bench.csv')} and {os.path.join(out_dir, 'bench.png')}")
    return rows, goals
