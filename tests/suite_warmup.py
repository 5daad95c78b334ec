"""`spatialkin warmup` for the suite, and the check that the calls a user makes after it compile nothing.

On a cold numba cache, tests/conftest.py runs the warm-up once, in a fresh process, before any test: every process
the suite starts then loads the compiled kernels from the cache instead of compiling its own. The warm-up's record
(its report line and the kernel specialisations it holds when done) goes to a file the tests read
(``recorded()``); where no warm-up ran for the session (the cache was warm), ``warm_up`` makes one.

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

#: `spatialkin warmup`, then the kernel specialisations it compiled and those it holds, as JSON lines.
WARM_UP = COMPILES + textwrap.dedent("""
    import json
    from spatialkin.cli.warmup import main
    main()
    print(json.dumps(sorted(compiled)))
""") + SPECIALISATIONS


def warm_up(env=None):
    """Run `spatialkin warmup` in a fresh process (env: its environment, default this one's); returns its record
    {"report": the line it printed, "specialisations": [...], "complete": it compiled every one}. RuntimeError with
    its stderr when it fails."""
    run = subprocess.run([sys.executable, "-c", WARM_UP], capture_output=True, text=True, env=env, timeout=1800)
    if run.returncode != 0:
        raise RuntimeError(f"spatialkin warmup failed:\n{run.stderr[-3000:]}")
    *report, compiled, specialisations = run.stdout.strip().splitlines()
    specialisations = json.loads(specialisations)
    return {"report": "\n".join(report), "specialisations": specialisations,
            "complete": set(specialisations) <= set(json.loads(compiled))}


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
