"""sk.intersect_many: sk.intersect over many pairs in one call, in worker processes when asked.

A sweep of a mechanism's configurations (the looper's torus and sphere at many placements, a tolerance study)
asks for the same intersection many times. The batch checks every argument before any numerics run, so that a bad
pair or option fails at once with its index, then intersects pair after pair, or in chunks on worker processes:
each pair's result is what ``sk.intersect`` returns for it (same curves, same numbers), in the pairs' order.

Workers are forked from a server process that imported spatialkin (forkserver; spawn where the platform has no
fork), never from the caller, whose threads (a notebook's, a BLAS pool's) a fork would not carry. One pool is kept
for the next batches, each worker warmed by one small intersection when it starts (numba loads its kernels from
the cache once per worker); it is replaced when another worker count is asked, dropped when a worker dies (the
next batch starts a new one), and shut down at exit. Surfaces of a kind registered at run time reach workers only
when their module can be imported there, and a script calls it under ``if __name__ == "__main__":`` (its workers
re-import the main module; worker_context).
"""
import atexit
import concurrent.futures
import multiprocessing
import os
import sys
import traceback
from concurrent.futures.process import BrokenProcessPool

from ..geometry.frame import Frame
from ..geometry.surfaces import Sphere, Torus
from .._lib.validation import check_choice, check_count
from .components import intersect
from ..geometry.traits import check_surface
from .march.trace import DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, check_options

#: Pairs sent to a worker per task (amortises the transfer of surfaces and curves).
CHUNK = 8
#: A batch smaller than this many chunks per worker runs in this process (the pool would cost more than it gives).
MIN_CHUNKS_PER_WORKER = 2
#: What a failing pair gives: 'raise' (the first failure is raised, naming its index) or 'return' (the exception
#: object stands in the result list at its index, the other pairs go on).
ERRORS = ("raise", "return")


class BatchError(RuntimeError):
    """A pair of sk.intersect_many failed (errors='raise'): its index and the error it raised.

    Parameters
    ----------
    index : int
        Position of the failing pair in ``pairs``.
    error : Exception
        What sk.intersect raised for it (also the ``__cause__``); on a worker its traceback is attached as a note.

    Attributes
    ----------
    index : int
    error : Exception

    Examples
    --------
    >>> import spatialkin as sk
    >>> pairs = [(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0)))), (sk.Sphere(1.0), sk.Sphere(1.0))]
    >>> try:
    ...     sk.intersect_many(pairs)
    ... except sk.BatchError as failure:
    ...     print(failure.index, type(failure.error).__name__, failure.__cause__ is failure.error)
    1 CoincidentSurfacesError True
    """

    def __init__(self, index, error):
        super().__init__(f"pairs[{index}]: {type(error).__name__}: {error}")
        self.index = index
        self.error = error

    def __reduce__(self):
        return BatchError, (self.index, self.error)


def intersect_many(pairs, tol=1e-10, *, workers=1, errors="raise", method=DEFAULT_METHOD, rtol=DEFAULT_RTOL,
                   atol=None, max_length=None, singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK):
    """``sk.intersect`` of every pair: a list (one entry per pair, in order) of lists of Curve.

    Each pair's result is what ``sk.intersect`` returns for it (the same curves, the same numbers), whether it
    runs in this process or on worker processes. Every argument is checked before any pair is intersected.

    Parameters
    ----------
    pairs : iterable of (Surface, Surface)
        The pairs (a, b) to intersect.
    tol, method, rtol, atol, max_length, singular_tol, pullback
        As in ``sk.intersect``, the same for every pair.
    workers : int or None
        Worker processes (None: one per CPU). 1 (default) runs in this process; a batch of fewer than
        MIN_CHUNKS_PER_WORKER x CHUNK pairs per worker also does. A kept pool of forkserver workers (spawn where
        there is no fork) serves later batches; from a script, call it under ``if __name__ == "__main__":``.
    errors : {'raise', 'return'}
        On a failing pair (TopologyError, CoincidentSurfacesError, ...): raise BatchError naming its index (its
        cause chained), or put the exception in that pair's place and go on.

    Returns
    -------
    list of (list of Curve or Exception)
        One entry per pair, in the pairs' order.

    Raises
    ------
    ValueError, TypeError
        A bad option or pair (named: ``pairs[k]``), before any pair is intersected.
    BatchError
        A pair failed and errors='raise'.
    RuntimeError
        A worker process died (its pool is discarded; the next call starts a new one).

    Examples
    --------
    A sphere moved along the axis of a torus (a sweep of placements):

    >>> import spatialkin as sk
    >>> torus = sk.Torus(1.0, 0.4)
    >>> pairs = [(torus, sk.Sphere(1.0, sk.Frame((1.0, 0.0, z)))) for z in (0.0, 0.3, 5.0)]
    >>> results = sk.intersect_many(pairs, tol=1e-10)
    >>> [len(curves) for curves in results]
    [2, 2, 0]
    >>> [round(c.length, 6) for c in results[1]] == [round(c.length, 6) for c in sk.intersect(*pairs[1])]
    True

    With errors='return' a failing pair leaves its exception in place:

    >>> results = sk.intersect_many(pairs[:1] + [(sk.Sphere(1.0), sk.Sphere(1.0))], errors="return")
    >>> [type(r).__name__ for r in results]
    ['list', 'CoincidentSurfacesError']
    >>> sk.intersect_many([(torus, "sphere")])
    Traceback (most recent call last):
    ...
    TypeError: pairs[0][1] must be a spatialkin surface (...), got str
    """
    pairs = check_pairs(pairs)
    check_choice("errors", errors, ERRORS)
    workers = (os.cpu_count() or 1) if workers is None else check_count("workers", workers)
    options = dict(tol=tol, method=method, rtol=rtol, atol=atol, max_length=max_length, singular_tol=singular_tol,
                   pullback=pullback)
    check_options(tol, method, rtol, atol, max_length, singular_tol, pullback)    # once: none depends on a pair
    chunks = [(start, pairs[start:start + CHUNK]) for start in range(0, len(pairs), CHUNK)]
    if workers == 1 or len(chunks) < MIN_CHUNKS_PER_WORKER * workers:
        done = [_intersect_chunk(start, chunk, options, errors) for start, chunk in chunks]
    else:
        done = _on_workers(workers, chunks, options, errors, len(pairs))
    results = [r for part in done for r in part]
    if errors == "raise":
        for k, r in enumerate(results):
            if isinstance(r, Exception):
                raise BatchError(k, r) from r
    return results


