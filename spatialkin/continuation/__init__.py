"""Continuation: follow a mechanism's configuration curve F(y) = 0 by arc length, and solve it at given inputs.

    from spatialkin.continuation import CurveKernels, trace_cycle, solve_at

``trace_cycle(kernels, y0, args, period, max_length)`` traces the closed configuration curve through y0 (a full
turn of the input, or between lock positions) with solve_ivp and the compiled engine; ``solve_at`` predicts the
states at given inputs from the traced branch and corrects each by the system's Newton at fixed input. The
looper drive, the RSSR and the planar linkages are built on these.
"""
from .cycle import ContinuationError, CurveKernels, Cycle, trace_cycle
from .solve import predict, solve_at, wrap_inputs

__all__ = ["ContinuationError", "CurveKernels", "Cycle", "predict", "solve_at", "trace_cycle", "wrap_inputs"]
