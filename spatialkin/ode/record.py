"""The record of one integration: every step of the method as its dense output's polynomial, in flat arrays.

The compiled methods (spatialkin.ode.solvers.CompiledDOP853, CompiledRK45) write their steps here as the engine
returns them; a solve_ivp method's result is converted once (``Steps.of_solution``). The same arrays are the
stored states, the dense output (``Steps.__call__``, the engine's own evaluator) and the tables of the compiled
distance kernels (spatialkin.tracing.curve.packed).

A step k from t[k] with length h[k] has the state y(t) = y[k] + h[k] (q[k, :, 0] x + q[k, :, 1] x^2 + ...),
x = (t - t[k]) / h[k]: scipy's RkDenseOutput form (RK23's and RK45's Q as they are; DOP853's F rows turned into
powers of x by the engine's integer matrix, spatialkin.kernels.ode.rk.DOP853_POWERS).

References
----------
scipy.integrate.OdeSolution (the interface: a state, or states (n, M), at times t), RK23, RK45 and DOP853 (their
dense outputs).
"""
import numpy as np

from ..kernels.ode import rk

#: solve_ivp's methods whose steps' dense output is y_old + h Q (x, x^2, ...) (scipy's RkDenseOutput): taken as it is.
POWER_FORM = ("RK23", "RK45")


class Steps:
    """The steps of one integration (see the module docstring).

    Attributes
    ----------
    t : ndarray (m,)
        Step ends, ascending from the start.
    y : ndarray (m, n)
        States at t.
    h : ndarray (m - 1,)
        Step lengths: t[k + 1] - t[k], except that the last step's polynomial may reach past a terminal event at
        t[-1] (its whole step's length).
    q : ndarray (m - 1, n, c)
        The steps' polynomial coefficients.
    sol : OdeSolution or None
        For a solve_ivp method whose dense output is no such polynomial (Radau, BDF, LSODA): its own dense output,
        which then evaluates the record (and the compiled tables do not hold it); None otherwise.
    events : list
        The events a compiled method located, in time order: (position in its watched events, t, y (n,)).
    budget_exceeded : bool
        A compiled method stopped because its evaluation budget ran out.
    """

    __slots__ = ("t", "y", "h", "q", "sol", "events", "budget_exceeded", "_chunks")

    def __init__(self, t=None, y=None, h=None, q=None, sol=None):
        self.t, self.y, self.h, self.q, self.sol = t, y, h, q, sol
        self.events = []
        self.budget_exceeded = False
        self._chunks = []

    # --- written by the compiled methods, step call by step call --------------------------------------------------
    def add(self, ts, ys, hs, qs):
        """Append one call of the engine: its steps' ends ts (k + 1,) from the last end, states ys, lengths hs and
        polynomials qs (at least k rows each; rows past them are the engine's work space). A call without a step
        (or ending where the last one ended) adds nothing."""
        k = len(ts) - 1
        if k < 1 or (self._chunks and self._chunks[-1][0][-1] == ts[-1]):
            return
        self._chunks.append((ts, ys[:k + 1], hs[:k], qs[:k]))

    def close(self, t0, y0):
        """Join the chunks into the arrays (once; the record of an integration without a step holds its start
        t0, y0 alone). Returns self."""
        chunks = self._chunks
        if not chunks:
            self.t, self.y = np.array([float(t0)]), np.asarray(y0, dtype=float).reshape(1, -1).copy()
            self.h, self.q = np.empty(0), np.empty((0, self.y.shape[1], 1))
        elif len(chunks) == 1:
            self.t, self.y, self.h, self.q = chunks[0]
        else:
            self.t = np.concatenate([chunks[0][0]] + [c[0][1:] for c in chunks[1:]])
            self.y = np.concatenate([chunks[0][1]] + [c[1][1:] for c in chunks[1:]])
            self.h = np.concatenate([c[2] for c in chunks])
            self.q = np.concatenate([c[3] for c in chunks])
        self._chunks = []
        return self

    # --- a solve_ivp method's result, converted once -------------------------------------------------------------
    @classmethod
    def of_solution(cls, res, method):
        """The record of solve_ivp's result res (dense_output=True) by `method` (a name or an OdeSolver class): its
        steps res.t, res.y, and each step's polynomial from its dense output (RK23's and RK45's Q, DOP853's F); for
        another method (no such polynomial) its OdeSolution kept as ``sol``."""
        t, y = np.asarray(res.t, dtype=float), np.ascontiguousarray(np.asarray(res.y, dtype=float).T)
        dense = list(res.sol.interpolants) if res.sol is not None and len(t) > 1 else []
        name = getattr(method, "__name__", method)
        if dense and name in POWER_FORM and all(hasattr(d, "Q") for d in dense):
            q = np.stack([d.Q for d in dense])
        elif dense and name == "DOP853" and all(d.F.shape[0] == rk.DENSE_COLUMNS[rk.DOP853] for d in dense):
            q = np.stack([(rk.DOP853_POWERS @ d.F).T / d.h for d in dense])
        else:
            return cls(t, y, np.diff(t), np.empty((max(len(t) - 1, 0), y.shape[1], 1)), sol=res.sol)
        h = np.array([d.h for d in dense], dtype=float)
        return cls(t, y, h, np.ascontiguousarray(q, dtype=float))

    # --- the dense output ------------------------------------------------------------------------------------------
    @property
    def compiled(self):
        """True when the arrays hold the dense output (every step a polynomial): the compiled kernels can read it."""
        return self.sol is None

    def __call__(self, t):
        """The state (n,) at a time t, or the states (n, M) at times t (M,) (scipy's OdeSolution's shapes); outside
        [t[0], t[-1]] the first or last step's polynomial is extended."""
        if self.sol is not None:
            return self.sol(t)
        if np.ndim(t) == 0:
            return rk.dense_at(self.t, self.y, self.h, self.q, float(t))
        tt = np.ascontiguousarray(np.ravel(t), dtype=float)
        out = np.empty((tt.size, self.y.shape[1]))
        rk.dense_many(self.t, self.y, self.h, self.q, tt, out)
        return out.T
