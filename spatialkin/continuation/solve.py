"""Solve a mechanism at given inputs: predict from the traced curve, correct at each fixed input.

Every mechanism of the library answers "the configuration at these input angles" the same way: the
configuration curve is traced once (trace_cycle, or sk.intersect for the looper), samples of the branch on
which the input is monotonic give each requested input a prediction, and the system's own Newton at fixed
input (a kernel, which may also return derivatives) makes it exact. ``solve_at`` is that driver; the
system supplies only the samples and the corrector.
"""
import numpy as np

#: How a prediction is read from the samples: linear interpolation in the input, or the nearest sample (for
#: states holding angles that wrap by 2 pi between samples).
PREDICTIONS = ("linear", "nearest")


def wrap_inputs(inputs, start, period):
    """The inputs moved by whole periods into [start, start + period)."""
    return start + np.mod(np.asarray(inputs, dtype=float) - start, period)


def predict(local, sample_inputs, sample_states, index, how="linear"):
    """States (m, n) predicted at inputs `local` (m,) from samples (k,), (k, n) sorted by input; column index is
    set to the input itself."""
    if how not in PREDICTIONS:
        raise ValueError(f"how must be one of {PREDICTIONS}, got {how!r}")
    if how == "nearest":
        idx = np.searchsorted(sample_inputs, local)
        lo = np.clip(idx - 1, 0, len(sample_inputs) - 1)
        hi = np.clip(idx, 0, len(sample_inputs) - 1)
        near = np.where(np.abs(sample_inputs[lo] - local) <= np.abs(sample_inputs[hi] - local), lo, hi)
        guess = np.array(sample_states[near], dtype=float)
    else:
        guess = np.column_stack([np.interp(local, sample_inputs, sample_states[:, i])
                                 for i in range(sample_states.shape[1])])
    guess[:, index] = local
    return guess


def solve_at(inputs, sample_inputs, sample_states, correct, index=-1, period=None, start=None, reach=None,
             how="linear", outside=None, wrapped=False):
    """Exact states at the given inputs.

    Parameters
    ----------
    inputs : ndarray (m,)
        The requested inputs (finite).
    sample_inputs, sample_states : ndarray (k,), (k, n)
        Samples of the branch, sorted by input (the input is monotonic along it), e.g. Cycle.branch_samples().
    correct : callable
        ``correct(guess (m, n))`` -> tuple of arrays, each (m, ...): the system's Newton at fixed input, given
        the predictions sorted by input (so that each may start from the one solved before it), their input
        column the requested input itself.
    index : int
        Column of the input in the states.
    period : float, optional
        The input's period: inputs are first moved by whole periods into [start, start + period) ...
    start : float, optional
        ... (default sample_inputs[0]).
    reach : float, optional
        Where the branch does not cover a period (it ends at lock positions): inputs farther than this past the
        last sample are outside it ...
    outside : callable, optional
        ... and ``outside(mask)`` gives the exception raised for them (mask over the requested inputs).
    how : str
        'linear' or 'nearest' (PREDICTIONS).
    wrapped : bool
        The predictions' input column holds the wrapped input (for a corrector that compares the inputs of
        neighbours), not the requested one.

    Returns
    -------
    tuple
        correct's arrays, in the order of the inputs.
    """
    inputs = np.asarray(inputs, dtype=float)
    if reach is not None and outside is None:
        raise ValueError("reach needs outside (the exception raised for inputs beyond it)")
    start = sample_inputs[0] if start is None else start
    local = inputs if period is None else wrap_inputs(inputs, start, period)
    if reach is not None:
        beyond = local > sample_inputs[-1] + reach
        if beyond.any():
            raise outside(beyond)
    guess = predict(local, sample_inputs, sample_states, index, how)
    if not wrapped:
        guess[:, index] = inputs        # the input exactly as asked (the system is periodic in it)
    order = np.argsort(local, kind="stable")
    back = np.empty_like(order)
    back[order] = np.arange(len(order))
    return tuple(np.asarray(x)[back] for x in correct(np.ascontiguousarray(guess[order])))
