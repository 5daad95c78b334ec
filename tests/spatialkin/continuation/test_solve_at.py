"""spatialkin.continuation.solve_at, the predict-and-correct driver, on the curve q = a sin(phi) (closed form)."""
import numpy as np
import pytest

from spatialkin.continuation import predict, solve_at, wrap_inputs

A = 0.5
#: Newton at fixed input to round-off; the closed form q = a sin(phi) to this.
TOL = 1e-14


def samples(lo, hi, n=400):
    phi = np.linspace(lo, hi, n)
    return phi, np.column_stack([A * np.sin(phi) + 1e-3 * np.cos(7 * phi), phi])   # a rough prediction


def newton(guess):
    """(states, inputs seen): Newton on q - a sin(phi) = 0 at each fixed phi (q enters linearly: one step)."""
    ys = guess.copy()
    ys[:, 0] -= ys[:, 0] - A * np.sin(ys[:, 1])
    return ys, guess[:, 1].copy()


def test_states_at_the_inputs_in_their_order_wrapped_by_the_period():
    phi, states = samples(0.3, 0.3 + 2 * np.pi)
    inputs = np.array([5.0, -1.0, 0.31, 12.0, 2 * np.pi])
    calls = []

    def corrector(guess):
        calls.append(guess[:, 1].copy())
        return newton(guess)
    ys, _ = solve_at(inputs, phi, states, corrector, index=1, period=2 * np.pi)
    np.testing.assert_array_equal(ys[:, 1], inputs)                 # the input exactly as asked
    np.testing.assert_allclose(ys[:, 0], A * np.sin(inputs), rtol=0, atol=TOL)
    # the corrector got the predictions sorted by the input wrapped into [0.3, 0.3 + 2 pi)
    assert len(calls) == 1 and np.all(np.diff(wrap_inputs(calls[0], 0.3, 2 * np.pi)) > 0)


def test_predictions_linear_and_nearest():
    phi, states = samples(0.0, 1.0, 11)
    linear = predict(np.array([0.05]), phi, states, 1)
    nearest = predict(np.array([0.07]), phi, states, 1, how="nearest")
    np.testing.assert_allclose(linear[0, 0], 0.5 * (states[0, 0] + states[1, 0]), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(nearest[0], [states[1, 0], 0.07])
    with pytest.raises(ValueError, match="how"):
        predict(np.array([0.05]), phi, states, 1, how="cubic")


def test_inputs_beyond_a_branch_that_ends_at_locks_raise_the_systems_error():
    phi, states = samples(-1.0, 1.0)

    class Locked(ValueError):
        pass
    with pytest.raises(Locked):
        solve_at(np.array([0.5, 1.5]), phi, states, newton, index=1, period=2 * np.pi, reach=0.0,
                 outside=lambda mask: Locked(mask))
    with pytest.raises(ValueError, match="outside"):
        solve_at(np.array([0.5]), phi, states, newton, index=1, reach=0.0)
    ys, _ = solve_at(np.array([0.5, -0.9]), phi, states, newton, index=1, period=2 * np.pi, reach=0.0,
                     outside=lambda mask: Locked(mask))
    np.testing.assert_allclose(ys[:, 0], A * np.sin([0.5, -0.9]), rtol=0, atol=TOL)
