"""A jump's arc length (spatialkin.tracing.march.singular.JumpArc) against closed forms."""
import numpy as np
import pytest

from spatialkin.tracing.march.singular import _ARC_X, ARC_NODES, JumpArc


def test_jump_arc_integrates_and_inverts_a_smooth_speed():
    """Speeds 1 + c tau^2 on two sides of lengths 0.3 and 0.2: the arc length is tau + c tau^3 / 3 on each side
    (exact for the Legendre series through ARC_NODES nodes), chord_position inverts it and arc_position maps back,
    to 1e-14."""
    lengths, c = (0.3, 0.2), (0.5, 2.0)
    speeds = [1.0 + ck * (0.5 * length * (1.0 + _ARC_X)) ** 2 for length, ck in zip(lengths, c)]
    arc = JumpArc(lengths, speeds)
    sides = [length + ck * length ** 3 / 3.0 for length, ck in zip(lengths, c)]
    assert arc.length == pytest.approx(sum(sides), abs=1e-15)
    tau = np.concatenate([np.linspace(0.0, lengths[0], 7), lengths[0] + np.linspace(0.0, lengths[1], 7)[1:]])
    exact = np.where(tau <= lengths[0], tau + c[0] * tau ** 3 / 3.0,
                     sides[0] + (tau - lengths[0]) + c[1] * (tau - lengths[0]) ** 3 / 3.0)
    assert np.max(np.abs(arc.chord_position(exact) - tau)) < 1e-14
    assert max(abs(arc.arc_position(float(d)) - e) for d, e in zip(tau, exact)) < 1e-14
    assert len(speeds[0]) == ARC_NODES
