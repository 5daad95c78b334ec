"""Layer 3: rigid links of a serial chain of revolute joints - positions, velocities, accelerations.

A link is reached from a fixed base frame through revolute joints; joint i sits at an offset (in the
previous link's frame) and turns about a local axis by an angle q_i(t) with rate and acceleration given.
The propagation is the classic one: omega_i = omega_{i-1} + qdot_i z_i, alpha_i = alpha_{i-1} + qddot_i z_i
+ omega_{i-1} x qdot_i z_i, and a point p on link i has v = v_o + omega x r, a = a_o + alpha x r +
omega x (omega x r), r = R p.
"""
import numpy as np


def axis_rotation(axis, angles):
    """Rotations (N, 3, 3) about a unit axis (3,) by angles (N,) (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    s = np.sin(angles)[:, None, None]
    c = np.cos(angles)[:, None, None]
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


class LinkState:
    """Pose and motion of one link over N instants: origin (N, 3), rotation (N, 3, 3), origin velocity and
    acceleration (N, 3), angular velocity omega and angular acceleration alpha (N, 3), in fixed axes."""

    def __init__(self, origin, rotation, velocity, acceleration, omega, alpha):
        self.origin, self.rotation = origin, rotation
        self.velocity, self.acceleration = velocity, acceleration
        self.omega, self.alpha = omega, alpha

    def __repr__(self):
        return f"LinkState({len(self.origin)} positions: origin, rotation, velocity, acceleration, omega, alpha)"

    def point(self, local):
        """(position, velocity, acceleration) (N, 3) each of a point fixed to the link, local (3,)."""
        r = self.rotation @ np.asarray(local, dtype=float)
        w = self.omega
        position = self.origin + r
        velocity = self.velocity + np.cross(w, r)
        acceleration = self.acceleration + np.cross(self.alpha, r) + np.cross(w, np.cross(w, r))
        return position, velocity, acceleration


def serial_chain(origin, rotation, joints, q, qdot, qddot):
    """Propagate a chain of revolute joints from a fixed base frame.

    Parameters
    ----------
    origin : (3,), rotation : (3, 3)
        The base frame (fixed).
    joints : list of (offset (3,), axis (3,))
        Joint i sits at `offset` in the frame of link i-1 and turns about the unit `axis` of that frame.
    q, qdot, qddot : ndarray (N, len(joints))
        Joint angles, rates and accelerations.

    Returns
    -------
    list of LinkState, one per joint (the link after it).
    """
    q = np.asarray(q, dtype=float)
    n = q.shape[0]
    o = np.broadcast_to(np.asarray(origin, dtype=float), (n, 3)).copy()
    rot = np.broadcast_to(np.asarray(rotation, dtype=float), (n, 3, 3)).copy()
    v = np.zeros((n, 3))
    a = np.zeros((n, 3))
    w = np.zeros((n, 3))
    al = np.zeros((n, 3))
    links = []
    for i, (offset, axis) in enumerate(joints):
        r = rot @ np.asarray(offset, dtype=float)
        o = o + r
        a = a + np.cross(al, r) + np.cross(w, np.cross(w, r))
        v = v + np.cross(w, r)
        z = rot @ np.asarray(axis, dtype=float)
        spin = qdot[:, i, None] * z
        al = al + qddot[:, i, None] * z + np.cross(w, spin)
        w = w + spin
        rot = rot @ axis_rotation(axis, q[:, i])
        links.append(LinkState(o, rot, v, a, w, al))
    return links
