"""The motion of a planar linkage at given input angles: joints' positions, velocities (total and per
crank), accelerations, and the links' angles, angular velocities and accelerations."""
import math

import numpy as np

from spatialkin.trajectory import time_map, to_time


class LockError(ValueError):
    """Requested input angles lie beyond a lock position of the driven group (or on one).

    Attributes
    ----------
    locks : ndarray
        Input angles (rad) of the lock positions of the assembly.
    angles : ndarray
        The requested angles that cannot be reached.
    """

    def __init__(self, locks, angles):
        self.locks = np.asarray(locks, dtype=float)
        self.angles = np.asarray(angles, dtype=float)
        where = ", ".join(f"{math.degrees(a):.6g}" for a in self.locks) or "none found"
        super().__init__(
            f"the linkage cannot reach input angle(s) {_degrees(self.angles)} deg on this assembly: "
            f"its driven group locks (singular Jacobian, the input reverses) at {where} deg")


def _degrees(angles, most=4):
    text = ", ".join(f"{math.degrees(a):.6g}" for a in angles[:most])
    return text + (f" ... ({len(angles)} in all)" if len(angles) > most else "")


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


class LinkageMotion:
    """Motion of a Linkage at input angles (N,), the input turning at the constant rate omega.

    Attributes
    ----------
    crank_angles : ndarray (N,)
        The input angles.
    omega : float
        Input rate (rad per unit time); crank k turns at ratio_k * omega.
    states : ndarray (N, n+1)
        Scaled configuration states (joint coordinates / mean length, input angle).
    """

    def __init__(self, linkage, states, omega, d1, d2, parts):
        """From solved states (N, n+1) and their derivatives in the input
        (kernels.solve_configurations)."""
        self.linkage = linkage
        self.states = states
        self.omega = omega
        self.crank_angles = states[:, -1]
        m = len(states)
        ell = linkage.mean_length
        sdot, sddot = time_map(d1[:, -1], d2[:, -1], omega)
        rates, accels = to_time(d1[:, :-1], d2[:, :-1], sdot, sddot)
        self._q = states[:, :-1].reshape(m, -1, 2) * ell
        self._v = rates.reshape(m, -1, 2) * ell
        self._a = accels.reshape(m, -1, 2) * ell
        crank_rates = np.array([c.ratio for c in linkage.cranks]) * omega
        self._parts = parts.reshape(m, len(linkage.cranks), -1, 2) * ell * crank_rates[None, :, None, None]

    def __repr__(self):
        a = np.degrees(self.crank_angles)
        joints = list(self.linkage.fixed) + list(self.linkage.moving)
        return (f"LinkageMotion({len(self)} input angles {a.min():.6g}..{a.max():.6g} deg, omega {self.omega:g}; "
                f"joints {joints})")

    def __len__(self):
        return len(self.crank_angles)

    def _index(self, joint):
        if joint in self.linkage.fixed:
            return None
        try:
            return self.linkage.moving.index(joint)
        except ValueError:
            raise ValueError(f"joint must be one of {self.linkage.joints}, got {joint!r}") from None

    def _crank(self, crank):
        if not (isinstance(crank, (int, np.integer)) and 1 <= crank <= len(self.linkage.cranks)):
            raise ValueError(f"crank must be None or 1..{len(self.linkage.cranks)}, got {crank!r}")
        return crank - 1

    def position(self, joint):
        """(N, 2) position of a joint."""
        i = self._index(joint)
        if i is None:
            return np.tile(self.linkage.fixed[joint], (len(self), 1))
        return self._q[:, i].copy()

    def velocity(self, joint, crank=None):
        """(N, 2) velocity of a joint; with crank=k only crank k's share (the other cranks stopped), so that
        the shares add up to the velocity."""
        i = self._index(joint)
        if i is None:
            return np.zeros((len(self), 2))
        if crank is None:
            return self._v[:, i].copy()
        return self._parts[:, self._crank(crank), i].copy()

    def acceleration(self, joint):
        """(N, 2) acceleration of a joint (constant input rate)."""
        i = self._index(joint)
        if i is None:
            return np.zeros((len(self), 2))
        return self._a[:, i].copy()

    def _link(self, link):
        for c in self.linkage.cranks:
            if c.name == link:
                return c.pivot, c.pin
        for lk in self.linkage.links:
            if lk.name == link:
                return lk.joints[0], lk.joints[1]
        names = [c.name for c in self.linkage.cranks] + [lk.name for lk in self.linkage.links]
        raise ValueError(f"link must be one of {names}, got {link!r}")

    def link_angle(self, link):
        """(N,) angle of the line from a link's first joint to its second, from the x-axis (unwrapped)."""
        p, q = self._link(link)
        d = self.position(q) - self.position(p)
        return np.unwrap(np.arctan2(d[:, 1], d[:, 0]))

    def angular_velocity(self, link, crank=None):
        """(N,) angular velocity of a link (anticlockwise positive); crank=k for crank k's share."""
        p, q = self._link(link)
        d = self.position(q) - self.position(p)
        return _cross(d, self.velocity(q, crank) - self.velocity(p, crank)) / np.sum(d * d, axis=1)

    def angular_acceleration(self, link):
        """(N,) angular acceleration of a link."""
        p, q = self._link(link)
        d = self.position(q) - self.position(p)
        return _cross(d, self.acceleration(q) - self.acceleration(p)) / np.sum(d * d, axis=1)
