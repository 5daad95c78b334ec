"""Layer 1: numba-jitted pure functions on floats and arrays (no classes, no scipy, no validation).

``jit`` is the decorator every kernel is compiled with (defined in spatialkin._lib.jit: cache=True, and
SPATIALKIN_DISABLE_JIT=1 runs the kernels as plain Python); code outside spatialkin that writes kernels on
spatialkin's pipeline (planar) uses it from here.
"""
from .._lib.jit import jit

__all__ = ["jit"]
