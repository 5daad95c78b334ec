"""Inverse dynamics of a mechanism whose motion is known: Newton-Euler per link, the joints' constraint forces and
the driving torques solved as one linear system per instant (vectorised over the instants).

Each moving link k with mass m, centre of mass G and inertia I_G (fixed axes) obeys

    sum of the joint forces on it + m g + F_ext = m a_G,
    sum of the joint moments and of (P - G) x F over its joints + M_ext + (P_ext - G) x F_ext = I_G alpha + omega x I_G omega.

A joint acts on its child link with a force F (3 unknowns) and a moment M, and on its parent with -F, -M (the
frame when the parent is None): a revolute joint's M is normal to its axis (2 unknowns), a driven revolute's M
also has the driving torque along the axis (3 unknowns), a spherical joint carries no moment. The system is square
for a mechanism of one degree of freedom per driving joint (6 equations per link).

Units follow the inputs: masses in kg and lengths in the mechanism's unit L, time in s: forces in kg L / s^2 (mN
for L = mm), moments and torques in kg L^2 / s^2 (uN m for L = mm).

References
----------
J. J. Craig, Introduction to Robotics: Mechanics and Control, 3rd ed., ch. 6 (Newton-Euler); R. L. Norton,
Design of Machinery, 5th ed., ch. 11 (the dynamic force analysis of linkages, shaking force and moment).
"""
from dataclasses import dataclass

import numpy as np

#: Joint kinds and the moment unknowns each carries.
REVOLUTE, DRIVEN, SPHERICAL = "revolute", "driven", "spherical"
MOMENT_UNKNOWNS = {REVOLUTE: 2, DRIVEN: 3, SPHERICAL: 0}


@dataclass(frozen=True)
class Joint:
    """A joint: its name, the links it connects (parent None: the frame), its kind, and where it is at each
    instant: its point (N, 3) and, for a revolute, its unit axis (N, 3), in fixed axes."""
    name: str
    parent: object
    child: str
    kind: str
    point: np.ndarray
    axis: np.ndarray = None


class Loads:
    """The loads of a mechanism over its instants (fixed axes; units: see spatialkin.dynamics.newton_euler).

    Attributes
    ----------
    joint_force, joint_moment : dict of ndarray (N, 3)
        Per joint: the force and moment it applies to its child link (its parent, or the frame, takes the
        opposite), in fixed axes. A driven joint's moment includes its driving torque.
    joint_force_local : dict of ndarray (N, 3)
        The same forces in the child link's own axes.
    torque : dict of ndarray (N,)
        Per driven joint: the driving torque about its axis.
    shaking_force, shaking_moment : ndarray (N, 3)
        The force, and the moment about the origin of the fixed axes, that the mechanism applies to the frame
        through its bearings (the driving motors' reactions included).
    """

    def __init__(self, joint_force, joint_moment, joint_force_local, torque, shaking_force, shaking_moment):
        self.joint_force, self.joint_moment, self.joint_force_local = joint_force, joint_moment, joint_force_local
        self.torque = torque
        self.shaking_force, self.shaking_moment = shaking_force, shaking_moment

    def __repr__(self):
        return (f"Loads({len(self.shaking_force)} instants; joints {list(self.joint_force)}; peak |F| "
                + ", ".join(f"{k} {np.max(np.linalg.norm(v, axis=1)):.4g}" for k, v in self.joint_force.items())
                + ")")


