"""The one place that defines the numba jit decorator, and the switch between compiled and interpreted kernels.

Every kernel is compiled with ``cache=True`` so that compilation happens once per machine, not per
process. Set the environment variable ``SPATIALKIN_DISABLE_JIT=1`` to run the kernels as plain Python
(for debugging and coverage); numba's own ``NUMBA_DISABLE_JIT`` works too.

Each kernel is kept both ways: its plain Python function and its numba dispatcher. ``use`` binds every kernel
name in spatialkin's and planar's modules to one or the other, so that a process whose kernels are not compiled
yet runs them as plain Python (the same arithmetic, about a hundred times slower, with no wait) and turns to the
compiled ones once they are in numba's cache (spatialkin._lib.warm decides when).

Saves to numba's on-disk cache are made under an exclusive lock of the cache folder (POSIX ``flock``): numba
reads a kernel's index, adds the new specialisation and writes the index back, so two processes compiling the
same kernel at once (a worker pool or a test runner's workers on a cold cache) would otherwise lose one entry, or
give two specialisations one data file.

``borrowed`` and ``kept`` let a kernel use arrays without numba's reference counts (atomic operations) where a loop
would count them at every step: the integrator's, Newton's and the dense output's.
"""
import os
import sys

try:
    import fcntl
except ImportError:                 # (no flock: numba's own saves, unlocked)
    fcntl = None

import numba
import numba.extending
from numba.core import types
from numba.core import event as _event

#: True when kernels run as plain Python (debugging / coverage).
JIT_DISABLED = os.environ.get("SPATIALKIN_DISABLE_JIT", "0") not in ("", "0")
#: The kernels' modes: numba dispatchers (compiled on first call, or loaded from the cache) or plain Python.
COMPILED, INTERPRETED = "compiled", "interpreted"
#: The packages whose modules use, and bind, kernels.
PACKAGES = ("spatialkin", "planar")

#: The lock file numba's saves take, one per cache folder.
SAVE_LOCK = "spatialkin-numba-save.lock"

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
        if options["cache"]:
            lock_saves(dispatcher)
        _KERNELS.append((f, dispatcher))
        _COUNTERPART[id(f)], _COUNTERPART[id(dispatcher)] = dispatcher, f
        return f if _MODE[0] == INTERPRETED else dispatcher

    return wrap if func is None else wrap(func)


def lock_saves(dispatcher):
    """Make the dispatcher's saves to numba's cache take SAVE_LOCK of its cache folder, exclusively, for the whole
    read-add-write of the index and the data file; left as numba's where flock or numba's cache layout is missing,
    or where the lock file cannot be opened (a read-only folder: numba then saves nothing there either)."""
    cache_file = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
    folder = getattr(cache_file, "_cache_path", None)
    if fcntl is None or folder is None or not callable(getattr(cache_file, "save", None)):
        return
    save = cache_file.save

    def locked_save(key, data):
        try:
            fd = os.open(os.path.join(folder, SAVE_LOCK), os.O_CREAT | os.O_RDWR, 0o644)
        except OSError:
            return save(key, data)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            return save(key, data)
        finally:
            os.close(fd)            # (closing releases the lock)

    cache_file.save = locked_save


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


def borrowed(value):
    """The same array (or tuple holding arrays), borrowed: in compiled code, a view of each array without its
    memory's reference count (a NULL meminfo), so that the code it passes through counts no references to it.
    numba counts a reference, with an atomic operation, for every array a variable takes, an inlined function's
    arguments included; in the integrator's and Newton's loops these cost as much as the arithmetic. A borrowed
    view is valid only while its array is alive: a kernel's argument (its caller holds it), or an array the kernel
    keeps alive with ``kept``; it is never returned or stored. In Python, the value itself."""
    return value


def kept(*arrays):
    """Nothing: a use of each array, so that compiled code keeps them alive up to this point (the owners of
    borrowed views)."""


def _borrow(context, builder, typ, value):
    """borrowed's code: the value of type typ with every array's meminfo set to NULL (tuples item by item)."""
    if isinstance(typ, types.Array):
        view = context.make_array(typ)(context, builder, value=value)
        view.meminfo = context.get_constant_null(types.MemInfoPointer(types.voidptr))
        return view._getvalue()
    if isinstance(typ, types.BaseTuple):
        items = [_borrow(context, builder, t, builder.extract_value(value, i)) for i, t in enumerate(typ.types)]
        return context.make_tuple(builder, typ, items)
    context.nrt.incref(builder, typ, value)        # (anything else: a new reference, as any returned value)
    return value


@numba.extending.intrinsic
def _borrowed(typingctx, value):
    return value(value), lambda context, builder, signature, args: _borrow(context, builder, value, args[0])


@numba.extending.overload(borrowed, jit_options={"cache": True})
def _borrowed_overload(value):
    return lambda value: _borrowed(value)


@numba.extending.overload(kept, jit_options={"cache": True})
def _kept_overload(*arrays):
    return lambda *arrays: None
