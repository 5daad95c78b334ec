"""Forces in the looper drive (LooperMotion.loads), checked against truths computed apart from the Newton-Euler
system, from the links' motion alone:

- virtual power: the crank torque times the crank rate equals the rate of change of the kinetic energy (here by a
  fourth-order central difference of T over the crank angle) less the power of gravity and of the external load;
- energy over a full turn at constant speed: the mean driving power is zero without gravity or external loads;
- the shaking force (on the frame) is minus the sum of m a over the links, the shaking moment minus the sum of their
  rates of change of angular momentum about the origin;
- quasi-static under gravity: at a crank rate of 1e-4 rad/s the torque is the virtual work of the weights,
  -sum m g . dG/du1 (dG/du1 by a central difference of the centres of mass).
"""
import numpy as np
import pytest

from spatialkin.dynamics import Body
from spatialkin.mechanisms import LooperDrive

#: The drive at 2000 rpm, and plausible steel links for the check (not data of the papers).
OMEGA = 2000 * np.pi / 30
DRIVE = LooperDrive.reference()
BODIES = {"crank": Body(0.08, (4.0, 0.0, 0.0), np.diag([20.0, 40.0, 40.0])),
          "coupler": Body.rod(0.05, DRIVE.coupler_length),
          "rocker_shaft": Body.disc(0.1, 5.0, axis=(0.0, 0.0, 1.0), centre=(0.0, 0.0, -3.0)),
          "rocker_arm": Body(0.04, (12.0, 1.0, 0.5), [[5.0, 0.3, 0.0], [0.3, 6.0, 0.1], [0.0, 0.1, 4.0]])}
#: Gravity in mm / s^2, fixed axes (z up).
GRAVITY = (0.0, 0.0, -9810.0)


def kinetic_energy(motion):
    """T (N,) of the links, from their motion: 1/2 m |v_G|^2 + 1/2 omega . I_G omega."""
    total = np.zeros(len(motion))
    for name, state in motion.links().items():
        body = BODIES[name]
        _, v, _ = state.point(body.com)
        inertia = state.rotation @ body.inertia @ np.swapaxes(state.rotation, 1, 2)
        total += 0.5 * body.mass * np.sum(v * v, axis=1)
        total += 0.5 * np.einsum("ni,nij,nj->n", state.omega, inertia, state.omega)
    return total


def centres(motion):
    return {name: state.point(BODIES[name].com)[0] for name, state in motion.links().items()}


def test_virtual_power_and_the_turns_mean_power():
    angles = np.linspace(0.0, 2 * np.pi, 721)
    motion = DRIVE.solve(angles, omega=OMEGA)
    loads = motion.loads(BODIES, gravity=GRAVITY)
    h = 1e-3
    t = [kinetic_energy(DRIVE.solve(angles + k * h, omega=OMEGA)) for k in (-2, -1, 1, 2)]
    dt_du = (t[0] - 8 * t[1] + 8 * t[2] - t[3]) / (12 * h)
    weight_power = sum(BODIES[name].mass * (state.point(BODIES[name].com)[1] @ np.array(GRAVITY))
                       for name, state in motion.links().items())
    power = loads.crank_torque * OMEGA
    np.testing.assert_allclose(power, OMEGA * dt_du - weight_power, rtol=0, atol=1e-6 * np.max(np.abs(power)))
    free = motion.loads(BODIES)
    mean = np.trapezoid(free.crank_torque * OMEGA, angles) / (2 * np.pi)
    assert abs(mean) < 1e-10 * np.max(np.abs(free.crank_torque * OMEGA))


