"""The compiled solve_ivp methods: ``scipy.integrate.solve_ivp(..., method=CompiledDOP853)`` (or CompiledRK45) runs
many steps of the compiled Runge–Kutta engine (spatialkin.kernels.ode.rk) per solver step and stops at the events
it watches, writing its steps into a record (Steps: the stored states, the dense output and the compiled kernels'
tables in one). Used by the tracer (spatialkin.tracing.march) and by continuation (spatialkin.continuation)."""
from .record import Steps
from .solvers import (COMPILED, COMPILED_RK45, COMPILED_SOLVERS, BudgetExceeded, CompiledDOP853, CompiledRK45, Event,
                      System, Watch, integrate)

__all__ = ["COMPILED", "COMPILED_RK45", "COMPILED_SOLVERS", "BudgetExceeded", "CompiledDOP853", "CompiledRK45", "Event",
           "Steps", "System", "Watch", "integrate"]
