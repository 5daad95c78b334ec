"""RSSR through the tracing/trajectory pipeline against its closed form A cos psi + B sin psi + C = 0."""
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.mechanisms.rssr import RSSR


def closed_form(m, phi, branch):
    rot2, o2 = m.rocker_frame.rotation, m.rocker_frame.origin
    b = m.crank_frame.origin + m.crank_radius * np.stack([np.cos(phi), np.sin(phi), 0 * phi], -1) @ m.crank_frame.rotation.T
    d = o2 - b
    a_ = 2 * m.rocker_radius * d @ rot2[:, 0]
    b_ = 2 * m.rocker_radius * d @ rot2[:, 1]
    c0 = np.einsum("ij,ij->i", d, d) + m.rocker_radius ** 2 - m.coupler_length ** 2
    psi = np.arctan2(b_, a_) + (-1 if branch == 0 else 1) * np.arccos(-c0 / np.hypot(a_, b_))
    c = o2 + m.rocker_radius * np.stack([np.cos(psi), np.sin(psi), 0 * psi], -1) @ rot2.T
    return psi, c


def five_point(f, x, h):
    fm2, fm1, f0, fp1, fp2 = f(x - 2 * h), f(x - h), f(x), f(x + h), f(x + 2 * h)
    return (fm2 - 8 * fm1 + 8 * fp1 - fp2) / (12 * h), (-fm2 + 16 * fm1 - 30 * f0 + 16 * fp1 - fp2) / (12 * h * h)


@pytest.fixture(scope="module")
def mech():
    return RSSR(10.0, 60.0, 30.0, sk.Frame(), sk.Frame((20.0, 40.0, 30.0), sk.rotation_about((1, 0, 0), 1.2)))


@pytest.mark.parametrize("branch", [0, 1])
def test_rssr_matches_closed_form(mech, branch):
    """Positions to 1e-9, velocities and accelerations to 1e-8 relative (5-point differences, h = 3e-3)."""
    omega = 2.5
    phi = np.linspace(0, 2 * np.pi, 361)
    m = mech.solve(phi, omega=omega, branch=branch)
    psi, c = closed_form(mech, phi, branch)
    assert np.max(np.abs(np.angle(np.exp(1j * (m.rocker_angle - psi))))) < 1e-11
    assert np.max(np.abs(m.ball_center.position - c)) < 1e-9
    np.testing.assert_allclose(np.linalg.norm(m.ball_center.position - m.crank_pin.position, axis=1), 60.0, atol=1e-11)
    d1, d2 = five_point(lambda x: closed_form(mech, x, branch)[1], phi, 3e-3)
    v, a = omega * d1, omega ** 2 * d2
    assert np.max(np.abs(m.ball_center.velocity - v)) < 1e-8 * np.abs(v).max()
    assert np.max(np.abs(m.ball_center.acceleration - a)) < 1e-8 * np.abs(a).max()
    # the crank pin turns uniformly: |v_B| = omega a, |a_B| = omega^2 a
    np.testing.assert_allclose(np.linalg.norm(m.crank_pin.velocity, axis=1), omega * 10.0, rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(m.crank_pin.acceleration, axis=1), omega ** 2 * 10.0, rtol=1e-13)


def test_rssr_that_cannot_be_assembled_or_turn_fully():
    """Coupler too long to assemble at crank angle 0; then a coupler too short to follow the crank all round:
    the dead position where the farthest point of the rocker circle is L away,
    sqrt((rho - c)^2 + h^2) = L with rho^2 = (55 - 30 cos phi)^2 + (30 sin phi)^2, h = 5, c = 15, L = 35."""
    with pytest.raises(ValueError, match="cannot be assembled on branch 0 at crank angle 0"):
        RSSR(30.0, 45.0, 15.0, sk.Frame(), sk.Frame((55.0, 0.0, 5.0))).solve([0.0])
    m = RSSR(30.0, 35.0, 15.0, sk.Frame(), sk.Frame((55.0, 0.0, 5.0)))
    rho = 15.0 + np.sqrt(35.0 ** 2 - 25.0)
    dead = np.degrees(np.arccos((55.0 ** 2 + 30.0 ** 2 - rho ** 2) / (2 * 55.0 * 30.0)))
    with pytest.raises(ValueError, match="cannot turn fully: dead position at crank angle") as info:
        m.solve(np.linspace(0, 2 * np.pi, 10))
    assert abs(float(str(info.value).split("crank angle ")[1].split(" deg")[0]) - dead) < 1e-3
