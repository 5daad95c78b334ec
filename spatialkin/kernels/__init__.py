"""Layer 1: numba-jitted pure functions on floats and arrays (no classes, no scipy, no validation)."""
