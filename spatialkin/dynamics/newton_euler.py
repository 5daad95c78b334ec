"""Inverse dynamics of a mechanism whose motion is known: Newton-Euler per link, the joints' constraint forces and
the driving torques solved as one linear system per instant (vectorised over the instants).

Each moving link k with mass m, centre of mass G and inertia I_G (fixed axes) obeys

    sum of the joint forces on it + m g + F_ext = m a_G,
    sum of the joint moments and of (P - G) x F over its joints + M_ext + (P_ext - G) x F_ext = I_G alpha + omega x I_G omega.

A joint acts on its child link with a force F (3 unknowns) and a moment M, and on its parent with -F, -M (the
frame when the parent is None): a revolute joint's M is normal to its axis (2 unknowns), a driven revolute's M
also has the driving torque along the axis (3 unknowns), a spherical joint carries no moment. The system is square
for a mechanism of one degree of freedom per driving joint (6 equations per link). A driven joint from the frame
holds all six unknowns its link's equations lack once the others are known: the other links' equations are solved
first, without it, and that link's then give it explicitly.

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
    joint_force_local, joint_moment_local : dict of ndarray (N, 3)
        The same forces and moments in the child link's own axes.
    torque : dict of ndarray (N,)
        Per driven joint: the driving torque about its axis.
    shaking_force, shaking_moment : ndarray (N, 3)
        The force, and the moment about the origin of the fixed axes, that the mechanism applies to the frame
        through its bearings (the driving motors' reactions included).
    """

    def __init__(self, joint_force, joint_moment, joint_force_local, joint_moment_local, torque, shaking_force,
                 shaking_moment):
        self.joint_force, self.joint_moment = joint_force, joint_moment
        self.joint_force_local, self.joint_moment_local = joint_force_local, joint_moment_local
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
    n = len(next(iter(links.values())).origin)
    order = {joint.name: k for k, joint in enumerate(joints)}
    count = sum(3 + MOMENT_UNKNOWNS[joint.kind] for joint in joints)
    if count != 6 * len(names):
        raise ValueError(f"the joints carry {count} unknowns for {6 * len(names)} equations of {len(names)} links")
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
        r = 6 * names.index(name)
        b[:, r:r + 3] = mass * (acc - g)
        b[:, r + 3:r + 6] = (np.einsum("nij,nj->ni", inertia_fixed, al)
                             + np.cross(w, np.einsum("nij,nj->ni", inertia_fixed, w)))
        if external and name in external:
            force, at, moment = (np.broadcast_to(np.asarray(x, dtype=float), (n, 3)) for x in external[name])
            b[:, r:r + 3] -= force
            b[:, r + 3:r + 6] -= moment + np.cross(at - centre, force)
    bases = {}
    for joint in joints:
        basis = None
        if joint.kind == REVOLUTE:
            basis = normal_basis(joint.axis)
        elif joint.kind == DRIVEN:
            basis = np.concatenate([normal_basis(joint.axis), joint.axis[:, :, None]], axis=2)
        bases[joint.name] = basis
    # a driven joint from the frame to a link carries all six of that link's unknowns beside the others' forces on
    # it: the other links' equations are solved without them, then that link's six give them explicitly
    explicit = [j for j in joints if j.kind == DRIVEN and j.parent is None
                and sum(j.child in (k.child, k.parent) for k in joints if k.kind == DRIVEN) == 1]
    kept_links = [name for name in names if name not in {j.child for j in explicit}]
    kept_joints = [j for j in joints if j not in explicit]
    row = {name: 6 * k for k, name in enumerate(kept_links)}
    size = 6 * len(kept_links)
    a = np.zeros((n, size, size))
    b_kept = np.concatenate([b[:, 6 * names.index(name):6 * names.index(name) + 6] for name in kept_links], axis=1) \
        if kept_links else np.zeros((n, 0))
    col, columns = 0, []
    for joint in kept_joints:
        columns.append(col)
        basis = bases[joint.name]
        for link, sign in ((joint.child, 1.0), (joint.parent, -1.0)):
            if link is None or link not in row:
                continue
            r = row[link]
            a[:, r:r + 3, col:col + 3] += sign * np.eye(3)
            a[:, r + 3:r + 6, col:col + 3] += sign * skew(joint.point - centres[link])
            if basis is not None:
                a[:, r + 3:r + 6, col + 3:col + 3 + basis.shape[2]] += sign * basis
        col += 3 + MOMENT_UNKNOWNS[joint.kind]
    try:
        x = np.linalg.solve(a, b_kept[..., None])[..., 0] if size else np.zeros((n, 0))
    except np.linalg.LinAlgError:
        bad = [k for k in range(n) if np.linalg.matrix_rank(a[k]) < size]
        raise ValueError(f"the loads are not determined at instants {bad[:10]} (a dead or branch position)") from None
    joints = kept_joints + explicit
    solved = {}
    for joint, c in zip(kept_joints, columns):
        basis = bases[joint.name]
        f = x[:, c:c + 3]
        m = np.zeros((n, 3)) if basis is None else np.einsum("nij,nj->ni", basis, x[:, c + 3:c + 3 + basis.shape[2]])
        solved[joint.name] = (f, m)
    for driven in explicit:
        link = driven.child
        k = names.index(link)
        f_need, m_need = b[:, 6 * k:6 * k + 3].copy(), b[:, 6 * k + 3:6 * k + 6].copy()
        for joint in kept_joints:
            for end, sign in ((joint.child, 1.0), (joint.parent, -1.0)):
                if end == link:
                    f, m = solved[joint.name]
                    f_need -= sign * f
                    m_need -= sign * (m + np.cross(joint.point - centres[link], f))
        solved[driven.name] = (f_need, m_need - np.cross(driven.point - centres[link], f_need))
    force, moment, local, local_moment, torque = {}, {}, {}, {}, {}
    shaking_force, shaking_moment = np.zeros((n, 3)), np.zeros((n, 3))
    for joint in sorted(joints, key=lambda j: order[j.name]):
        f, m = solved[joint.name]
        force[joint.name], moment[joint.name] = f, m
        local[joint.name] = np.einsum("nji,nj->ni", links[joint.child].rotation, f)
        local_moment[joint.name] = np.einsum("nji,nj->ni", links[joint.child].rotation, m)
        if joint.kind == DRIVEN:
            torque[joint.name] = np.einsum("ni,ni->n", m, joint.axis)
        if joint.parent is None:
            shaking_force -= f
            shaking_moment -= m + np.cross(joint.point, f)
    return Loads(force, moment, local, local_moment, torque, shaking_force, shaking_moment)
