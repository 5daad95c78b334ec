"""The kernels' first use on a machine: run them as plain Python at once, compile them in the background.

numba compiles a kernel the first time it is called and caches it on disk (``cache=True``): a few hundred
specialisations, one to two minutes of compiling on a 2-core machine, against well under a second to run a first
``sk.intersect`` or looper drive with the same kernels as plain Python. So when the package is imported and the
cache is not warm (no stamp of a finished warm-up for these versions and kernel sources), the kernels run as plain
Python (spatialkin._lib.jit.use), one warning says so, and a background process at the lowest priority compiles
them (``python -m`` each registered workload: spatialkin.cli.warmup, and planar.warmup once planar is imported),
then writes a stamp naming the cache index of every kernel it compiled. The next call of an entry point after it
finishes (``refresh``) turns the kernels to their compiled, cached form, in this process too; later processes find
the stamps and start compiled. Kernels inline kernels of other modules, and numba checks a cached kernel against its
own module only: a stamp also holds a digest of every kernel module, and once any of them changes, every cached
kernel of the stamp's folders is dropped and compiles again (``drop_stale``).

``SPATIALKIN_FIRST_RUN=compile`` turns this off: kernels compile in the foreground, as numba does by default
(announced by the entry that compiles). ``spatialkin warmup`` compiles everything in the foreground ahead (for an
image, or a cluster's workers).
"""
import functools
import hashlib
import json
import os
import subprocess
import sys
import time
import warnings

from . import jit

#: The environment switch: 'interpret' (default: plain Python while the cache is cold) or 'compile'.
ENV = "SPATIALKIN_FIRST_RUN"
#: The workload spatialkin itself compiles (a module run as ``python -m``).
WORKLOAD = "spatialkin.cli.warmup"
#: The entry point group naming other packages' workloads (a module with ``run()``; planar's: planar.warmup).
PLUGIN_GROUP = "spatialkin.warmup"
#: The names beside numba's cache: a workload's stamp, and the lock its background warm-up holds.
STAMP = "spatialkin-warm-{}.json"
LOCK = "spatialkin-warm-{}.lock"
#: Scheduling priority of the background warm-up (added niceness).
BACKGROUND_NICENESS = 19
#: A lock older than this (s) is from a warm-up that died: it is taken over.
STALE_LOCK_S = 900.0
#: refresh() looks at the background warm-ups at most this often (s).
POLL_S = 1.0
#: The folder of the kernel modules (beside this one), which inline one another's kernels: numba checks a cached
#: kernel against its own module's source only, so a stamp records a digest of them all and of the jit module
#: (kernels_digest), and a change to any of them makes every kernel of the stamp's folders compile again
#: (drop_stale).
KERNELS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "kernels")
#: The line of a cold cache, and of a compile in the foreground (each once per process).
COLD = ("spatialkin: first use of its compiled kernels on this machine: they are being compiled in the background "
        "(one to two minutes); until then they run as plain Python (the same results, slower), and this process "
        "turns to the compiled ones when they are ready. `spatialkin warmup` compiles them ahead.")
COMPILING = ("spatialkin: compiling the numerical kernels this call needs (one to two minutes on first use; numba "
             "caches them, later calls and processes start at once). `spatialkin warmup` compiles them ahead.")

#: The workloads registered (spatialkin's, then each package's that imports this), the background processes
#: started by this process, and when refresh() last looked.
_WORKLOADS = [WORKLOAD]
_STARTED = {}
_LAST_POLL = [0.0]
#: What has been said (COLD, COMPILING), and how a line is said: a warning (Python, Jupyter) unless the command
#: line sets its own (one line on stderr).
_SAID = set()
_SAY = [None]


def _probe():
    return 0


@functools.lru_cache(maxsize=1)
def cache_folder():
    """The folder of numba's cache for this package's modules (where the stamps are), or None (jit off, or numba's
    layout unknown); found once per process."""
    if jit.JIT_DISABLED:
        return None
    try:
        import numba
        return numba.njit(cache=True)(_probe)._cache._cache_path
    except AttributeError:
        return None


def source_hash(path):
    """sha256 of a kernel module's source, numba's own freshness stamp of its cache index."""
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


