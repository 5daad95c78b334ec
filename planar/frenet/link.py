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

import numpy as np

from spatialkin.trajectory import Trajectory, time_map
from spatialkin.validation import check_finite, check_omega

from . import kernels as lk
from .laws import Law


class DrivenLink:
    """Kinematics of the link driven by a law at crank speed omega (rad per unit time).

    Methods take s (arc length of the pin's circle; the crank angle is k s) and rho (signed distance from
    the pin along the link), broadcast together; results are (..., 2) in fixed axes unless named _frame.
    """

    def __init__(self, law, omega=1.0):
        if not isinstance(law, Law):
            raise TypeError(f"law must be a planar law (CrankSlider, CrankRocker, ...), got {type(law).__name__}")
        self.law = law
        self.omega = check_omega(omega)
        self.k = law.k
        self.speed = self.omega / self.k          # V, the pin's speed

    def __repr__(self):
        return f"DrivenLink({self.law!r}, omega={self.omega:g})"

    def trajectory(self, s, rho):
        """Trajectory (the spatial side's pipeline) of the points (s, rho), broadcast together: the law is
        evaluated once per value of s and shared by every rho (s[:, None] with rho (R,) gives R points of
        the link at N crank positions), positions and s-derivatives by a jitted kernel."""
        s = np.asarray(s, dtype=float)
        rho = check_finite("rho", rho)
        shape = np.broadcast_shapes(s.shape, rho.shape)
        if s.ndim == 2 and s.shape[1] == 1 and rho.ndim == 1:        # N positions x R points
            s = s[:, 0]
            rho = np.broadcast_to(rho, shape)
        else:
            s = np.broadcast_to(s, shape).ravel()
            rho = np.broadcast_to(rho, shape).reshape(-1, 1)
        _, dphi, ddphi, cg, sg, ck, sk = self.law.evaluate_with_direction(s)
        out = np.empty((3,) + rho.shape + (2,))
        lk.link_derivatives(self.k, dphi, ddphi, cg, sg, ck, sk, rho, out[0], out[1], out[2])
        sdot, sddot = time_map(self.k, 0.0, self.omega)        # uniform: ds/dt = omega / k for every point
        return Trajectory(*(o.reshape(shape + (2,)) for o in out), sdot, sddot)

    def position(self, s, rho):
        return self.trajectory(s, rho).position

    def velocity(self, s, rho):
        return self.trajectory(s, rho).velocity

    def acceleration(self, s, rho):
        return self.trajectory(s, rho).acceleration

    def _on_frame(self, s, vectors):
        ks = self.k * np.asarray(s, dtype=float)
        tau = np.stack([np.cos(ks), np.sin(ks)], axis=-1)
        n = np.stack([-np.sin(ks), np.cos(ks)], axis=-1)
        return np.stack([np.sum(vectors * tau, -1), np.sum(vectors * n, -1)], axis=-1)

    def velocity_frame(self, s, rho):
        """(V_tau, V_n) (..., 2): velocity components on the trihedron (tau, n)."""
        return self._on_frame(s, self.velocity(s, rho))

    def acceleration_frame(self, s, rho):
        """(W_tau, W_n) (..., 2): acceleration components on (tau, n)."""
        return self._on_frame(s, self.acceleration(s, rho))

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
