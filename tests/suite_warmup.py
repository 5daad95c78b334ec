"""`spatialkin warmup` for the suite, and the check that the calls a user makes after it compile nothing.

On a cold numba cache, tests/conftest.py runs the warm-up once before any test, each workload in a fresh process of
its own, side by side: every process the suite starts then loads the compiled kernels from the cache instead of
compiling its own. The warm-up's record (its report lines and the kernel specialisations its processes hold when
done) goes to a file the tests read (``recorded()``); where no warm-up ran for the session (the cache was warm),
``warm_up`` makes one.

A process holds the specialisations of the kernels it called from Python, and of the kernels those call only where
it compiled them: one loaded from the cache brings no callee with it. A record is complete when its warm-up
compiled every specialisation it holds (a cold cache): only then does it list every one it left in the cache.
"""
import json
import os
import subprocess
import sys
import textwrap

#: The environment variable naming the file of the session's warm-up record.
RECORD_ENV = "SPATIALKIN_SUITE_WARMUP"

#: Print every specialisation of spatialkin's and planar's kernels this process holds, as JSON, on one line.
SPECIALISATIONS = textwrap.dedent("""
    import json
    from spatialkin._lib import jit
    print(json.dumps(sorted({f"{d.py_func.__module__}.{d.py_func.__qualname__}{sig}"
                             for d in jit.dispatchers() for sig in d.signatures})))
""")

#: Collect in the set `compiled` each kernel specialisation of spatialkin and planar numba compiles from here on
#: (its compile events; none for one loaded from the cache).
COMPILES = textwrap.dedent("""
    from numba.core import event
    compiled = set()
    class Listener(event.Listener):
        def on_start(self, e):
            kernel = getattr(e.data.get("dispatcher"), "py_func", None)
            if (getattr(kernel, "__module__", "") or "").startswith(("spatialkin", "planar")):
                compiled.add(f"{kernel.__module__}.{kernel.__qualname__}{tuple(e.data['args'])}")
        def on_end(self, e):
            pass
    event.register("numba:compile", Listener())
""")

#: The workloads of `spatialkin warmup`, their stale caches dropped (all of them, before any compiles), as JSON.
PREPARE = textwrap.dedent("""
    import json
    from spatialkin._lib import warm
    print(json.dumps(warm.prepare()))
""")

#: `spatialkin warmup` of the workloads named in sys.argv, then the kernel specialisations it compiled and those it
#: holds, as JSON lines.
WARM_UP = COMPILES + textwrap.dedent("""
    import json
    import sys
    from spatialkin.cli.warmup import main
    main(names=sys.argv[1:])
    print(json.dumps(sorted(compiled)))
""") + SPECIALISATIONS


def warm_up(env=None):
    """Run `spatialkin warmup` in fresh processes, one per workload (spatialkin's, planar's), side by side (env:
    their environment, default this one's); returns its record {"report": the lines they printed,
    "specialisations": [...] they hold, "complete": they compiled every one, "uncompiled": those none of them
    compiled}. RuntimeError with the stderr of one that fails. numba's cache saves are locked
    (spatialkin._lib.jit.lock_saves): two processes compiling one kernel both keep their specialisation."""
    prepared = subprocess.run([sys.executable, "-c", PREPARE], capture_output=True, text=True, env=env, timeout=600)
    if prepared.returncode != 0:
        raise RuntimeError(f"spatialkin warmup failed:\n{prepared.stderr[-3000:]}")
    names = json.loads(prepared.stdout.strip().splitlines()[-1])
    runs = [subprocess.Popen([sys.executable, "-c", WARM_UP, name], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=env) for name in names]
    reports, compiled, held = [], set(), set()
    for run in runs:
        out, err = run.communicate(timeout=1800)
        if run.returncode != 0:
            for other in runs:
                other.kill()
            raise RuntimeError(f"spatialkin warmup failed:\n{err[-3000:]}")
        *report, events, specialisations = out.strip().splitlines()
        reports.extend(report)
        compiled |= set(json.loads(events))
        held |= set(json.loads(specialisations))
    return {"report": "\n".join(reports), "specialisations": sorted(held), "complete": held <= compiled,
            "uncompiled": sorted(held - compiled)}


def recorded():
    """The record of the session's warm-up (warm_up), or None where none ran."""
    path = os.environ.get(RECORD_ENV)
    if not path or not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def record(path, env=None):
    """warm_up, its record written to path (whole: written aside, then moved), and RECORD_ENV set to path for this
    process and the ones it starts."""
    data = warm_up(env)
    with open(path + ".tmp", "w") as f:
        json.dump(data, f)
    os.replace(path + ".tmp", path)
    os.environ[RECORD_ENV] = path
    return data
