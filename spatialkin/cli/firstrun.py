"""The first run after an install: run the looper job at once and compile its kernels in the background.

numba compiles a kernel the first time it is called and caches it on disk (``cache=True``); the looper job
needs a few dozen kernels, about half a minute of compiling on a 2-core machine, against 1-2 s to run the
whole job's numerics with the same kernels as plain Python (SPATIALKIN_DISABLE_JIT: the same arithmetic in
the same order, so the same numbers; the job's table is bitwise the same here). So when the kernels the
looper job needs are not cached yet, ``spatialkin looper`` runs this once as plain Python in a child process
and, when it is done, starts ``python -m spatialkin.cli.firstrun``: a background process (lowest priority) that
compiles exactly those kernels (it runs the job's numerics on the reference drive) into numba's cache, then
writes a stamp naming the cache index of every kernel it compiled. Later runs find the stamp and every index
in place (for the same kernel sources) and run compiled.

``SPATIALKIN_FIRST_RUN=compile`` turns this off (kernels compile in the foreground, with a line saying so).
"""
import hashlib
import json
import os
import subprocess
import sys
import time

#: The environment switch: 'interpret' (default) or 'compile'.
ENV = "SPATIALKIN_FIRST_RUN"
#: File names beside numba's cache of spatialkin.kernels: the stamp of a finished warm-up, and the lock held
#: while one runs.
STAMP_NAME = "spatialkin-kernels-ready.json"
LOCK_NAME = "spatialkin-kernels-compiling.lock"
#: Scheduling priority of the background warm-up (added niceness).
BACKGROUND_NICENESS = 19
#: A lock older than this (s) is from a warm-up that died: it is taken over.
STALE_LOCK_S = 900.0


def _kernel_modules():
    import importlib
    import pkgutil

    from .. import kernels
    names = [m.name for m in pkgutil.walk_packages(kernels.__path__, kernels.__name__ + ".") if not m.ispkg]
    return [importlib.import_module(n) for n in names]


def _dispatchers():
    """Every numba dispatcher defined in spatialkin.kernels and its subpackages, once each."""
    from numba.core.registry import CPUDispatcher
    seen = {}
    for module in _kernel_modules():
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.py_func.__module__ == module.__name__:
                seen[id(value)] = value
    return list(seen.values())


def cache_folder():
    """The folder of numba's cache for spatialkin.kernels, or None (jit off, or numba's layout unknown)."""
    from .._lib.jit import JIT_DISABLED
    if JIT_DISABLED:
        return None
    try:
        from ..kernels.march import curve
        return curve.newton_fixed_many._cache._cache_path
    except AttributeError:
        return None


def source_hash(path):
    """sha256 of a kernel module's source, numba's own freshness stamp of its cache index."""
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def ready():
    """True when a warm-up finished for these versions and every cache index it named is still there, for the
    same kernel source (its hash); also True where this cannot be known (jit off, numba's layout unknown)."""
    folder = cache_folder()
    if folder is None:
        return True
    try:
        with open(os.path.join(folder, STAMP_NAME)) as f:
            stamp = json.load(f)
    except (OSError, ValueError):
        return False
    if not isinstance(stamp, dict) or stamp.get("versions") != _versions():
        return False
    hashes = {}
    try:
        for index, source, digest in stamp.get("indexes", []):
            if not os.path.exists(index) or hashes.setdefault(source, source_hash(source)) != digest:
                return False
    except (OSError, ValueError, TypeError, AttributeError):     # gone, or a stamp of another layout
        return False
    return True


def _versions():
    import numba

    from .. import __version__
    return {"spatialkin": __version__, "numba": numba.__version__, "python": sys.version.split()[0]}


def start_background():
    """Start the warm-up in its own session (it outlives the command), unless one is running. Returns True
    when one was started."""
    folder = cache_folder()
    if folder is None:
        return False
    lock = os.path.join(folder, LOCK_NAME)
    try:
        os.makedirs(folder, exist_ok=True)
        if os.path.exists(lock) and time.time() - os.path.getmtime(lock) < STALE_LOCK_S:
            return False
        with open(lock, "w") as f:
            f.write(str(os.getpid()))
    except OSError:
        return False
    env = {**os.environ, ENV: "compile"}
    env.pop("SPATIALKIN_DISABLE_JIT", None)
    subprocess.Popen([sys.executable, "-P", "-m", "spatialkin.cli.firstrun", lock], env=env, start_new_session=True,
                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return True


def run_interpreted(argv):
    """Run the command line argv in a child process with the kernels as plain Python; its exit status."""
    env = {**os.environ, "SPATIALKIN_DISABLE_JIT": "1", ENV: "compile"}
    return subprocess.call([sys.executable, "-P", "-m", "spatialkin.cli", *argv], env=env)


def warm_up():
    """Compile what the looper job calls (the reference drive over a turn, its analysis, the paths' check,
    every component of torus ∩ sphere for drives that do not turn fully), then write the stamp."""
    import numpy as np

    from ..mechanisms import LooperDrive
    drive = LooperDrive.reference()
    angles = np.linspace(0.0, 2 * np.pi, 361)
    motion = drive.solve(angles, omega=2.0, branch=0)
    drive.analyse(branch=0, samples=361)
    drive.torus.distance(motion.ball_center), drive.sphere.distance(motion.ball_center)
    motion.looper_tip
    partial = LooperDrive(drive.crank_radius, drive.coupler_length, drive.rocker_length,
                          rocker_frame=drive.rocker_frame.__class__((40.0, 0.0, 60.0)))
    partial.analyse(branch=0, samples=361)
    write_stamp()


def write_stamp():
    """Stamp the cache as ready: the index of every kernel compiled (or loaded) in this process."""
    folder = cache_folder()
    if folder is None:
        return
    try:
        sources = {}
        indexes = []
        for d in _dispatchers():
            if d.signatures:
                source = d.py_func.__code__.co_filename
                indexes.append([d._cache._cache_file._index_path, source,
                                sources.setdefault(source, source_hash(source))])
    except AttributeError:              # numba's cache layout changed: no stamp, the next run compiles
        return
    path = os.path.join(folder, STAMP_NAME)
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        with open(tmp, "w") as f:
            json.dump({"versions": _versions(), "indexes": indexes}, f)
        os.replace(tmp, path)
    except OSError:                     # a read-only cache: numba itself then uses another folder
        if os.path.exists(tmp):
            os.remove(tmp)


if __name__ == "__main__":
    try:
        os.nice(BACKGROUND_NICENESS)         # the command in the foreground goes first
    except (AttributeError, OSError):
        pass
    try:
        warm_up()
    finally:
        if len(sys.argv) > 1:
            try:
                os.remove(sys.argv[1])
            except OSError:
                pass
