"""Forces in a planar linkage over its motion: the driving torque of each crank, every pin's load on every link it
holds, and the shaking force and moment on the frame, by Newton-Euler in the plane (three equations per moving
link, the pins' forces and the cranks' torques solved as one linear system per input angle, vectorised).

A link's own frame: the first of its joints at the origin of its ``shape`` coordinates (a binary link: (0, 0) and
(length, 0); a crank: the pivot at (0, 0), the pin at (radius, 0)). Its Body (spatialkin.dynamics.Body) gives the
centre of mass in those coordinates (x, y; z ignored) and the moment of inertia about the centre of mass normal
to the plane (inertia[2, 2]). A pin joining k members (the frame counted where the joint is fixed) carries 2 (k - 1)
unknowns: the force on each member but one (the frame, else the first); each crank's torque acts between it and the
frame at its pivot.

Units: kg, the linkage's length unit L and s with the input rate omega in rad/s: forces in kg L / s^2, torques and
moments in kg L^2 / s^2.

References
----------
R. L. Norton, Design of Machinery, 5th ed., ch. 11 (the dynamic force analysis of linkages by a matrix of
Newton-Euler equations, shaking force and moment).
"""
import numpy as np

from spatialkin._lib.validation import as_float_array, check_omega
from spatialkin.dynamics import Loads
from spatialkin.dynamics.balance import counterweight
from spatialkin.dynamics.body import check_bodies

from .motion import _cross


def _members(linkage):
    """[(name, joints, local (k, 2), is a crank)] of the moving links: the cranks, then the links."""
    out = [(c.name, (c.pivot, c.pin), np.array([[0.0, 0.0], [float(c.radius), 0.0]]), True) for c in linkage.cranks]
    out += [(lk.name, tuple(lk.joints), lk.local(), False) for lk in linkage.links]
    return out


def _check(linkage, bodies, gravity):
    bodies = check_bodies(bodies, [m[0] for m in _members(linkage)])
    g = np.zeros(2)
    if gravity is not None:
        g = as_float_array("gravity", gravity)
        if g.shape != (2,) or not np.all(np.isfinite(g)):
            raise ValueError(f"gravity must be 2 finite numbers (L / s^2, fixed axes), got {np.ravel(g).tolist()}")
    for crank in linkage.cranks:
        if crank.pivot not in linkage.fixed:
            raise ValueError(f"crank {crank.name!r}: its pivot {crank.pivot!r} is not a fixed joint (its torque's "
                             "reaction has no frame to act on)")
    return bodies, g


