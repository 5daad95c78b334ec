"""sk.intersect_many: sk.intersect over many pairs in one call, in worker processes when asked.

A sweep of a mechanism's configurations (the looper's torus and sphere at many placements, a tolerance study)
asks for the same intersection many times. The batch checks every argument before any numerics run, so that a bad
pair or option fails at once with its index, then intersects pair after pair, or in chunks on worker processes:
each pair's result is what ``sk.intersect`` returns for it (same curves, same numbers), in the pairs' order.

Workers start by fork where the platform has it, elsewhere by the platform's default (they import spatialkin);
the pool is kept for the next batches, each worker warmed by one small intersection when it starts (numba loads
its kernels from the cache once per worker).
"""
import atexit
import concurrent.futures
import multiprocessing
import os

from ..validation import check_choice, check_count
from .intersect import intersect
from .traits import check_surface
from .trace import DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL, check_options

#: Pairs sent to a worker per task (amortises the transfer of surfaces and curves).
CHUNK = 8
#: A batch smaller than this many chunks per worker runs in this process (the pool would cost more than it gives).
MIN_CHUNKS_PER_WORKER = 2
#: What a failing pair gives: 'raise' (the first failure is raised, naming its index) or 'return' (the exception
#: object stands in the result list at its index, the other pairs go on).
ERRORS = ("raise", "return")


class BatchError(RuntimeError):
    """A pair of sk.intersect_many failed (errors='raise'); ``index`` is its position, ``__cause__`` the error."""

    def __init__(self, index, error):
        super().__init__(f"pairs[{index}]: {type(error).__name__}: {error}")
        self.index = index


def intersect_many(pairs, tol=1e-10, *, workers=1, errors="raise", method=DEFAULT_METHOD, rtol=DEFAULT_RTOL,
                   atol=None, max_length=None, singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK):
    """``sk.intersect`` of every pair: a list (one entry per pair, in order) of lists of Curve.

    Parameters
    ----------
    pairs : iterable of (Surface, Surface)
    tol, method, rtol, atol, max_length, singular_tol, pullback
        As in ``sk.intersect``, the same for every pair.
    workers : int or None
        Worker processes (None: one per CPU). 1 (default) runs in this process; a batch of fewer than
        MIN_CHUNKS_PER_WORKER x CHUNK pairs per worker also does.
    errors : {'raise', 'return'}
        On a failing pair (TopologyError, CoincidentSurfacesError, ...): raise BatchError naming its index (its
        cause chained), or put the exception in that pair's place and go on.

    Returns
    -------
    list of (list of Curve or Exception)

    Raises
    ------
    ValueError, TypeError
        A bad option or pair (named: ``pairs[k]``), before any pair is intersected.
    BatchError
        A pair failed and errors='raise'.
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
        done = list(_pool(workers, pairs[0]).map(_intersect_chunk, *zip(*chunks), [options] * len(chunks),
                                       [errors] * len(chunks)))
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


def _intersect_chunk(start, chunk, options, errors):
    """sk.intersect of each pair of a chunk; with errors='return' (and in workers, where the first failure is
    re-raised by the caller) a failure is kept as its exception. `start` is the chunk's first index."""
    out = []
    for k, (a, b) in enumerate(chunk):
        try:
            out.append(intersect(a, b, **options))
        except Exception as error:      # noqa: BLE001 - kept in place, raised by the caller as BatchError
            if errors == "raise" and multiprocessing.parent_process() is None:
                raise BatchError(start + k, error) from error
            out.append(error)
    return out


_POOLS = {}


def _pool(workers, first):
    """The process pool of `workers` workers, made at its first use and kept for the next batches (a worker's
    first intersection loads the compiled kernels, about 0.3 s: paid once per worker, not per batch; `first`, a
    pair, warms each worker); shut down at exit."""
    pool = _POOLS.get(workers)
    if pool is None:
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=_context(),
                                                      initializer=_warm, initargs=first)
        _POOLS[workers] = pool
        if len(_POOLS) == 1:
            atexit.register(_shutdown)
    return pool


def _warm(a, b):
    """A worker's first work: the first pair of the batch that made the pool, so that its kernels are loaded before
    the first chunk (a failure there is left for the chunk that has the pair)."""
    try:
        intersect(a, b)
    except Exception:       # noqa: BLE001 - the pair's own chunk reports it
        pass


def _shutdown():
    for pool in _POOLS.values():
        pool.shutdown(wait=False, cancel_futures=True)
    _POOLS.clear()


def _context():
    """fork where the platform has it (workers inherit the compiled kernels), else the default start method."""
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("fork" if "fork" in methods else None)
