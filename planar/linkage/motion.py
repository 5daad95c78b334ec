"""The motion of a planar linkage at given input angles: joints' positions, velocities (total and per
crank), accelerations, and the links' angles, angular velocities and accelerations."""
import math

import numpy as np

from spatialkin.motion.trajectory import time_map, to_time


class LockError(ValueError):
    """Requested input angles lie beyond a lock position of the driven group (or on one).

    A subclass of ValueError, raised by Linkage.solve.

    Parameters
    ----------
    locks : array_like
        Input angles (rad) of the lock positions of the assembly.
    angles : array_like
        The requested angles that cannot be reached.

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

    Made by Linkage.solve. Positions in the linkage's length unit, velocities in length per unit time,
    accelerations in length per unit time squared (the time unit that of 1/omega), all in fixed axes.

    Parameters
    ----------
    linkage : Linkage
    states : ndarray, shape (N, n+1)
        Solved scaled states (joint coordinates / mean length, input angle).
    omega : float
        Input rate (rad per unit time).
    d1, d2 : ndarray, shape (N, n+1)
        First and second derivatives of the states along the configuration curve.
    parts : ndarray
        Each crank's share of the joints' first derivatives.

    Attributes
    ----------
    crank_angles : ndarray (N,)
        The input angles.
    omega : float
        Input rate (rad per unit time); crank k turns at ratio_k * omega.
    states : ndarray (N, n+1)
        Scaled configuration states (joint coordinates / mean length, input angle).
    linkage : Linkage

    Examples
    --------
    >>> import numpy as np
    >>> import planar
    >>> mech = planar.examples.fnf_sixbar()
    >>> sol = mech.solve(np.radians([0.0, 45.0, 90.0]), omega=2.0)
    >>> len(sol), sol.crank_angles.shape
    (3, (3,))
    >>> np.allclose(np.linalg.norm(sol.position("K") - sol.position("E"), axis=1), 58.0)   # rocker EK
    True
    >>> sol.angular_velocity("6").shape
    (3,)
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
        """Position of a joint at each input angle, in fixed axes.

        Parameters
        ----------
        joint : str
            A joint's name (fixed or moving; see ``linkage.joints``).

        Returns
        -------
        ndarray, shape (N, 2)
            (x, y) in the linkage's length unit (a fixed joint's position repeated).

        Raises
        ------
        ValueError
            Naming `joint` when the linkage has no such joint.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> mech = planar.examples.fnf_sixbar()
        >>> sol = mech.solve(np.radians([0.0, 90.0]))
        >>> sol.position("K").round(1).tolist()[0]
        [95.0, 155.0]
        >>> sol.position("E").tolist()
        [[153.0, 155.0], [153.0, 155.0]]
        >>> sol.position("Z")
        Traceback (most recent call last):
        ...
        ValueError: joint must be one of ['O1', 'O2', 'E', 'A', 'D', 'B', 'C', 'K'], got 'Z'
        """
        i = self._index(joint)
        if i is None:
            return np.tile(self.linkage.fixed[joint], (len(self), 1))
        return self._q[:, i].copy()

    def velocity(self, joint, crank=None):
        """Velocity of a joint, or one crank's share of it, at each input angle, in fixed axes.

        Parameters
        ----------
        joint : str
            A joint's name.
        crank : int, optional
            None (default): the velocity; k (1-based): only crank k's share, the other cranks stopped. At a fixed
            position the velocities are linear in the crank rates, so the shares add up to the velocity.

        Returns
        -------
        ndarray, shape (N, 2)
            In length per unit time (zero for a fixed joint).

        Raises
        ------
        ValueError
            Naming `joint` (unknown) or `crank` (not None or 1..number of cranks).

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> mech = planar.examples.fnf_sixbar()
        >>> sol = mech.solve(np.radians([10.0, 100.0]), omega=1.0)
        >>> np.allclose(sol.velocity("C", crank=1) + sol.velocity("C", crank=2), sol.velocity("C"))
        True

        Against central differences of the position in the input angle (omega = 1):

        >>> h = 1e-6
        >>> q = mech.solve([1.0 - h, 1.0, 1.0 + h]).position("K")
        >>> np.allclose((q[2] - q[0]) / (2 * h), mech.solve([1.0]).velocity("K")[0], atol=1e-6)
        True
        """
        i = self._index(joint)
        if i is None:
            return np.zeros((len(self), 2))
        if crank is None:
            return self._v[:, i].copy()
        return self._parts[:, self._crank(crank), i].copy()

    def acceleration(self, joint):
        """Acceleration of a joint at each input angle (constant input rate), in fixed axes.

        Parameters
        ----------
        joint : str
            A joint's name.

        Returns
        -------
        ndarray, shape (N, 2)
            In length per unit time squared (zero for a fixed joint).

        Raises
        ------
        ValueError
            Naming `joint` when the linkage has no such joint.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> mech = planar.examples.fnf_sixbar()
        >>> slow = mech.solve(np.radians([30.0, 200.0]), omega=1.0)
        >>> fast = mech.solve(np.radians([30.0, 200.0]), omega=3.0)
        >>> np.allclose(fast.acceleration("K"), 9 * slow.acceleration("K"))
        True
        >>> h = 1e-5
        >>> v = mech.solve([1.0 - h, 1.0 + h]).velocity("K")
        >>> np.allclose((v[1] - v[0]) / (2 * h), mech.solve([1.0]).acceleration("K")[0], atol=1e-5)
        True
        """
        i = self._index(joint)
        if i is None:
            return np.zeros((len(self), 2))
        return self._a[:, i].copy()

    def loads(self, omega=None, bodies=None, gravity=None):
        """The forces over the motion: each crank's driving torque, every pin's load and the shaking force and
        moment on the frame (Newton-Euler in the plane; planar.linkage.loads).

        Parameters
        ----------
        omega : float, optional
            The input rate (rad/s) the loads are for (velocities scale with it, accelerations with its square);
            default the motion's own.
        bodies : dict of link name -> spatialkin.dynamics.Body, optional
            Mass properties of the cranks and links in their own frames (kg, the linkage's length unit; the centre
            of mass's x, y and inertia[2, 2] are read); a link not named is massless.
        gravity : array_like (2,), optional
            The acceleration of gravity (length unit / s^2, fixed axes).

        Returns
        -------
        spatialkin.dynamics.Loads
            ``torque[crank name]`` (N,) (kg L^2 / s^2); ``joint_force[joint]`` (N, 3) the pin's force on the last
            member it holds (a fixed pin: on its moving link) and ``member_force['joint:link']`` on each;
            ``joint_force_local`` and ``member_force_local`` in the link's own axes; ``shaking_force``,
            ``shaking_moment`` (N, 3) on the frame (z: the moment about the origin).

        Raises
        ------
        ValueError
            Naming the argument: an unknown link, a value that is not a Body, a gravity that is not 2 finite
            numbers; or a crank whose pivot is not fixed.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> from spatialkin.dynamics import Body
        >>> mech = planar.examples.fnf_sixbar()
        >>> sol = mech.solve(np.linspace(0.0, 2 * np.pi, 73), omega=2.0)
        >>> loads = sol.loads(bodies={"4": Body(0.3, (40.0, 10.0, 0.0), np.diag([0.0, 0.0, 400.0]))})
        >>> sorted(loads.torque), loads.joint_force["K"].shape
        (['1', '2'], (73, 3))
        """
        from .loads import linkage_loads
        return linkage_loads(self, bodies, gravity, omega)

    def counterweight(self, radius, bodies=None, crank=1, omega=None):
        """The point mass on crank `crank` (1, 2, ...), at the given radius from its pivot, that minimises the RMS
        shaking force over the motion (spatialkin.dynamics.balance): a spatialkin.dynamics.Counterweight with its
        mass (kg), angle (rad from the crank's pivot-to-pin line) and the shaking force's peak and RMS and that
        crank's peak torque before and after (``before``, ``after``). bodies and omega as in ``loads``.

        Examples
        --------
        >>> import numpy as np
        >>> import planar
        >>> from spatialkin.dynamics import Body
        >>> sol = planar.examples.fnf_sixbar().solve(np.linspace(0.0, 2 * np.pi, 181), omega=2.0)
        >>> weight = sol.counterweight(10.0, {"3": Body.rod(0.4, 137.0)})
        >>> bool(weight.after["rms_force"] < weight.before["rms_force"])
        True
        """
        from .loads import linkage_counterweight
        return linkage_counterweight(self, radius, bodies, crank, omega)

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
