"""The one place that defines the numba jit decorator, and the switch between compiled and interpreted kernels.

Every kernel is compiled with ``cache=True`` so that compilation happens once per machine, not per
process. Set the environment variable ``SPATIALKIN_DISABLE_JIT=1`` to run the kernels as plain Python
(for debugging and coverage); numba's own ``NUMBA_DISABLE_JIT`` works too.

Each kernel is kept both ways: its plain Python function and its numba dispatcher. ``use`` binds every kernel
name in spatialkin's and planar's modules to one or the other, so that a process whose kernels are not compiled
yet runs them as plain Python (the same arithmetic, about a hundred times slower, with no wait) and turns to the
compiled ones once they are in numba's cache (spatialkin._lib.warm decides when).
"""
import os
import sys

import numba
from numba.core import event as _event

#: True when kernels run as plain Python (debugging / coverage).
JIT_DISABLED = os.environ.get("SPATIALKIN_DISABLE_JIT", "0") not in ("", "0")
#: The kernels' modes: numba dispatchers (compiled on first call, or loaded from the cache) or plain Python.
COMPILED, INTERPRETED = "compiled", "interpreted"
#: The packages whose modules use, and bind, kernels.
PACKAGES = ("spatialkin", "planar")

#: The current mode (one entry, so that the decorator and use() share it).
_MODE = [COMPILED]
#: Every kernel as (plain function, dispatcher), and each of those objects' counterpart by id.
_KERNELS = []
_COUNTERPART = {}


def jit(func=None, **options):
    """Compile ``func`` with numba in nopython mode, cached on disk, unless jit is disabled. Returns the dispatcher,
    or the plain function while the kernels are interpreted (``use``)."""
    options.setdefault("cache", True)
    options.setdefault("nogil", True)

    def wrap(f):
        if JIT_DISABLED:
            return f
        dispatcher = numba.njit(**options)(f)
        _KERNELS.append((f, dispatcher))
        _COUNTERPART[id(f)], _COUNTERPART[id(dispatcher)] = dispatcher, f
        return f if _MODE[0] == INTERPRETED else dispatcher

    return wrap if func is None else wrap(func)


def mode():
    """The kernels' current mode: COMPILED or INTERPRETED."""
    return _MODE[0]


def use(mode):
    """Bind every kernel name in the loaded modules of spatialkin and planar to the kernels' dispatchers (COMPILED)
    or plain functions (INTERPRETED); kernels decorated later follow the mode too. Nothing changes with jit
    disabled. ValueError for another mode."""
    if mode not in (COMPILED, INTERPRETED):
        raise ValueError(f"mode must be {COMPILED!r} or {INTERPRETED!r}, got {mode!r}")
    if JIT_DISABLED or _MODE[0] == mode:
        return
    _MODE[0] = mode
    wanted = {id(f if mode == COMPILED else d) for f, d in _KERNELS}
    for name, module in list(sys.modules.items()):
        if module is None or name.partition(".")[0] not in PACKAGES:
            continue
        space = vars(module)
        for key, value in list(space.items()):
            if id(value) in wanted and _COUNTERPART.get(id(value)) is not None:
                space[key] = _COUNTERPART[id(value)]


def dispatchers():
    """Every kernel's numba dispatcher."""
    return [d for _, d in _KERNELS]


class _FirstCompile(_event.Listener):
    """numba event listener: calls announce() once, when the first spatialkin or planar kernel starts
    compiling (numba fires no compile event for a kernel loaded from its on-disk cache)."""

    def __init__(self, announce):
        self.announce = announce
        self.done = False

    def on_start(self, event):
        if self.done:
            return
        dispatcher = event.data.get("dispatcher")
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        if module.split(".")[0] in PACKAGES:
            self.done = True
            self.announce()

    def on_end(self, event):
        pass


def announce_compilation(announce):
    """Call announce() once, the first time a kernel is compiled in this process (a fresh install or a
    cleared cache); nothing happens when every kernel a call needs loads from the cache. Returns the
    listener (numba.core.event.unregister("numba:compile", listener) removes it)."""
    listener = _FirstCompile(announce)
    _event.register("numba:compile", listener)
    return listener