@functools.lru_cache(maxsize=1)
def kernel_hashes():
    """{path: source_hash} of every kernel module (the .py files under KERNELS, in a fixed order) and of the jit
    module, whose compiled helpers (borrowed, kept) the kernels compile into themselves; read once per process."""
    hashes = {jit.__file__: source_hash(jit.__file__)}
    for folder, subfolders, names in os.walk(KERNELS):
        subfolders.sort()
        for name in sorted(names):
            if name.endswith(".py"):
                path = os.path.join(folder, name)
                hashes[path] = source_hash(path)
    return hashes


def kernels_digest():
    """sha256 over every kernel module's relative path and source hash, and the jit module's (kernel_hashes)."""
    digest = hashlib.sha256()
    for path, source in kernel_hashes().items():
        name = "jit" if path == jit.__file__ else os.path.relpath(path, KERNELS)
        digest.update(name.encode())
        digest.update(source.encode())
    return digest.hexdigest()


def versions():
    """The versions a stamp is valid for."""
    import numba

    from .version import __version__
    return {"spatialkin": __version__, "numba": numba.__version__, "python": sys.version.split()[0]}


def ready(workload=WORKLOAD):
    """True when a warm-up of the workload finished for these versions and every cache index it named is still
    there, for the same kernel source (its hash); also True where this cannot be known (jit off, numba's layout
    unknown)."""
    folder = cache_folder()
    if folder is None:
        return True
    try:
        with open(os.path.join(folder, STAMP.format(workload))) as f:
            stamp = json.load(f)
    except (OSError, ValueError):
        return False
    if not isinstance(stamp, dict) or stamp.get("versions") != versions() or stamp.get("kernels") != kernels_digest():
        return False
    hashes = dict(kernel_hashes())          # (the kernel modules read once: the digest above read them)
    try:
        for index, source, digest in stamp.get("indexes", []):
            if not os.path.exists(index) or hashes.setdefault(source, source_hash(source)) != digest:
                return False
    except (OSError, ValueError, TypeError, AttributeError):     # gone, or a stamp of another layout
        return False
    return True


def write_stamp(workload=WORKLOAD):
    """Stamp the cache as warm for the workload: the index of every kernel compiled (or loaded) in this process."""
    folder = cache_folder()
    if folder is None:
        return
    sources, indexes = {}, []
    for d in jit.dispatchers():
        if not d.signatures or d.py_func.__module__.partition(".")[0] not in jit.PACKAGES:
            continue
        index = _index_of(d)
        if index is None or not os.path.exists(index):     # (a kernel not cached on disk: nothing to stamp)
            continue
        source = d.py_func.__code__.co_filename
        indexes.append([index, source, sources.setdefault(source, source_hash(source))])
    if not indexes:                     # numba's cache layout unknown: no stamp, the next run compiles
        return
    path = os.path.join(folder, STAMP.format(workload))
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        os.makedirs(folder, exist_ok=True)
        with open(tmp, "w") as f:
            json.dump({"versions": versions(), "kernels": kernels_digest(), "indexes": indexes}, f)
        os.replace(tmp, path)
    except OSError:                     # a read-only cache: numba itself then uses another folder
        if os.path.exists(tmp):
            os.remove(tmp)


def _index_of(dispatcher):
    """The path of a kernel's cache index in numba's layout, or None where that layout is unknown."""
    return getattr(getattr(getattr(dispatcher, "_cache", None), "_cache_file", None), "_index_path", None)


def kernel_folders(package):
    """The cache folders of the package's kernels registered in this process (one per source folder)."""
    folders = set()
    for d in jit.dispatchers():
        index = _index_of(d)
        if index is not None and d.py_func.__module__.partition(".")[0] == package:
            folders.add(os.path.dirname(index))
    return folders