def linkage_loads(motion, bodies=None, gravity=None, omega=None):
    """The loads of a LinkageMotion (see LinkageMotion.loads)."""
    linkage = motion.linkage
    bodies, g = _check(linkage, bodies, gravity)
    scale = 1.0 if omega is None else check_omega(omega) / motion.omega
    members = _members(linkage)
    n = len(motion)
    index = {m[0]: k for k, m in enumerate(members)}
    centres, turns, rows_b = {}, {}, np.zeros((n, 3 * len(members)))
    for k, (name, joints, local, _) in enumerate(members):
        body = bodies.get(name)
        p0, p1 = motion.position(joints[0]), motion.position(joints[1])
        d = p1 - p0
        turn = np.arctan2(d[:, 1], d[:, 0]) - np.arctan2(*(local[1] - local[0])[::-1])
        c, s = turns[name] = np.cos(turn), np.sin(turn)        # the link frame's axes: (c, s) and (-s, c)
        com = np.zeros(2) if body is None else body.com[:2] - local[0]
        r = np.stack([c * com[0] - s * com[1], s * com[0] + c * com[1]], axis=1)
        centres[name] = p0 + r
        w = motion.angular_velocity(name) * scale
        al = motion.angular_acceleration(name) * scale ** 2
        acc = motion.acceleration(joints[0]) * scale ** 2 + al[:, None] * np.stack([-r[:, 1], r[:, 0]], axis=1) \
            - (w ** 2)[:, None] * r
        mass = 0.0 if body is None else body.mass
        inertia = 0.0 if body is None else float(body.inertia[2, 2])
        rows_b[:, 3 * k:3 * k + 2] = mass * (acc - g)
        rows_b[:, 3 * k + 2] = inertia * al
    # the pins: every member but the reference (the frame where the joint is fixed, else the first member)
    pins = []
    for joint in linkage.joints:
        held = [m[0] for m in members if joint in m[1]]
        reference = None if joint in linkage.fixed else (held[0] if held else None)
        pins.append((joint, reference, [name for name in held if name != reference]))
    unknowns = 2 * sum(len(others) for _, _, others in pins) + len(linkage.cranks)
    if unknowns != 3 * len(members):
        raise ValueError(f"the pins and cranks carry {unknowns} unknowns for {3 * len(members)} equations")
    a = np.zeros((n, unknowns, unknowns))
    col, columns = 0, {}
    for joint, reference, others in pins:
        point = motion.position(joint)
        for name in others:
            columns[joint, name] = col
            for member, sign in ((name, 1.0), (reference, -1.0)):
                if member is None:
                    continue
                row = 3 * index[member]
                lever = point - centres[member]
                a[:, row, col] += sign
                a[:, row + 1, col + 1] += sign
                a[:, row + 2, col] += -sign * lever[:, 1]
                a[:, row + 2, col + 1] += sign * lever[:, 0]
            col += 2
    for crank in linkage.cranks:
        columns[crank.name] = col
        a[:, 3 * index[crank.name] + 2, col] = 1.0
        col += 1
    try:
        x = np.linalg.solve(a, rows_b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        raise ValueError("the loads are not determined at some input angles (a dead or change point)") from None
    member_force, frame_force = {}, np.zeros((n, 2))
    shaking_moment = np.zeros(n)
    for joint, reference, others in pins:
        point = motion.position(joint)
        total = np.zeros((n, 2))
        for name in others:
            f = x[:, columns[joint, name]:columns[joint, name] + 2]
            member_force[joint, name] = f
            total += f
        if reference is None:           # the frame holds the pin: it takes minus the members' forces
            frame_force -= total
            shaking_moment -= _cross(point, total)
        else:
            member_force[joint, reference] = -total
    torque = {crank.name: x[:, columns[crank.name]] for crank in linkage.cranks}
    shaking_moment -= sum(torque.values())
    flat = {f"{joint}:{name}": np.column_stack([f, np.zeros(n)]) for (joint, name), f in member_force.items()}
    local = {}
    for key, f in flat.items():
        c, s = turns[key.split(":", 1)[1]]
        local[key] = np.column_stack([c * f[:, 0] + s * f[:, 1], -s * f[:, 0] + c * f[:, 1], np.zeros(n)])
    last = {joint: f"{joint}:{others[-1]}" for joint, _, others in pins if others}
    zeros = np.zeros((n, 3))
    zeros_by_joint = {j: zeros for j in last}               # (a pin carries no moment in the plane)
    loads = Loads({j: flat[k] for j, k in last.items()}, zeros_by_joint, {j: local[k] for j, k in last.items()},
                  zeros_by_joint, torque, np.column_stack([frame_force, np.zeros(n)]),
                  np.column_stack([np.zeros((n, 2)), shaking_moment]))
    loads.member_force, loads.member_force_local = flat, local
    return loads


def linkage_counterweight(motion, radius, bodies=None, crank=1, omega=None):
    """The counterweight on a crank of least RMS shaking force (see LinkageMotion.counterweight)."""
    linkage = motion.linkage
    if not (isinstance(crank, (int, np.integer)) and 1 <= crank <= len(linkage.cranks)):
        raise ValueError(f"crank must be 1..{len(linkage.cranks)}, got {crank!r}")
    chosen = linkage.cranks[crank - 1]
    d = motion.position(chosen.pin) - motion.position(chosen.pivot)
    x = d / np.linalg.norm(d, axis=1)[:, None]
    axes = np.stack([x, np.stack([-x[:, 1], x[:, 0]], axis=1)], axis=2)
    rate = chosen.ratio * (motion.omega if omega is None else check_omega(omega))
    return counterweight(lambda given: linkage_loads(motion, given, None, omega), bodies, chosen.name, axes, rate,
                         radius, lambda loads: loads.torque[chosen.name])
