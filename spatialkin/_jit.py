"""The one place that defines the numba jit decorator.

Every kernel is compiled with ``cache=True`` so that compilation happens once per machine, not per
process. Set the environment variable ``SPATIALKIN_DISABLE_JIT=1`` to run the kernels as plain Python
(for debugging and coverage); numba's own ``NUMBA_DISABLE_JIT`` works too.
"""
import os

import numba

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