def drop_stale(workload=WORKLOAD):
    """Remove the workload's stamp and every cache index in the folders of its kernels (those the stamp names, and
    those of its package's kernels registered here) when a kernel module changed since the stamp was written (its
    kernels digest differs): a kernel may have inlined the changed one, and numba, which compares a cached kernel
    with its own module only, would load it as it was. Returns how many indexes were removed (none when the stamp
    is current, absent or unreadable)."""
    folder = cache_folder()
    if folder is None:
        return 0
    path = os.path.join(folder, STAMP.format(workload))
    try:
        with open(path) as f:
            stamp = json.load(f)
        if stamp.get("kernels") == kernels_digest():
            return 0
        folders = {os.path.dirname(entry[0]) for entry in stamp.get("indexes", [])}
    except (OSError, ValueError, TypeError, AttributeError, IndexError, KeyError):
        return 0
    folders |= kernel_folders(workload.partition(".")[0])
    removed = 0
    for where in folders:
        try:
            names = os.listdir(where)
        except (OSError, TypeError):
            continue
        for name in names:
            if name.endswith(".nbi"):
                try:
                    os.remove(os.path.join(where, name))
                    removed += 1
                except OSError:
                    pass
    try:
        os.remove(path)
    except OSError:
        pass
    return removed


def start_background(workload=WORKLOAD):
    """Start the workload's warm-up in its own session at the lowest priority (it outlives this process), unless one
    is running. Returns True when one was started."""
    folder = cache_folder()
    if folder is None:
        return False
    lock = os.path.join(folder, LOCK.format(workload))
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
    _STARTED[workload] = subprocess.Popen(
        [sys.executable, "-c", prelude(workload) + f"from spatialkin._lib import warm; "
         f"warm.background({workload!r}, {lock!r})"],
        env=env, start_new_session=True, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL)
    return True


def prelude(workload):
    """The first statement of a child process's ``python -c`` code: the folders this process imported spatialkin and
    the workload's package from, first on its path. ``python -c`` puts the working folder first, and a child started
    in a source checkout would import the checkout's copy, compiling kernels this process never looks up (numba
    keys its cache by the kernels' source files)."""
    roots = []
    for name in ("spatialkin", workload.partition(".")[0]):
        module = sys.modules.get(name)
        if module is not None and getattr(module, "__file__", None):
            root = os.path.dirname(os.path.dirname(os.path.abspath(module.__file__)))
            if root not in roots:
                roots.append(root)
    return f"import sys; sys.path[:0] = {roots!r}; "


def stop_background():
    """Stop the background warm-ups this process started (a foreground warm-up does their work) and free their
    locks."""
    import signal
    folder = cache_folder()
    for workload, process in list(_STARTED.items()):
        if process.poll() is None:
            try:
                os.killpg(process.pid, signal.SIGTERM)
            except (ProcessLookupError, PermissionError):
                pass
            process.wait()
        if folder is not None:
            try:
                os.remove(os.path.join(folder, LOCK.format(workload)))
            except OSError:
                pass
        del _STARTED[workload]


def workloads():
    """spatialkin's workload, every other registered one, then every installed package's (a module named by the
    entry point group PLUGIN_GROUP, e.g. planar.warmup)."""
    from importlib.metadata import entry_points
    names = list(_WORKLOADS)
    for point in entry_points(group=PLUGIN_GROUP):
        if point.module not in names:
            names.append(point.module)
    return names


def prepare(names=None):
    """Before compiling the workloads (default: workloads()): their packages imported, this process's background
    warm-ups stopped, and the stale caches of them all dropped (drop_stale), before any of them compiles. Returns
    the workloads' names. (Workloads compiled in parallel processes each call it on their own workload only, after
    one call on them all.)"""
    import importlib
    names = workloads() if names is None else list(names)
    for name in names:        # (a package registers its workload when imported, and on a cold cache turns the kernels
        importlib.import_module(name.partition(".")[0])       # to plain Python: before the switch below, not after)
    stop_background()
    for name in names:
        drop_stale(name)
    return names


def compile_ahead(names=None):
    """Compile the workloads (default: workloads()) in the foreground, each kernel compiled or loaded from the
    cache, and stamp each; this process's background warm-ups are stopped (this does their work) and the kernels
    turned to their compiled form. Stale caches are dropped first, all of them before any compiles (a kernel
    module changed since a stamp: its folders compile again). Returns {workload: seconds}."""
    import importlib
    names = prepare(names)
    jit.use(jit.COMPILED)
    seconds = {}
    for name in names:
        t0 = time.perf_counter()
        importlib.import_module(name).run()
        write_stamp(name)
        seconds[name] = time.perf_counter() - t0
    return seconds