def check_pairs(pairs):
    """The pairs as a list of (a, b) tuples of surfaces, or TypeError/ValueError naming ``pairs[k]``."""
    try:
        items = list(pairs)
    except TypeError:
        raise TypeError(f"pairs must be an iterable of (surface, surface), got {type(pairs).__name__}") from None
    out = []
    for k, item in enumerate(items):
        try:
            a, b = item
        except (TypeError, ValueError):
            raise ValueError(f"pairs[{k}] must be a pair (surface, surface), got {item!r}") from None
        check_surface(f"pairs[{k}][0]", a)
        check_surface(f"pairs[{k}][1]", b)
        out.append((a, b))
    return out


def _on_workers(workers, chunks, options, errors, count):
    """The chunks' results from the kept pool, in order. With errors='raise' the chunks not started yet are
    cancelled at the first one that holds a failure (the caller raises it)."""
    pool = _pool(workers)
    futures = []
    done = []
    try:        # a pool that found a dead worker before this batch refuses the submission itself
        for start, chunk in chunks:
            futures.append(pool.submit(_intersect_chunk, start, chunk, options, "return"))
        for future in futures:
            done.append(future.result())
            if errors == "raise" and any(isinstance(r, Exception) for r in done[-1]):
                break
    except BrokenProcessPool as err:
        _discard()
        raise RuntimeError(f"a worker process of sk.intersect_many died (pairs[0:{count}] on {workers} workers); "
                           "its pool is discarded and the next call starts a new one. From a script, call it under "
                           "'if __name__ == \"__main__\":' (workers re-import the main module)") from err
    finally:
        for future in futures:
            future.cancel()
    return done


def _intersect_chunk(start, chunk, options, errors):
    """sk.intersect of each pair of a chunk (`start`: the index of its first pair). A failure raises BatchError
    with errors='raise' (in this process), and is kept in place as its exception with errors='return' (and on
    workers, which are always given 'return': the caller raises the first one)."""
    out = []
    for k, (a, b) in enumerate(chunk):
        try:
            out.append(intersect(a, b, **options))
        except Exception as error:      # noqa: BLE001 - kept in place, or raised as BatchError naming the pair
            if errors == "raise":
                raise BatchError(start + k, error) from error
            if multiprocessing.parent_process() is not None:   # on a worker: its traceback travels as a note
                error.add_note("".join(traceback.format_exception(error)).rstrip())
            out.append(error)
    return out


_POOL = {}          # {'workers': n, 'executor': ProcessPoolExecutor}: one kept pool


def _pool(workers):
    """The kept process pool, with `workers` workers (made at its first use, replaced when the count changes; a
    worker's first intersection loads the compiled kernels, about 0.3 s: paid once per worker, not per batch);
    shut down at exit."""
    if _POOL.get("workers") != workers:
        _discard()
        _warm()             # compiled here first, so that the workers load the kernels from numba's disk cache
        _POOL["executor"] = concurrent.futures.ProcessPoolExecutor(
            max_workers=workers, mp_context=worker_context(["spatialkin"]), initializer=_warm)
        _POOL["workers"] = workers
    return _POOL["executor"]


def _warm():
    """A worker's first work: one small torus–sphere intersection, so that its kernels are loaded before the first
    chunk."""
    intersect(Torus(1.0, 0.4), Sphere(1.0, Frame((1.0, 0.0, 0.3))))


def _discard(wait=False):
    """Shut the kept pool down (if any) and forget it."""
    executor = _POOL.pop("executor", None)
    _POOL.clear()
    if executor is not None:
        executor.shutdown(wait=wait, cancel_futures=True)


def worker_context(preload):
    """The start method of spatialkin's worker pools (intersect_many, spatialkin.design's sweep): forkserver, the
    modules `preload` imported in the server (a worker starts as a fork of a process that has them, never of the
    caller's, whose threads a fork would not carry); spawn where there is no fork. A forkserver's or spawned
    worker re-imports the caller's main script (a script needs ``if __name__ == "__main__":`` round the call), so
    when that is no file (a script piped on stdin) the workers are plain forks of this process."""
    methods = multiprocessing.get_all_start_methods()
    main_file = getattr(sys.modules.get("__main__"), "__file__", None)
    if main_file is not None and not os.path.isfile(main_file) and "fork" in methods:
        return multiprocessing.get_context("fork")
    if "forkserver" in methods:
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(list(preload))
        return context
    return multiprocessing.get_context("spawn")


atexit.register(_discard)
if hasattr(os, "register_at_fork"):     # a forked child (the user's own pool) must not use the parent's workers
    os.register_at_fork(after_in_child=_POOL.clear)
