"""Where a first call's time goes on a fresh install: ``python -m spatialkin.bench.compile``.

Each entry (a first ``sk.intersect``, a looper drive over a turn, the planar six-link over a turn when planar is
installed, each followed by an ``sk.intersect`` of another pair kind) runs in a fresh interpreter on an empty numba
cache, import included, twice: with the kernels compiled in the foreground (``SPATIALKIN_FIRST_RUN=compile``,
numba's own compile events recorded) and as the library starts by default (plain Python at once, compiled in the
background: spatialkin._lib.warm; the background process is stopped after the call). It prints the first-call
times of both, and the kernels' compile times: each kernel's own time (its callees' compiles excluded) summed over
its specialisations, the costliest first (``--all``: every kernel).
"""
import json
import os
import signal
import subprocess
import sys
import tempfile

#: The entries: (name, code after ``import numpy as np; import spatialkin as sk``).
ENTRIES = (
    ("sk.intersect(torus, sphere)",
     "sk.intersect(sk.Torus(2, 1), sk.Sphere(1.2, frame=sk.Frame(origin=(2.5, 0, 0.3))))"),
    ("LooperDrive.reference().solve(361 angles)",
     "from spatialkin.mechanisms import LooperDrive\nLooperDrive.reference().solve(np.linspace(0, 2 * np.pi, 361))"),
    ("planar fnf_sixbar().solve(361 angles)",
     "import planar\nplanar.examples.fnf_sixbar().solve(np.linspace(0, 2 * np.pi, 361))"),
)
#: The call after each entry: another pair kind.
LATER = "sk.intersect(sk.Cylinder(1.0), sk.Sphere(1.2, frame=sk.Frame(origin=(0.5, 0, 0.3))))"
#: Kernels listed in the table.
TOP = 10

CHILD = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from numba.core import event
records, stack = [], []

class Recorder(event.Listener):
    def on_start(self, ev):
        stack.append((time.perf_counter(), ev.data.get("dispatcher"), [0.0]))

    def on_end(self, ev):
        t0, dispatcher, inner = stack.pop()
        took = time.perf_counter() - t0
        if stack:
            stack[-1][2][0] += took
        f = getattr(dispatcher, "py_func", None)
        name = f"{getattr(f, '__module__', '?')}.{getattr(f, '__qualname__', '?')}"
        lines = len(__import__("inspect").getsourcelines(f)[0]) if f is not None else 0
        records.append((name, took - inner[0], lines))

event.register("numba:compile", Recorder())
t0 = time.perf_counter()
import numpy as np
import spatialkin as sk
ENTRY
t1 = time.perf_counter()
LATER
t2 = time.perf_counter()
from spatialkin._lib import warm
json.dump({"first": t1 - t0, "later": t2 - t1, "records": records,
           "background": [p.pid for p in warm._STARTED.values()]}, sys.stdout)
"""


def run_entry(entry, mode):
    """One entry in a fresh interpreter on an empty cache: {'first', 'later' (s), 'records': [(kernel, own compile
    time s, source lines)]}, or None when it cannot run (planar not installed)."""
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "SPATIALKIN_FIRST_RUN": mode}
        out = subprocess.run([sys.executable, "-c", CHILD.replace("ENTRY", entry).replace("LATER", LATER)], capture_output=True,
                             text=True, env=env)
        if out.returncode != 0:
            return None
        result = json.loads(out.stdout)
        for pid in result["background"]:       # the background warm-up would compete with the next entry
            try:
                os.killpg(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        return result


def table(echo=print, every=False):
    """Run every entry both ways and print the first-call times and the costliest kernels' compile times (every
    kernel's with every=True)."""
    costs = {}
    echo("first call on a fresh install (fresh interpreter, empty numba cache, import included; s)")
    echo(f"{'entry':44s} {'compiling':>10s} {'then':>6s} {'default':>8s} {'then':>6s}  kernels compiled")
    for name, entry in ENTRIES:
        compiled, default = run_entry(entry, "compile"), run_entry(entry, "interpret")
        if compiled is None or default is None:
            echo(f"{name:44s} (not run: {name.split()[0]} is not installed)")
            continue
        for kernel, took, lines in compiled["records"]:
            cost = costs.setdefault(kernel, [0.0, 0, lines])
            cost[0] += took
            cost[1] += 1
        echo(f"{name:44s} {compiled['first']:10.2f} {compiled['later']:6.2f} {default['first']:8.2f} "
             f"{default['later']:6.2f}  {len(compiled['records'])} specialisations, "
             f"{sum(r[1] for r in compiled['records']):.1f} s")
    echo("('compiling': SPATIALKIN_FIRST_RUN=compile; 'default': plain Python at once, compiled in the background; "
         "'then': an sk.intersect of a cylinder and a sphere next)")
    echo("")
    shown = "every kernel" if every else f"the {TOP} costliest kernels"
    echo(f"{shown} to compile (own time, callees excluded, over the entries above)")
    echo(f"{'kernel':64s} {'s':>6s} {'specialisations':>16s} {'lines':>6s}")
    ranked = sorted(costs.items(), key=lambda kv: -kv[1][0])
    for kernel, (took, count, lines) in ranked if every else ranked[:TOP]:
        echo(f"{kernel:64s} {took:6.2f} {count:16d} {lines:6d}")
    total = sum(c[0] for c in costs.values())
    echo(f"all {len(costs)} kernels: {total:.1f} s over {sum(c[1] for c in costs.values())} specialisations")
    return costs


if __name__ == "__main__":
    table(every="--all" in sys.argv[1:])