def compiled_for_timing(say):
    """Before a benchmark: the kernels compiled, so that it times compiled code. Nothing to do where the kernels
    are compiled and every workload's cache is warm; else say(line) and compile_ahead (the background warm-up's
    work, in the foreground). Returns the seconds spent compiling (0.0 when none)."""
    if jit.JIT_DISABLED or jit.mode() == jit.COMPILED and all(ready(w) for w in workloads()):
        return 0.0
    say("compiling the kernels first (one to two minutes on a cold cache), so that the timings are of compiled code")
    return sum(compile_ahead().values())


def background(workload, lock):
    """The background warm-up (run in its own process): the workload's ``run()`` compiled at the lowest priority,
    then its stamp; the lock removed in any case."""
    try:
        os.nice(BACKGROUND_NICENESS)         # the foreground goes first
    except (AttributeError, OSError):
        pass
    try:
        import importlib
        drop_stale(workload)
        importlib.import_module(workload).run()
        write_stamp(workload)
    finally:
        try:
            os.remove(lock)
        except OSError:
            pass


def wanted():
    """True unless the first-run switch asks for compiling in the foreground (or jit is off)."""
    return not jit.JIT_DISABLED and os.environ.get(ENV, "interpret") != "compile"


def register(workload):
    """Add a package's warm-up workload (a module with ``run()``, importable as ``python -m``); when its kernels are
    not in the cache, they run as plain Python and it is compiled in the background (see the module docstring)."""
    if workload not in _WORKLOADS:
        _WORKLOADS.append(workload)
    if wanted() and not ready(workload):
        _go_cold(workload)
    elif not wanted():
        drop_stale(workload)


def decide():
    """At import, before the kernels: plain Python and a background warm-up when the cache is cold; a line when a
    kernel compiles in the foreground (numba fires no event for one loaded from its cache)."""
    if jit.JIT_DISABLED:
        return
    jit.announce_compilation(lambda: _say(COMPILING))
    if wanted() and not ready(WORKLOAD):
        _go_cold(WORKLOAD)
    elif not wanted():              # (compiling in the foreground: no kernel inlining a changed one loaded as it was)
        drop_stale(WORKLOAD)


def _go_cold(workload):
    jit.use(jit.INTERPRETED)
    start_background(workload)


def say_with(say):
    """Say the first-use lines with say(line) (the command line's stderr) instead of a warning."""
    _SAY[0] = say


def _say(line):
    if line in _SAID:
        return
    _SAID.add(line)
    if _SAY[0] is not None:
        _SAY[0](line)
    else:
        warnings.warn(line, RuntimeWarning, stacklevel=_caller_level())


def _caller_level():
    """The stacklevel, for a warnings.warn in _say, of the first frame outside spatialkin, planar, numba and the
    context managers numba's compile events pass through (contextlib): the user's call, the line a warning names."""
    import contextlib
    import numba
    inside = (os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep,
              os.path.dirname(os.path.abspath(numba.__file__)) + os.sep,
              os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "planar")
              + os.sep, os.path.abspath(contextlib.__file__))
    frame, level = sys._getframe(2), 2              # (_say's caller: stacklevel 2 of a warn in _say)
    while frame.f_back is not None and os.path.abspath(frame.f_code.co_filename).startswith(inside):
        frame, level = frame.f_back, level + 1
    return level


def refresh():
    """At an entry point: while the kernels run as plain Python, say so once; once every registered workload is warm
    (its background warm-up finished, here or in another process), turn them to their compiled form. Cheap when they
    are compiled already."""
    if jit.mode() == jit.COMPILED:
        return
    _say(COLD)
    now = time.monotonic()
    if now - _LAST_POLL[0] < POLL_S:
        return
    _LAST_POLL[0] = now
    if any(p.poll() is None for p in _STARTED.values()):
        return
    if all(ready(w) for w in _WORKLOADS):
        jit.use(jit.COMPILED)
