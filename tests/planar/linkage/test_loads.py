"""Forces in a planar linkage (LinkageMotion.loads), checked against truths computed apart from the Newton-Euler
system, from the links' motion alone:

- virtual power on the double-crank six-link (two cranks): the sum of each crank's torque times its rate equals
  the rate of change of the kinetic energy (a fourth-order central difference over the input angle) less the
  power of gravity;
- the shaking force on the frame is minus the sum of m (a_G - g), its moment minus the sum of the rates of angular
  momentum (less the weights' moment);
- a parallelogram four-bar whose only mass is its coupler (centre of mass at its middle): the coupler translates,
  the massless rocker is a two-force member, so the pins' forces and the crank torque follow in closed form
  (written out here);
- loads at another input rate scale with its square (without gravity).
"""
import numpy as np
import pytest

import planar
from spatialkin.dynamics import Body

OMEGA = 2.0
MECH = planar.examples.fnf_sixbar()
BODIES = {"1": Body(0.2, (5.0, 1.0, 0.0), np.diag([0.0, 0.0, 30.0])), "2": Body.rod(0.25, 16.0),
          "3": Body.rod(0.4, 137.0), "5": Body.rod(0.3, 107.0),
          "4": Body(0.6, (40.0, 12.0, 0.0), np.diag([0.0, 0.0, 900.0])), "6": Body.rod(0.2, 58.0)}
GRAVITY = (0.0, -9810.0)


def members(linkage):
    out = {c.name: ((c.pivot, c.pin), np.array([[0.0, 0.0], [c.radius, 0.0]])) for c in linkage.cranks}
    out.update({lk.name: (tuple(lk.joints), lk.local()) for lk in linkage.links})
    return out


def centre_motion(sol, name, body):
    """(G (N, 2), v_G (N, 2), omega (N,)) of a link from its first two joints' motion."""
    joints, local = members(sol.linkage)[name]
    p0, p1 = sol.position(joints[0]), sol.position(joints[1])
    d, e = p1 - p0, local[1] - local[0]
    turn = np.arctan2(d[:, 1], d[:, 0]) - np.arctan2(e[1], e[0])
    com = body.com[:2] - local[0]
    r = np.stack([np.cos(turn) * com[0] - np.sin(turn) * com[1], np.sin(turn) * com[0] + np.cos(turn) * com[1]], 1)
    w = sol.angular_velocity(name)
    return p0 + r, sol.velocity(joints[0]) + w[:, None] * np.stack([-r[:, 1], r[:, 0]], 1), w


def kinetic_energy(sol):
    total = 0.0
    for name, body in BODIES.items():
        _, v, w = centre_motion(sol, name, body)
        total = total + 0.5 * body.mass * np.sum(v * v, axis=1) + 0.5 * body.inertia[2, 2] * w ** 2
    return total


def test_virtual_power_of_the_two_cranks():
    angles = np.linspace(0.1, 2 * np.pi - 0.1, 181)
    sol = MECH.solve(angles, omega=OMEGA)
    loads = sol.loads(bodies=BODIES, gravity=GRAVITY)
    h = 1e-3
    t = [kinetic_energy(MECH.solve(angles + k * h, omega=OMEGA)) for k in (-2, -1, 1, 2)]
    dt_dt = OMEGA * (t[0] - 8 * t[1] + 8 * t[2] - t[3]) / (12 * h)
    weight = sum(body.mass * (centre_motion(sol, name, body)[1] @ np.array(GRAVITY)) for name, body in BODIES.items())
    power = sum(loads.torque[c.name] * c.ratio * OMEGA for c in MECH.cranks)
    np.testing.assert_allclose(power, dt_dt - weight, rtol=0, atol=1e-6 * np.max(np.abs(dt_dt - weight)))


def test_shaking_force_and_moment():
    sol = MECH.solve(np.linspace(0.0, 2 * np.pi, 91), omega=OMEGA)
    loads = sol.loads(bodies=BODIES, gravity=GRAVITY)
    force, moment = np.zeros((len(sol), 2)), np.zeros(len(sol))
    h = 1e-4
    for name, body in BODIES.items():
        g, _, _ = centre_motion(sol, name, body)
        joints, _ = members(MECH)[name]
        a_g = (centre_motion(MECH.solve(sol.crank_angles + h, omega=OMEGA), name, body)[1]
               - centre_motion(MECH.solve(sol.crank_angles - h, omega=OMEGA), name, body)[1]) * OMEGA / (2 * h)
        f = body.mass * (a_g - np.array(GRAVITY))
        force += f
        moment += g[:, 0] * f[:, 1] - g[:, 1] * f[:, 0] + body.inertia[2, 2] * sol.angular_acceleration(name)
    np.testing.assert_allclose(loads.shaking_force[:, :2], -force, rtol=0, atol=1e-6 * np.max(np.abs(force)))
    np.testing.assert_allclose(loads.shaking_moment[:, 2], -moment, rtol=0, atol=1e-6 * np.max(np.abs(moment)))