def test_shaking_force_and_moment_are_the_links_rates_of_momentum():
    motion = DRIVE.solve(np.linspace(0.0, 2 * np.pi, 181), omega=OMEGA)
    loads = motion.loads(BODIES)
    force, moment = np.zeros((len(motion), 3)), np.zeros((len(motion), 3))
    for name, state in motion.links().items():
        body = BODIES[name]
        g, _, a = state.point(body.com)
        inertia = state.rotation @ body.inertia @ np.swapaxes(state.rotation, 1, 2)
        force += body.mass * a
        moment += (np.cross(g, body.mass * a) + np.einsum("nij,nj->ni", inertia, state.alpha)
                   + np.cross(state.omega, np.einsum("nij,nj->ni", inertia, state.omega)))
    scale = np.max(np.abs(force))
    np.testing.assert_allclose(loads.shaking_force, -force, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(loads.shaking_moment, -moment, rtol=0, atol=1e-10 * np.max(np.abs(moment)))


def test_quasi_static_torque_is_the_virtual_work_of_the_weights():
    angles = np.linspace(0.0, 2 * np.pi, 73)
    slow = 1e-4
    loads = DRIVE.loads(angles, slow, BODIES, gravity=GRAVITY)
    h = 1e-5
    ahead, behind = centres(DRIVE.solve(angles + h)), centres(DRIVE.solve(angles - h))
    virtual = -sum(BODIES[name].mass * ((ahead[name] - behind[name]) / (2 * h)) @ np.array(GRAVITY)
                   for name in BODIES)
    np.testing.assert_allclose(loads.crank_torque, virtual, rtol=0, atol=1e-6 * np.max(np.abs(virtual)))


def test_an_external_load_at_the_tip_does_its_work():
    """A thread load F(u1) at the looper tip and a moment on the looper link: the crank's power balances their
    power (at a tiny crank rate, massless links: tau omega + F . v_tip + M . omega_link = 0)."""
    angles = np.linspace(0.0, 2 * np.pi, 37)
    slow = 1e-4

    def thread(u1):
        return (np.stack([np.cos(u1), np.sin(u1), 0.5 + 0 * u1], axis=1) * 100.0,
                np.stack([0 * u1, 0 * u1, 50.0 + 0 * u1], axis=1))
    motion = DRIVE.solve(angles, omega=slow)
    loads = motion.loads(external=thread)
    force, moment = thread(angles)
    tip = motion.looper_tip.velocity
    spin = motion.links()[DRIVE.looper_link].omega
    balance = loads.crank_torque * slow + np.sum(force * tip, axis=1) + np.sum(moment * spin, axis=1)
    assert np.max(np.abs(balance)) < 1e-9 * np.max(np.abs(loads.crank_torque * slow))


def test_joint_forces_in_the_links_axes_and_action_reaction():
    motion = DRIVE.solve(np.linspace(0.0, 2 * np.pi, 91), omega=OMEGA)
    loads = motion.loads(BODIES, gravity=GRAVITY)
    arm = motion.links()["rocker_arm"]
    np.testing.assert_allclose(np.einsum("nij,nj->ni", arm.rotation, loads.joint_force_local["ball"]),
                               loads.joint_force["ball"], rtol=0, atol=1e-9 * np.max(np.abs(loads.joint_force["ball"])))
    assert not np.any(loads.joint_moment["ball"])            # a ball joint carries no moment
    axis = motion.links()["coupler"].rotation[:, :, 1]
    assert np.max(np.abs(np.sum(loads.joint_moment["crank_pin"] * axis, axis=1))) < 1e-9 * np.max(
        np.abs(loads.joint_moment["crank_pin"]))              # nor a revolute one about its axis


@pytest.mark.parametrize("kwargs, key", [({"bodies": {"looper": Body(1.0)}}, "unknown link"),
                                         ({"bodies": {"crank": 1.0}}, "Body"),
                                         ({"bodies": [Body(1.0)]}, "dict"),
                                         ({"gravity": (0.0, -9810.0)}, "gravity"),
                                         ({"external": 3.0}, "external")])
def test_bad_input_is_named(kwargs, key):
    motion = DRIVE.solve(np.linspace(0.0, 1.0, 3))
    with pytest.raises(ValueError, match=key):
        motion.loads(**kwargs)
    with pytest.raises(TypeError, match="gravity must be an array of real numbers"):
        motion.loads(gravity="down")


def test_the_crank_counterweight_is_the_least_rms_shaking_force():
    """The counterweight's RMS shaking force (the full solve with it on the crank) is below that of the same mass
    2 % heavier or lighter, or turned 0.05 rad either way, and below the unbalanced one."""
    from spatialkin.dynamics import combined
    motion = DRIVE.solve(np.linspace(0.0, 2 * np.pi, 181), omega=OMEGA)
    weight = motion.counterweight(10.0, BODIES)

    def rms(mass, angle):
        point = Body.point(mass, (10.0 * np.cos(angle), 10.0 * np.sin(angle), 0.0))
        force = motion.loads({**BODIES, "crank": combined(BODIES["crank"], point)}).shaking_force
        return np.sqrt(np.mean(np.sum(force ** 2, axis=1)))

    best = rms(weight.mass, weight.angle)
    assert abs(best - weight.after["rms_force"]) < 1e-9 * best and best < weight.before["rms_force"]
    for mass, angle in ((1.02 * weight.mass, weight.angle), (0.98 * weight.mass, weight.angle),
                        (weight.mass, weight.angle + 0.05), (weight.mass, weight.angle - 0.05)):
        assert rms(mass, angle) > best


def test_joint_moments_in_the_links_axes():
    """A revolute joint's moment in its child link's axes has no component along the joint's own axis there (the
    crank pin's local -y, the rocker bearing's local z), except the driven crank bearing's: the crank torque."""
    motion = DRIVE.solve(np.linspace(0.0, 2 * np.pi, 61), omega=OMEGA)
    loads = motion.loads(BODIES, gravity=GRAVITY)
    pin, bearing = loads.joint_moment_local["crank_pin"], loads.joint_moment_local["rocker_bearing"]
    assert np.max(np.abs(pin[:, 1])) < 1e-9 * np.max(np.abs(pin))
    assert np.max(np.abs(bearing[:, 2])) < 1e-9 * np.max(np.abs(bearing))
    np.testing.assert_allclose(loads.joint_moment_local["crank_bearing"][:, 2], loads.crank_torque, rtol=0,
                               atol=1e-12 * np.max(np.abs(loads.crank_torque)))