def skew(v):
    """Cross-product matrices (N, 3, 3) of vectors (N, 3): skew(v) @ x = v x x."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def normal_basis(axis):
    """Two unit vectors (N, 3, 2) spanning the plane normal to each unit axis (N, 3)."""
    helper = np.where(np.abs(axis[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    e1 = np.cross(axis, helper)
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    return np.stack([e1, np.cross(axis, e1)], axis=2)


def inverse_dynamics(links, joints, bodies, gravity=None, external=None):
    """Solve the joint forces and driving torques (see the module docstring).

    Parameters
    ----------
    links : dict of name -> LinkState
        The moving links' motion (spatialkin.motion.kinematics.LinkState), N instants each.
    joints : list of Joint
    bodies : dict of name -> Body
        Mass properties per link in its own frame (a link not named is massless).
    gravity : array_like (3,), optional
        The acceleration of gravity in fixed axes (L / s^2).
    external : dict of name -> (force (N, 3), point (N, 3), moment (N, 3)), optional
        Loads applied to links (fixed axes): a force at a point and a moment.

    Returns
    -------
    Loads

    Raises
    ------
    ValueError
        When the system is not square (the joints do not fix the links' loads), or singular at some instants
        (named: the mechanism is at a dead or branch position there).
    """
    names = list(links)
    row = {name: 6 * k for k, name in enumerate(names)}
    n = len(next(iter(links.values())).origin)
    columns, count = [], 0
    for joint in joints:
        columns.append(count)
        count += 3 + MOMENT_UNKNOWNS[joint.kind]
    if count != 6 * len(names):
        raise ValueError(f"the joints carry {count} unknowns for {6 * len(names)} equations of {len(names)} links")
    a = np.zeros((n, count, count))
    b = np.zeros((n, count))
    centres = {}
    g = np.zeros(3) if gravity is None else np.asarray(gravity, dtype=float)
    for name in names:
        state, body = links[name], bodies.get(name)
        mass = 0.0 if body is None else body.mass
        com = np.zeros(3) if body is None else body.com
        inertia = np.zeros((3, 3)) if body is None else body.inertia
        centre, _, acc = state.point(com)
        centres[name] = centre
        inertia_fixed = state.rotation @ inertia @ np.swapaxes(state.rotation, 1, 2)
        w, al = state.omega, state.alpha
        r = row[name]
        b[:, r:r + 3] = mass * (acc - g)
        b[:, r + 3:r + 6] = (np.einsum("nij,nj->ni", inertia_fixed, al)
                             + np.cross(w, np.einsum("nij,nj->ni", inertia_fixed, w)))
        if external and name in external:
            force, at, moment = (np.broadcast_to(np.asarray(x, dtype=float), (n, 3)) for x in external[name])
            b[:, r:r + 3] -= force
            b[:, r + 3:r + 6] -= moment + np.cross(at - centre, force)
    bases = {}
    for joint, col in zip(joints, columns):
        basis = None
        if joint.kind == REVOLUTE:
            basis = normal_basis(joint.axis)
        elif joint.kind == DRIVEN:
            basis = np.concatenate([normal_basis(joint.axis), joint.axis[:, :, None]], axis=2)
        bases[joint.name] = basis
        for link, sign in ((joint.child, 1.0), (joint.parent, -1.0)):
            if link is None:
                continue
            r = row[link]
            a[:, r:r + 3, col:col + 3] += sign * np.eye(3)
            a[:, r + 3:r + 6, col:col + 3] += sign * skew(joint.point - centres[link])
            if basis is not None:
                a[:, r + 3:r + 6, col + 3:col + 3 + basis.shape[2]] += sign * basis
    try:
        x = np.linalg.solve(a, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        bad = [k for k in range(n) if np.linalg.matrix_rank(a[k]) < count]
        raise ValueError(f"the loads are not determined at instants {bad[:10]} (a dead or branch position)") from None
    force, moment, local, torque = {}, {}, {}, {}
    shaking_force, shaking_moment = np.zeros((n, 3)), np.zeros((n, 3))
    for joint, col in zip(joints, columns):
        f = x[:, col:col + 3]
        basis = bases[joint.name]
        m = np.zeros((n, 3)) if basis is None else np.einsum("nij,nj->ni", basis, x[:, col + 3:col + 3 + basis.shape[2]])
        force[joint.name], moment[joint.name] = f, m
        local[joint.name] = np.einsum("nji,nj->ni", links[joint.child].rotation, f)
        if joint.kind == DRIVEN:
            torque[joint.name] = x[:, col + 5]
        if joint.parent is None:
            shaking_force -= f
            shaking_moment -= m + np.cross(joint.point, f)
    return Loads(force, moment, local, torque, shaking_force, shaking_moment)
