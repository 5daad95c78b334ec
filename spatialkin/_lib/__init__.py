"""The library's helpers, below every other layer: the jit switch, argument validation, files written whole or not
at all, length units and the opt-in stage profiler. No numerics."""
