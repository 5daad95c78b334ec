"""The one place that defines the numba jit decorator.

Every kernel is compiled with ``cache=True`` so that compilation happens once per machine, not per
process. Set the environment variable ``SPATIALKIN_DISABLE_JIT=1`` to run the kernels as plain Python
(for debugging and coverage); numba's own ``NUMBA_DISABLE_JIT`` works too.
"""
import os

import numba
from numba.core import event as _event

#: True when kernels run as plain Python (debugging / coverage).
JIT_DISABLED = os.environ.get("SPATIALKIN_DISABLE_JIT", "0") not in ("", "0")


def jit(func=None, **options):
    """Compile ``func`` with numba in nopython mode, cached on disk, unless jit is disabled."""
    options.setdefault("cache", True)
    options.setdefault("nogil", True)

    def wrap(f):
        if JIT_DISABLED:
            return f
        return numba.njit(**options)(f)

    return wrap if func is None else wrap(func)


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
        if module.split(".")[0] in ("spatialkin", "planar"):
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
