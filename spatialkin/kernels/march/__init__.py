"""Kernels of spatialkin.tracing.march: Dragilev's right-hand side, the pull-back and Newton corrections (curve), the
intersection branch as a system of the engine (branch_ode), and the start of a segment in one call (restart)."""
