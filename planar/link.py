"""The driven link of a crank mechanism, described in the Frenet trihedron riding on the crank pin.

For a point at signed distance rho from the pin A along the link, with gamma = ks + phi the link's angle to
Ox and e = (cos gamma, sin gamma), e_perp = (-sin gamma, cos gamma):

    P   = A + rho e
    P'  = tau + rho gamma' e_perp                              (gamma' = k + phi')
    P'' = k n + rho (gamma'' e_perp - gamma'^2 e)              (gamma'' = phi'')

and the spatial side's trajectory pipeline maps s to time: the crank angle ks turning at omega gives
ds/dt = omega / k = V and d2s/dt2 = 0. Velocity and acceleration components on (tau, n) are the seed's
(3) and (4); they are tested against each other.

References
----------
Seed 000; ../shared/reference/frenet-planar.md (eqs. (2)-(4), (11)).
"""
import math

import numpy as np

from spatialkin.trajectory import Trajectory, time_map

from .laws import Law


class DrivenLink:
    """Kinematics of the link driven by a law at crank speed omega (rad per unit time).

    Methods take s (arc length of the pin's circle; the crank angle is k s) and rho (signed distance from
    the pin along the link), broadcast together; results are (..., 2) in fixed axes unless named _frame.
    """

    def __init__(self, law, omega=1.0):
        if not isinstance(law, Law):
            raise TypeError(f"law must be a planar law (CrankSlider, CrankRocker, ...), got {type(law).__name__}")
        if not math.isfinite(omega) or omega == 0:
            raise ValueError(f"omega must be finite and non-zero, got {omega!r}")
        self.law = law
        self.omega = float(omega)
        self.k = law.k
        self.speed = self.omega / self.k          # V, the pin's speed

    def trajectory(self, s, rho):
        """Trajectory (the spatial side's pipeline) of the points (s, rho), each law value computed once."""
        s, rho = np.broadcast_arrays(np.asarray(s, dtype=float), np.asarray(rho, dtype=float))
        if not np.all(np.isfinite(rho)):
            raise ValueError("rho must be finite")
        k = self.k
        phi, dphi, ddphi = self.law.evaluate(s)
        ks = k * s
        gamma = ks + phi
        g1 = k + dphi
        e = np.stack([np.cos(gamma), np.sin(gamma)], axis=-1)
        ep = np.stack([-np.sin(gamma), np.cos(gamma)], axis=-1)
        tau = np.stack([np.cos(ks), np.sin(ks)], axis=-1)
        n = np.stack([-np.sin(ks), np.cos(ks)], axis=-1)
        pin = np.stack([np.sin(ks), -np.cos(ks)], axis=-1) / k
        r = rho[..., None]
        position = pin + r * e
        d1 = tau + r * g1[..., None] * ep
        d2 = k * n + r * (ddphi[..., None] * ep - (g1 ** 2)[..., None] * e)
        sdot, sddot = time_map(np.full(s.shape, k), np.zeros(s.shape), self.omega)
        traj = Trajectory(position, d1, d2, sdot, sddot)
        traj.frame = (tau, n)
        traj.law = (phi, dphi, ddphi)
        return traj

    def position(self, s, rho):
        return self.trajectory(s, rho).position

    def velocity(self, s, rho):
        return self.trajectory(s, rho).velocity

    def acceleration(self, s, rho):
        return self.trajectory(s, rho).acceleration

    def velocity_frame(self, s, rho):
        """(V_tau, V_n) (..., 2): velocity components on the trihedron (tau, n)."""
        t = self.trajectory(s, rho)
        tau, n = t.frame
        return np.stack([np.sum(t.velocity * tau, -1), np.sum(t.velocity * n, -1)], axis=-1)

    def acceleration_frame(self, s, rho):
        """(W_tau, W_n) (..., 2): acceleration components on (tau, n)."""
        t = self.trajectory(s, rho)
        tau, n = t.frame
        return np.stack([np.sum(t.acceleration * tau, -1), np.sum(t.acceleration * n, -1)], axis=-1)

    def angular_velocity(self, s):
        """Omega = V (k + phi') of the link (anticlockwise positive)."""
        _, dphi, _ = self.law.evaluate(s)
        return self.speed * (self.k + dphi)

    def angular_acceleration(self, s):
        """epsilon = V^2 phi''."""
        _, _, ddphi = self.law.evaluate(s)
        return self.speed ** 2 * ddphi

    def crank_angle(self, s):
        return self.k * np.asarray(s, dtype=float)