def test_a_parallelogram_four_bar_against_its_closed_form():
    r, length, mass, g = 2.0, 5.0, 0.7, 9810.0
    four = planar.Linkage(fixed={"O": (0.0, 0.0), "P": (length, 0.0)}, cranks=[planar.Crank("1", "O", "A", r)],
                          links=[planar.Link("2", ("A", "B"), length=length), planar.Link("3", ("P", "B"), length=r)],
                          hint={"A": (0.0, r), "B": (length, r)}, hint_angle=np.pi / 2)
    angles = np.linspace(0.3, np.pi - 0.3, 25)
    sol = four.solve(angles, omega=OMEGA)
    np.testing.assert_allclose(sol.position("B") - sol.position("A"), [[length, 0.0]] * len(angles), atol=1e-9)
    loads = sol.loads(bodies={"2": Body.rod(mass, length)}, gravity=(0.0, -g))
    a_g = -OMEGA ** 2 * r * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    # the rocker (massless, no torque) is a two-force member: its pin force on the coupler lies along it, (cos, sin);
    # the coupler translates, so its moment balance about its middle makes both pins' y-forces equal
    f_y = 0.5 * mass * (a_g[:, 1] + g)
    on_b = np.stack([f_y / np.tan(angles), f_y], axis=1)
    on_a = np.stack([mass * a_g[:, 0] - on_b[:, 0], f_y], axis=1)
    scale = np.max(np.abs(on_b))
    np.testing.assert_allclose(loads.member_force["B:2"][:, :2], on_b, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(loads.member_force["A:2"][:, :2], on_a, rtol=0, atol=1e-9 * scale)
    torque = r * (np.cos(angles) * on_a[:, 1] - np.sin(angles) * on_a[:, 0])     # the massless crank: A x F_A
    np.testing.assert_allclose(loads.torque["1"], torque, rtol=0, atol=1e-9 * np.max(np.abs(torque)))


def test_loads_scale_with_the_square_of_the_rate():
    sol = MECH.solve(np.linspace(0.0, 2 * np.pi, 37), omega=OMEGA)
    slow, fast = sol.loads(bodies=BODIES), sol.loads(omega=3 * OMEGA, bodies=BODIES)
    for name in slow.torque:
        np.testing.assert_allclose(fast.torque[name], 9 * slow.torque[name], rtol=1e-12,
                                   atol=1e-12 * np.max(np.abs(fast.torque[name])))


@pytest.mark.parametrize("kwargs, key", [({"bodies": {"7": Body(1.0)}}, "unknown link"),
                                         ({"bodies": {"3": "steel"}}, "Body"),
                                         ({"gravity": (0.0, 0.0, -9810.0)}, "gravity")])
def test_bad_input_is_named(kwargs, key):
    sol = MECH.solve(np.linspace(0.0, 1.0, 3))
    with pytest.raises(ValueError, match=key):
        sol.loads(**kwargs)


def test_the_counterweight_is_the_least_rms_shaking_force():
    """The counterweight's RMS shaking force (the full solve with it on crank 1) is below that of the same mass
    2 % heavier or lighter, or turned 0.05 rad either way (a least-squares optimum), and below the unbalanced one."""
    from spatialkin.dynamics import combined
    sol = MECH.solve(np.linspace(0.0, 2 * np.pi, 181), omega=OMEGA)
    weight = sol.counterweight(10.0, BODIES)

    def rms(mass, angle):
        point = Body.point(mass, (10.0 * np.cos(angle), 10.0 * np.sin(angle), 0.0))
        force = sol.loads(bodies={**BODIES, "1": combined(BODIES["1"], point)}).shaking_force
        return np.sqrt(np.mean(np.sum(force ** 2, axis=1)))

    best = rms(weight.mass, weight.angle)
    assert abs(best - weight.after["rms_force"]) < 1e-9 * best
    assert best < weight.before["rms_force"]
    for mass, angle in ((1.02 * weight.mass, weight.angle), (0.98 * weight.mass, weight.angle),
                        (weight.mass, weight.angle + 0.05), (weight.mass, weight.angle - 0.05)):
        assert rms(mass, angle) > best
