"""The driven link of a crank mechanism, described in the Frenet trihedron riding on the crank pin.

For a point at signed distance rho from the pin A along the link, with gamma = ks + phi the link's angle to
Ox and e = (cos gamma, sin gamma), e_perp = (-sin gamma, cos gamma):

    P   = A + rho e
    P'  = tau + rho gamma' e_perp                              (gamma' = k + phi')
    P'' = k n + rho (gamma'' e_perp - gamma'^2 e)              (gamma'' = phi'')

and the spatial side's trajectory pipeline maps s to time: the crank angle ks turning at omega gives
ds/dt = omega / k = V and d2s/dt2 = 0. Velocity and acceleration components on (tau, n) are the paper's
(3) and (4); they are tested against each other.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven
member using Frenet trihedron", 2017 (eqs. (2)-(4), (11)).
"""

import numpy as np

from spatialkin.motion.trajectory import Trajectory, time_map
from spatialkin._lib.validation import check_finite, check_omega

from . import kernels as lk
from .laws import Law


class DrivenLink:
    """Kinematics of the link driven by a law, the crank turning at the constant rate omega.

    Methods take s (arc length of the pin's circle; the crank angle is k s) and rho (signed distance from
    the pin along the link), broadcast together; results are (..., 2) in fixed axes unless named _frame.
    For a point P = A + rho e of the link (e the link's unit direction at gamma = ks + phi to Ox),
    P' = tau + rho gamma' e_perp and P'' = k n + rho (gamma'' e_perp - gamma'^2 e) in s, mapped to time by
    ds/dt = V = omega / k (eqs. (2)-(4), (11) of [1]_).

    Parameters
    ----------
    law : Law
        The driven link's law phi(s): CrankSlider, CrankRocker, LawFromFunctions or LawFromGamma.
    omega : float
        Crank rate (rad per unit time), finite and non-zero.

    Attributes
    ----------
    law : Law
    omega : float
    k : float
        The law's curvature of the crank circle.
    speed : float
        V = omega / k, the pin's speed (length per unit time).

    Raises
    ------
    TypeError
        When `law` is not a planar law.
    ValueError
        Naming `omega` when it is zero or not finite.

    References
    ----------
    .. [1] S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms'
       driven member using Frenet trihedron", 2017.

    Examples
    --------
    >>> import numpy as np
    >>> import planar
    >>> link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0), omega=2.0)
    >>> link.speed                                            # V = omega / k
    4.0
    >>> s = np.linspace(0.0, 4 * np.pi, 9)
    >>> link.position(s[:, None], np.array([0.0, 2.0, 4.0])).shape    # 9 crank positions x 3 points
    (9, 3, 2)
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
        s = check_finite("s", s)
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
        rho = np.array(rho, dtype=float, order="C")       # (a broadcast view is read-only: one kernel signature)
        lk.link_derivatives(self.k, dphi, ddphi, cg, sg, ck, sk, rho, out[0], out[1], out[2])
        sdot, sddot = time_map(self.k, 0.0, self.omega)        # uniform: ds/dt = omega / k for every point
        return Trajectory(*(o.reshape(shape + (2,)) for o in out), sdot, sddot)

    def position(self, s, rho):
        """Position of the link's point rho at arc length s, in fixed axes.

        Parameters
        ----------
        s : float or array_like
            Arc length of the crank pin's circle (length unit); the crank angle is k s (radians).
        rho : float or array_like
            Signed distance of the point from the pin A along the link (length), broadcast with s (s[:, None]
            with rho (R,) gives R points of the link at N crank positions).

        Returns
        -------
        ndarray, shape (..., 2)
            P = A + rho (cos gamma, sin gamma) (length), the shape of s and rho broadcast.

        Raises
        ------
        ValueError
            Naming `s` or `rho` when not finite, or from the law (a user law's non-finite values).

        Examples
        --------
        The pin (rho = 0) runs on the crank circle of radius 1/k:

        >>> import numpy as np
        >>> import planar
        >>> link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0), omega=2.0)
        >>> s = np.linspace(0.0, 4 * np.pi, 9)
        >>> np.allclose(np.linalg.norm(link.position(s, 0.0), axis=1), 2.0)
        True
        >>> np.allclose(link.position(s, 4.0)[:, 1], 1.0)      # the slider, on the guide y = e
        True
        """
        return self.trajectory(s, rho).position

    def velocity(self, s, rho):
        """Velocity of the link's point rho at arc length s, in fixed axes.

        Parameters
        ----------
        s : float or array_like
            Arc length of the crank pin's circle (length unit); the crank angle is k s (radians).
        rho : float or array_like
            Signed distance of the point from the pin A along the link (length), broadcast with s (s[:, None]
            with rho (R,) gives R points of the link at N crank positions).

        Returns
        -------
        ndarray, shape (..., 2)
            dP/dt = V P' (length per unit time), V = omega / k.

        Raises
        ------
        ValueError
            Naming `s` or `rho` when not finite, or from the law.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0), omega=2.0)
        >>> s = np.linspace(0.0, 4 * np.pi, 9)
        >>> np.allclose(np.linalg.norm(link.velocity(s, 0.0), axis=1), 4.0)   # the pin at V = omega / k
        True
        >>> np.allclose(link.velocity(s, 4.0)[:, 1], 0.0)                   # the slider moves along the guide
        True

        Against central differences of the position in time (t = s / V):

        >>> h = 1e-6
        >>> fd = (link.position(s + h, 3.0) - link.position(s - h, 3.0)) / (2 * h / link.speed)
        >>> np.allclose(fd, link.velocity(s, 3.0), atol=1e-6)
        True
        """
        return self.trajectory(s, rho).velocity

    def acceleration(self, s, rho):
        """Acceleration of the link's point rho at arc length s, in fixed axes (constant crank rate).

        Parameters
        ----------
        s : float or array_like
            Arc length of the crank pin's circle (length unit); the crank angle is k s (radians).
        rho : float or array_like
            Signed distance of the point from the pin A along the link (length), broadcast with s (s[:, None]
            with rho (R,) gives R points of the link at N crank positions).

        Returns
        -------
        ndarray, shape (..., 2)
            d2P/dt2 = V^2 P'' (length per unit time squared).

        Raises
        ------
        ValueError
            Naming `s` or `rho` when not finite, or from the law.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0), omega=2.0)
        >>> s = np.linspace(0.0, 4 * np.pi, 9)
        >>> np.allclose(np.linalg.norm(link.acceleration(s, 0.0), axis=1), 8.0)   # the pin: V^2 k
        True
        >>> h = 1e-5
        >>> fd = (link.velocity(s + h, 3.0) - link.velocity(s - h, 3.0)) / (2 * h / link.speed)
        >>> np.allclose(fd, link.acceleration(s, 3.0), atol=1e-5)
        True
        """
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
        """The crank angle k s (radians) at arc lengths s."""
        return self.k * np.asarray(s, dtype=float)
