"""The looper drive of a blind-stitch sewing machine: a spatial five-link crank-rocker R-R-S-R-R.

Crank 1 turns about the crank shaft (local z of the crank frame) by u1; coupler 2 hinges on the crank pin
(axis perpendicular to the shaft and to the crank arm, at the crank radius R1) by v1; its ball centre C sits
at the coupler length r1 from the pin axis, so C runs on the torus M1(u1, v1). Rocker shaft 4 turns about
the local z of the rocker frame by u2, rocker arm 3 hinges on it about a perpendicular axis by v2, and C sits
at the rocker length R2 from the rocker centre: on the sphere M2(u2, v2). The motion of C over the cycle is
torus ∩ sphere, traced once by arc length and re-parametrised by the crank angle u1.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the scheme, the two surfaces, the start where the sphere's equator meets
the torus. The reference geometry (spatialkin.mechanisms.looper.reference) is assumed: the paper gives no dimensions.
"""
import math
import time

import numpy as np
from scipy.optimize import brentq

from ...geometry.frame import Frame
from ...continuation import solve_at
from ...kernels.march import curve as kc
from ...motion.kinematics import serial_chain
from . import reference as ref
from ...geometry.surfaces import Sphere, Torus
from ...tracing.march.start import auxiliary_starts
from ...tracing.curve.bspline import fit as fit_spline
from ...tracing.components import intersect
from ...tracing.curve.result import TracingError
from ...tracing.single import trace
from ...motion.trajectory import Trajectory, time_map, to_time
from ..._lib.validation import check_choice, check_count, check_length, check_positive, check_vector
from ..common import PointMotion, angle_range_text, check_branch, check_drive

#: Crank angles sampled when checking where the mechanism can be assembled.
ASSEMBLY_SAMPLES = 3600
#: Dense samples per traced loop used to predict the state at a requested crank angle.
LOOP_SAMPLES = 2048
#: Newton iterations at a fixed crank angle.
NEWTON_MAX_ITER = 30
#: The coupler's circle is taken to reach the rocker sphere within this relative rounding error of its reach (a
#: crank angle at a dead position, where the two crossings meet).
CROSSING_SLACK = 1e-12
#: Accuracy of positions relative to the mechanism's size ...
POSITION_TOL = 1e-14
#: ... or this many ulps of the coordinates' magnitude, where larger (a mechanism far from the origin).
ROUNDOFF_ULPS = 8.0
#: Crank angles at most this far apart (rad) are solved by continuation, each Newton started from a second
#: order prediction off the angle before; farther ones start from the nearest dense sample.
CONTINUATION_REACH = 0.02
#: A requested crank angle farther than this (rad) from every dense sample of the traced component is not
#: covered by it (the branch goes on along another component): then every component is traced.
COVERAGE_GAP = 0.05
#: Links of the mechanism, for points fixed to them.
LINKS = ("crank", "coupler", "rocker_shaft", "rocker_arm")
_Z = (0.0, 0.0, 1.0)
_MINUS_Y = (0.0, -1.0, 0.0)


class LooperDrive:
    """Spatial five-link crank-rocker (R-R-S-R-R) of a blind-stitch sewing machine's looper.

    The ball centre C of the coupler runs on the torus of the crank (major radius R1, minor radius r1, about the
    crank shaft) and on the sphere of the rocker (radius R2 about the rocker centre P2): its path is
    torus ∩ sphere, traced once by arc length (Dragilev's method) and re-parametrised by the crank angle u1 [1]_.
    Lengths are in the user's unit (mm for the reference drive), angles in radians.

    Parameters
    ----------
    crank_radius : float
        R1, distance of the crank pin axis from the crank shaft (the torus's major radius), > 0.
    coupler_length : float
        r1, distance of the ball centre C from the crank pin axis (the torus's minor radius), > 0.
    rocker_length : float
        R2, distance of C from the rocker centre (the sphere's radius), > 0.
    crank_frame : Frame, optional
        Origin on the crank shaft; local z along the shaft. u1 is measured from local x. Default: global axes.
    rocker_frame : Frame, optional
        Origin at the rocker centre P2; local z along the rocker shaft. (u2, v2) are the sphere's angles
        (longitude about the shaft, latitude). Default: global axes.
    looper_tip : array_like, shape (3,)
        The looper tip in the frame of `looper_link` (rocker arm: x along the arm from P2 to C).
    looper_link : {'rocker_arm', 'rocker_shaft'}
        The link that carries the looper.

    Attributes
    ----------
    torus : Torus
        The crank's torus, M1(u1, v1).
    sphere : Sphere
        The rocker's sphere, M2(u2, v2).
    size : float
        R1 + r1 + R2, the mechanism's length scale.
    blocked_ranges : list of (float, float)
        Crank-angle intervals (radians, in [0, 2 pi)) where the mechanism cannot be assembled; empty when the
        crank turns fully.

    Raises
    ------
    ValueError
        Naming the argument for non-positive lengths, a non-finite looper_tip or an unknown looper_link; or for a
        mechanism that cannot be assembled at any crank angle.
    TypeError
        Naming `crank_frame` or `rocker_frame` when it is not a spatialkin.Frame.

    See Also
    --------
    LooperDrive.reference : the reference drive.
    spatialkin.design.LooperDesign : its geometry as design parameters.

    References
    ----------
    .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
       machines of the light industry" (in Ukrainian).

    Examples
    --------
    The reference geometry, with the rocker shaft along +y:

    >>> import numpy as np
    >>> import spatialkin as sk
    >>> from spatialkin.mechanisms import LooperDrive
    >>> rocker = sk.Frame((6.0, 0.0, 75.0), sk.rotation_about((1.0, 0.0, 0.0), -np.pi / 2))
    >>> drive = LooperDrive(8.0, 50.0, 30.0, crank_frame=sk.Frame(), rocker_frame=rocker,
    ...                     looper_tip=(40.0, 0.0, 12.0))
    >>> drive.blocked_ranges                    # the crank turns fully
    []
    >>> motion = drive.solve(np.radians([0.0, 90.0, 180.0, 270.0]), omega=10.0)
    >>> motion.ball_center.shape
    (4, 3)
    >>> np.allclose(np.linalg.norm(motion.ball_center - rocker.origin, axis=1), 30.0)   # C on the sphere
    True
    >>> np.allclose(drive.torus.distance(motion.ball_center), 0.0, atol=1e-9)            # and on the torus
    True
    >>> LooperDrive(8.0, 50.0, 1.0, rocker_frame=rocker)
    Traceback (most recent call last):
    ...
    ValueError: the mechanism cannot be assembled at any crank angle: ...
    """

    def __init__(self, crank_radius, coupler_length, rocker_length, crank_frame=None, rocker_frame=None,
                 looper_tip=(0.0, 0.0, 0.0), looper_link="rocker_arm"):
        self.crank_radius = check_length("crank_radius", crank_radius)
        self.coupler_length = check_length("coupler_length", coupler_length)
        self.rocker_length = check_length("rocker_length", rocker_length)
        self.crank_frame = crank_frame if crank_frame is not None else Frame()
        self.rocker_frame = rocker_frame if rocker_frame is not None else Frame()
        for name, f in (("crank_frame", self.crank_frame), ("rocker_frame", self.rocker_frame)):
            if not isinstance(f, Frame):
                raise TypeError(f"{name} must be a spatialkin.Frame, got {type(f).__name__}")
        self.looper_link = check_choice("looper_link", looper_link, ("rocker_arm", "rocker_shaft"))
        self.looper_tip = check_vector("looper_tip", looper_tip)
        self.torus = Torus(self.crank_radius, self.coupler_length, self.crank_frame)
        self.sphere = Sphere(self.rocker_length, self.rocker_frame)
        self.size = self.crank_radius + self.coupler_length + self.rocker_length
        reach = max(float(np.max(np.abs(self.crank_frame.origin))), float(np.max(np.abs(self.rocker_frame.origin))))
        # positions to POSITION_TOL x size, or to the round-off of coordinates far from the origin
        self.position_tol = max(POSITION_TOL * self.size, ROUNDOFF_ULPS * np.finfo(float).eps * (reach + self.size))
        grid = np.linspace(0.0, 2 * np.pi, ASSEMBLY_SAMPLES, endpoint=False)
        margin = self.assembly_margin(grid)
        if np.all(margin < 0):
            raise ValueError("the mechanism cannot be assembled at any crank angle: the coupler's circle never "
                             f"reaches the rocker sphere (closest miss {-margin.max():.6g})")
        self._blocked = [(self._edge(lo - step, lo), self._edge(hi, hi + step))
                         for lo, hi in ranges_of(grid, margin < 0)
                         for step in [grid[1] - grid[0]]]
        self._loops = None

    def __repr__(self):
        tip = ", ".join(f"{x:g}" for x in self.looper_tip)
        return (f"LooperDrive(crank_radius={self.crank_radius:g}, coupler_length={self.coupler_length:g}, "
                f"rocker_length={self.rocker_length:g}, crank_frame={self.crank_frame!r}, "
                f"rocker_frame={self.rocker_frame!r}, looper_tip=({tip}), looper_link={self.looper_link!r})"
                + (f"  # blocked crank ranges: {len(self._blocked)}" if self._blocked else ""))

    @classmethod
    def reference(cls):
        """The reference looper drive (lengths in mm), defined in spatialkin.mechanisms.looper.reference.

        R1 = 8 (crank radius), r1 = 50 (coupler length), R2 = 30 (rocker length); the crank frame is the global
        axes, the rocker centre P2 = (6, 0, 75) with the rocker shaft along +y; the looper tip 40 mm along the
        rocker arm and 12 mm off it. The scheme is that of [1]_; the reference geometry is assumed: the paper
        gives no dimensions.

        Returns
        -------
        LooperDrive

        References
        ----------
        .. [1] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
           machines of the light industry" (in Ukrainian).

        Examples
        --------
        >>> import numpy as np
        >>> from spatialkin.mechanisms import LooperDrive
        >>> drive = LooperDrive.reference()
        >>> drive.crank_radius, drive.coupler_length, drive.rocker_length
        (8.0, 50.0, 30.0)
        >>> drive.rocker_frame.origin.tolist(), np.allclose(drive.rocker_frame.rotation[:, 2], (0.0, 1.0, 0.0))
        ([6.0, 0.0, 75.0], True)
        >>> drive.blocked_ranges
        []
        """
        return cls(ref.CRANK_RADIUS, ref.COUPLER_LENGTH, ref.ROCKER_LENGTH, Frame(), ref.rocker_frame(),
                   looper_tip=ref.LOOPER_TIP)

    # --- assembly ---------------------------------------------------------------------------------
    def assembly_margin(self, crank_angles):
        """How far (length) the rocker length lies inside the range of distances from the rocker centre to
        the coupler's circle at each crank angle (radians, any shape); negative where the mechanism cannot be
        assembled."""
        u1 = np.asarray(crank_angles, dtype=float)
        rot = self.crank_frame.rotation
        q = rot.T @ (self.rocker_frame.origin - self.crank_frame.origin)     # rocker centre, crank frame
        radial = np.stack([np.cos(u1), np.sin(u1), np.zeros_like(u1)], axis=-1)
        axis = np.stack([-np.sin(u1), np.cos(u1), np.zeros_like(u1)], axis=-1)   # the pin axis
        rel = q - self.crank_radius * radial
        h = np.einsum("...i,...i->...", rel, axis)
        inplane = np.linalg.norm(rel - h[..., None] * axis, axis=-1)
        d_min = np.hypot(inplane - self.coupler_length, h)
        d_max = np.hypot(inplane + self.coupler_length, h)
        return np.minimum(self.rocker_length - d_min, d_max - self.rocker_length)

    def _edge(self, a, b):
        """The crank angle in [a, b] where the assembly margin crosses zero (or a, b at the turn's ends)."""
        fa, fb = self.assembly_margin(np.array([a, b]))
        if fa * fb > 0:
            return float(np.clip(a if abs(fa) < abs(fb) else b, 0.0, 2 * np.pi))
        return float(np.mod(brentq(lambda x: float(self.assembly_margin(np.array([x]))[0]), a, b, xtol=1e-14),
                            2 * np.pi))

    @property
    def blocked_ranges(self):
        """Crank-angle intervals (radians, in [0, 2 pi)) where the mechanism cannot be assembled."""
        return list(self._blocked)

    def branch_of(self, states):
        """Assembly branch (0 or 1) of states (..., 4): 0 where the coupler's circle leaves the rocker
        sphere as v1 grows ((C - P2) . dC/dv1 > 0), 1 where it enters. In the reference geometry branch 0
        is the 59.7 mm loop with v1 in about 107-114 deg."""
        y = np.asarray(states, dtype=float).reshape(-1, 4)
        u1, v1 = y[:, 0], y[:, 1]
        # dC/dv1 of the torus point, in the crank frame then in fixed axes (all states at once)
        local = self.coupler_length * np.stack([-np.sin(v1) * np.cos(u1), -np.sin(v1) * np.sin(u1), np.cos(v1)],
                                               axis=-1)
        d_v1 = local @ self.crank_frame.rotation.T
        outward = np.einsum("ij,ij->i", self.torus.point(u1, v1) - self.rocker_frame.origin, d_v1)
        return np.where(outward > 0, 0, 1).reshape(np.shape(states)[:-1])

    def assemble(self, crank_angle, branch=0):
        """State (u1, v1, u2, v2) at one crank angle on the given branch: Newton from the coupler circle's
        crossings of the rocker sphere, found in closed form (crossings), so that both are found however close
        together, next to a dead position."""
        branch = check_branch(branch)
        u1 = float(crank_angle)
        self._check_assemblable(np.array([u1]))
        for v1 in self.crossings(u1):
            point = self.torus.point(u1, v1)
            y = self._at_crank_angles(np.array([[u1, v1, *self.sphere.parameters(point)]]))
            if y is not None and self.branch_of(y[0]) == branch:
                return y[0]
        raise ValueError(f"no assembly on branch {branch} at crank angle {math.degrees(u1):.6g} deg")

    def crossings(self, crank_angle):
        """The tube angles v1 (0, 1 or 2 of them) where the coupler's circle at the crank angle crosses the rocker
        sphere. The circle is C(v) = c + a cos v + b sin v with |a| = |b| = r and a normal to b (the torus at fixed
        u), so |C(v) - P2|^2 - L^2 = A + B cos v + D sin v: v = phi +- acos(-A / hypot(B, D)), phi = atan2(D, B)
        (clipped to the circle's reach where rounding puts a touching crossing just outside it), in [-pi, pi]."""
        u1 = float(crank_angle)
        c0, a0, b0 = (self.torus.point(u1, v) for v in (math.pi, 0.0, 0.5 * math.pi))
        c = 0.5 * (c0 + a0)
        a, b, rel = a0 - c, b0 - c, c - self.rocker_frame.origin
        A = rel @ rel + self.coupler_length ** 2 - self.rocker_length ** 2
        B, D = 2.0 * (rel @ a), 2.0 * (rel @ b)
        reach = math.hypot(B, D)
        if reach == 0.0 or abs(A) > reach * (1.0 + CROSSING_SLACK):
            return []
        phi, half = math.atan2(D, B), math.acos(min(1.0, max(-1.0, -A / reach)))
        return [math.remainder(v, 2.0 * math.pi) for v in ((phi - half, phi + half) if half > 0.0 else (phi,))]

    def _check_assemblable(self, u1):
        bad = self.assembly_margin(u1) < -self.position_tol
        if np.any(bad):
            spans = ", ".join(f"[{math.degrees(a):.3f}, {math.degrees(b):.3f}] deg" for a, b in self._blocked)
            raise ValueError(f"the mechanism cannot be assembled at {int(bad.sum())} of the requested crank "
                             f"angles (first {math.degrees(float(u1[bad][0])):.6g} deg): the coupler's circle "
                             f"misses the rocker sphere for crank angles in {spans}")

    def _at_crank_angles(self, ys):
        """Newton at fixed u1 (column 0) onto torus ∩ sphere, in place; None if any fails."""
        ys = np.ascontiguousarray(ys, dtype=float)
        ok = np.zeros(len(ys), dtype=np.bool_)
        kc.newton_fixed_many(ys, self.torus.data, self.sphere.data, 0, self.position_tol,
                             NEWTON_MAX_ITER, ok)
        return ys if np.all(ok) else None

    # --- the cycle --------------------------------------------------------------------------------
    def seed_starts(self):
        """The start of [Looper]'s method: states (K, 4) where the sphere's equator (v2 = 0) meets the torus."""
        return auxiliary_starts(self.torus, self.sphere)

    def loops(self):
        """Every component of torus ∩ sphere (sk.intersect), traced once and cached: the paths of C."""
        if self._loops is None:
            self._loops = intersect(self.torus, self.sphere)
        return self._loops

    def _samples(self, branch, crank_angles):
        """Dense states (M, 4) on the given branch, sorted by u1 mod 2 pi: Newton's starts, from the tracer's
        dense output (Curve.predicted_parameters).

        Only the component through the assembly at the first crank angle is traced (sk.trace) while it covers
        every requested angle on the branch; otherwise every component (loops(), sk.intersect) is used."""
        if self._loops is None:
            first = self.assemble(float(crank_angles[0]), branch)
            try:
                samples = self._branch_samples([trace(self.torus, self.sphere, first)], branch)
            except TracingError:        # e.g. the assembly sits on a singular point: every component then
                samples = np.empty((0, 4))
            if len(samples) and covers(np.mod(samples[:, 0], 2 * np.pi), np.mod(crank_angles, 2 * np.pi),
                                       COVERAGE_GAP):
                return samples
        samples = self._branch_samples(self.loops(), branch)
        if not len(samples):
            raise ValueError(f"no assembly of branch {branch} was found")
        return samples

    def _branch_samples(self, curves, branch):
        ys = [np.empty((0, 4))]
        for c in curves:
            if c.length == 0:
                continue
            y = c.predicted_parameters(np.linspace(0.0, c.length, LOOP_SAMPLES))
            ys.append(y[self.branch_of(y) == branch])
        y = np.vstack(ys)
        return y[np.argsort(np.mod(y[:, 0], 2 * np.pi))]

    def analyse(self, branch=0, samples=3601, motion=None):
        """What a designer needs to know: see spatialkin.mechanisms.looper.analysis.LooperAnalysis. The
        transmission angle is given over `samples` crank angles, or over those of `motion` (a LooperMotion of
        this drive and branch, reused): an integer from 3 to ANALYSIS_SAMPLES_MAX (ValueError naming it)."""
        from .analysis import ANALYSIS_SAMPLES_MAX, analyse
        if motion is None:
            check_count("samples", samples, minimum=3, maximum=ANALYSIS_SAMPLES_MAX)
        return analyse(self, check_branch(branch), samples, motion)

    def loads(self, crank_angles, omega=1.0, bodies=None, gravity=None, external=None, branch=0):
        """The forces over the crank angles at the crank rate omega (rad/s): ``self.solve(crank_angles, omega,
        branch).loads(bodies, gravity, external)`` (see LooperMotion.loads)."""
        return self.solve(crank_angles, omega, branch).loads(bodies, gravity, external)

    def solve(self, crank_angles, omega=1.0, branch=0):
        """Motion at exactly the given crank angles, the crank turning at the constant rate omega.

        The component of torus ∩ sphere through the assembly is traced once by arc length (cached per drive);
        each requested angle is then solved exactly by Newton at the fixed crank angle, and velocities and
        accelerations follow analytically from the curve's arc-length derivatives and the map s -> time.

        Parameters
        ----------
        crank_angles : float or array_like, shape (N,)
            Crank angles u1 (radians, any real values, in any order).
        omega : float
            Crank rate (radians per unit time), finite and non-zero; velocities come in length per that time
            unit, accelerations in length per time unit squared.
        branch : {0, 1}
            Assembly branch: 0 where the coupler's circle leaves the rocker sphere as v1 grows, 1 where it
            enters (see branch_of).

        Returns
        -------
        LooperMotion
            Positions, velocities and accelerations at the crank angles, in fixed axes (N rows each).

        Raises
        ------
        ValueError
            Naming `crank_angles` (not finite, empty), `omega` (zero, not finite) or `branch`; for crank angles
            where the mechanism cannot be assembled (inside blocked_ranges); where Newton fails next to a dead
            position, the branch is not continuous, or a singular point of torus ∩ sphere lies.

        Examples
        --------
        >>> import numpy as np
        >>> from spatialkin.mechanisms import LooperDrive
        >>> drive = LooperDrive.reference()
        >>> motion = drive.solve(np.linspace(0.0, 2 * np.pi, 361), omega=1.0)
        >>> motion.ball_center.shape, motion.ball_velocity.shape, motion.ball_acceleration.shape
        ((361, 3), (361, 3), (361, 3))

        The velocity against central differences of the position:

        >>> h = 1e-5
        >>> m = drive.solve([1.0 - h, 1.0, 1.0 + h])
        >>> np.allclose((m.ball_center[2] - m.ball_center[0]) / (2 * h), m.ball_velocity[1], atol=1e-6)
        True
        """
        u1, omega, branch = check_drive(crank_angles, omega, branch)
        t0 = time.perf_counter()
        self._check_assemblable(np.mod(u1, 2 * np.pi))
        samples = self._samples(branch, u1)
        # the nearest sample predicts (the states hold angles that wrap between samples); the angles are solved
        # in increasing order, each Newton started by continuation from the one before when it is within
        # CONTINUATION_REACH
        solved, status, dy, ddy, d1, d2 = solve_at(u1, np.mod(samples[:, 0], 2 * np.pi), samples,
                                                   self._fixed_crank_path, index=0, period=2 * np.pi,
                                                   start=0.0, how="nearest")
        if np.any(status == 1):
            raise ValueError("Newton at fixed crank angle failed: the crank angles are too close to a dead "
                             "position or a branch point")
        wrong = self.branch_of(solved) != branch
        if np.any(wrong):
            raise ValueError(f"branch {branch} is not continuous through crank angle "
                             f"{math.degrees(float(u1[wrong][0])):.6g} deg (branches meet there)")
        if np.any(status == 2):
            raise ValueError("a singular point of torus ∩ sphere (the branches meet) lies at crank angle "
                             f"{math.degrees(float(solved[status == 2][0, 0])):.6g} deg")
        return LooperMotion(self, solved, omega, branch, time.perf_counter() - t0, (dy, ddy, d1, d2))

    def _fixed_crank_path(self, ys):
        """(states, status, y', y'', C', C'') by Newton at the fixed crank angles of ys (N, 4), sorted by crank
        angle, each started from the one before within CONTINUATION_REACH (solve_at's corrector)."""
        n = len(ys)
        dy, ddy, d1, d2 = np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 3)), np.empty((n, 3))
        status = np.empty(n, dtype=np.int64)
        kc.fixed_parameter_path(ys, np.ascontiguousarray(ys[:, 0]), self.torus.data, self.sphere.data, 0,
                                CONTINUATION_REACH, self.position_tol, NEWTON_MAX_ITER, dy, ddy, d1, d2,
                                status)
        return ys, status, dy, ddy, d1, d2


def covers(keys, angles, gap):
    """True when every angle (mod 2 pi) lies within gap of one of the sorted keys in [0, 2 pi) (circularly)."""
    idx = np.searchsorted(keys, angles)
    before = keys[np.clip(idx - 1, 0, len(keys) - 1)]
    after = keys[np.clip(idx, 0, len(keys) - 1)]
    # the first key follows the last one round the circle
    before = np.where(idx == 0, keys[-1] - 2 * np.pi, before)
    after = np.where(idx == len(keys), keys[0] + 2 * np.pi, after)
    return bool(np.all(np.minimum(angles - before, after - angles) <= gap))


def state_derivatives(drive, states):
    """(y', y'', C', C'') in arc length (sign +1) at states (N, 4) on torus ∩ sphere."""
    n = len(states)
    dy, ddy = np.empty((n, 4)), np.empty((n, 4))
    d1, d2 = np.empty((n, 3)), np.empty((n, 3))
    ok = np.zeros(n, dtype=np.bool_)
    kc.curve_derivatives_many(states, drive.torus.data, drive.sphere.data, 1.0, dy, ddy, d1, d2, ok)
    if not np.all(ok):
        raise ValueError("a singular point of torus ∩ sphere (the branches meet) lies at crank angle "
                         f"{math.degrees(float(states[~ok][0, 0])):.6g} deg")
    return dy, ddy, d1, d2


class LooperMotion:
    """The looper drive's motion at given crank angles (all in fixed axes; angles in radians).

    Made by LooperDrive.solve. Lengths are in the drive's unit, time in the unit of 1/omega (omega in rad per
    unit time); the crank turns at the constant rate omega.

    Parameters
    ----------
    drive : LooperDrive
    states : ndarray, shape (N, 4)
        (u1, v1, u2, v2) on torus ∩ sphere at the crank angles u1.
    omega : float
        Crank rate (rad per unit time).
    branch : int
        The assembly branch.
    wall_time : float
        Seconds spent solving.
    derivatives : tuple of ndarray, optional
        (dy/ds (N, 4), d2y/ds2 (N, 4), C' (N, 3), C'' (N, 3)) at the states, else computed here.

    Attributes
    ----------
    crank_angle : ndarray, shape (N,)
        u1, exactly as requested (radians).
    coupler_angle : ndarray, shape (N,)
        v1, the coupler's angle about the crank pin (radians).
    coupler_rate, coupler_acceleration : ndarray, shape (N,)
        dv1/dt (rad per unit time) and d2v1/dt2 (rad per unit time squared).
    rocker_angles : ndarray, shape (N, 2)
        (u2, v2), the rocker shaft's and the rocker arm's angles (radians).
    rocker_rates, rocker_accelerations : ndarray, shape (N, 2)
        d/dt and d2/dt2 of (u2, v2).
    ball_center : ndarray, shape (N, 3)
        Position of the ball centre C (length).
    ball_velocity : ndarray, shape (N, 3)
        dC/dt (length per unit time).
    ball_acceleration : ndarray, shape (N, 3)
        d2C/dt2 (length per unit time squared).
    ball : Trajectory
        The ball centre with its arc-length derivatives (C', C'') and the map s -> time.
    ds_dt, d2s_dt2 : ndarray, shape (N,)
        Speed of C (arc length of torus ∩ sphere per unit time) and its rate.
    looper_tip : PointMotion
        Position, velocity and acceleration (N, 3) each of the looper tip.
    states : ndarray, shape (N, 4)
        (u1, v1, u2, v2).
    omega : float
    branch : int
    wall_time : float

    Examples
    --------
    >>> import numpy as np
    >>> from spatialkin.mechanisms import LooperDrive
    >>> drive = LooperDrive.reference()
    >>> angles = np.radians([30.0, 120.0, 250.0])
    >>> slow, fast = drive.solve(angles, omega=1.0), drive.solve(angles, omega=2.0)
    >>> np.allclose(fast.ball_center, slow.ball_center)
    True
    >>> np.allclose(fast.ball_velocity, 2 * slow.ball_velocity)
    True
    >>> np.allclose(fast.ball_acceleration, 4 * slow.ball_acceleration)
    True
    >>> np.allclose(np.linalg.norm(slow.ball_velocity, axis=1), slow.ds_dt)
    True
    >>> slow.rocker_angles.shape, slow.looper_tip.position.shape
    ((3, 2), (3, 3))
    """

    def __init__(self, drive, states, omega, branch, wall_time, derivatives=None):
        self.drive, self.omega, self.branch = drive, float(omega), branch
        self.states = states
        if derivatives is None:
            derivatives = state_derivatives(drive, states)
        dy, ddy, d1, d2 = (np.array(x) for x in derivatives)
        flip = np.where(dy[:, 0] < 0, -1.0, 1.0)        # orient s so that the crank angle grows with it
        dy *= flip[:, None]
        d1 *= flip[:, None]
        self.dy_ds, self.d2y_ds2 = dy, ddy
        sdot, sddot = time_map(dy[:, 0], ddy[:, 0], self.omega)
        self.ds_dt, self.d2s_dt2 = sdot, sddot
        rates, accels = to_time(dy, ddy, sdot, sddot)
        self.crank_angle = states[:, 0].copy()
        self.coupler_angle = states[:, 1].copy()
        self.rocker_angles = states[:, 2:].copy()
        self.rocker_rates, self.rocker_accelerations = rates[:, 2:], accels[:, 2:]
        self.coupler_rate, self.coupler_acceleration = rates[:, 1], accels[:, 1]
        self.ball = Trajectory(drive.torus.point(states[:, 0], states[:, 1]), d1, d2, sdot, sddot)
        self.ball_center = self.ball.position
        self.ball_velocity, self.ball_acceleration = self.ball.velocity, self.ball.acceleration
        self._rates, self._accels = rates, accels
        self.wall_time = wall_time
        self._links = None

    def links(self):
        """LinkState of each link (crank, coupler, rocker_shaft, rocker_arm) by serial-chain propagation."""
        if self._links is None:
            d = self.drive
            q, qd, qdd = self.states, self._rates, self._accels
            crank, coupler = serial_chain(d.crank_frame.origin, d.crank_frame.rotation,
                                          [((0, 0, 0), _Z), ((d.crank_radius, 0, 0), _MINUS_Y)],
                                          q[:, :2], qd[:, :2], qdd[:, :2])
            shaft, arm = serial_chain(d.rocker_frame.origin, d.rocker_frame.rotation,
                                      [((0, 0, 0), _Z), ((0, 0, 0), _MINUS_Y)], q[:, 2:], qd[:, 2:], qdd[:, 2:])
            self._links = dict(zip(LINKS, (crank, coupler, shaft, arm)))
        return self._links

    def point(self, link, local):
        """PointMotion of a point fixed to a link ('crank', 'coupler', 'rocker_shaft', 'rocker_arm'),
        given in that link's frame (coupler: x from the pin axis to C; rocker arm: x from P2 to C)."""
        check_choice("link", link, LINKS)
        local = check_vector("local", local)
        return PointMotion(*self.links()[link].point(local))

    def loads(self, bodies=None, gravity=None, external=None):
        """The forces over the motion: the crank torque, every joint's load, the shaking force and moment.

        Newton-Euler on the four moving links with the joints' constraint forces solved as one linear system per
        crank angle (spatialkin.mechanisms.looper.loads names the joints: crank_bearing, crank_pin, ball,
        rocker_hinge, rocker_bearing).

        Parameters
        ----------
        bodies : dict of link name -> spatialkin.dynamics.Body, optional
            Mass properties of 'crank', 'coupler', 'rocker_shaft', 'rocker_arm' in their own frames (kg, the
            drive's length unit); a link not named is massless.
        gravity : array_like (3,), optional
            The acceleration of gravity in fixed axes (length unit / s^2: (0, 0, -9810) for mm, z up).
        external : callable, optional
            external(crank_angles (N,)) -> (force (N, 3), moment (N, 3)) on the looper link, the force at the
            looper tip (a thread load), in fixed axes.

        Returns
        -------
        spatialkin.dynamics.Loads
            With ``crank_torque`` (N,) about the crank shaft (kg L^2 / s^2: uN m for mm), ``joint_force[joint]``,
            ``joint_moment[joint]`` and ``joint_force_local[joint]`` (N, 3) (kg L / s^2: mN for mm), and
            ``shaking_force``, ``shaking_moment`` (N, 3) on the frame; at the motion's crank rate omega (rad/s).

        Raises
        ------
        ValueError
            Naming the argument: an unknown link or a value that is not a Body, a gravity that is not 3 finite
            numbers, an external load that is not a function or not finite.

        Examples
        --------
        >>> import numpy as np
        >>> from spatialkin.mechanisms import LooperDrive
        >>> from spatialkin.dynamics import Body
        >>> drive = LooperDrive.reference()
        >>> motion = drive.solve(np.linspace(0.0, 2 * np.pi, 361), omega=2000 * np.pi / 30)
        >>> loads = motion.loads({"coupler": Body.rod(0.05, drive.coupler_length),
        ...                       "rocker_arm": Body.rod(0.04, drive.rocker_length)})
        >>> loads.crank_torque.shape, loads.joint_force["ball"].shape
        ((361,), (361, 3))
        """
        from .loads import motion_loads
        return motion_loads(self, bodies, gravity, external)

    def counterweight(self, radius, bodies=None):
        """The point mass on the crank, at the given radius, that minimises the RMS shaking force over the motion
        (gravity aside), with the shaking force's peak and RMS and the peak crank torque before and after it.

        Parameters
        ----------
        radius : float
            Its distance from the crank shaft (length unit), > 0.
        bodies : dict of link name -> spatialkin.dynamics.Body, optional
            As in ``loads``.

        Returns
        -------
        spatialkin.dynamics.Counterweight
            ``mass`` (kg), ``angle`` (rad, in the crank's frame from the crank arm), ``body`` (a Body to combine with
            the crank's: spatialkin.dynamics.combined), ``before`` and ``after``: {'peak_force', 'rms_force',
            'peak_torque'}.

        Examples
        --------
        >>> import numpy as np
        >>> from spatialkin.mechanisms import LooperDrive
        >>> from spatialkin.dynamics import Body
        >>> drive = LooperDrive.reference()
        >>> motion = drive.solve(np.linspace(0.0, 2 * np.pi, 361), omega=2000 * np.pi / 30)
        >>> weight = motion.counterweight(10.0, {"coupler": Body.rod(0.05, drive.coupler_length)})
        >>> bool(weight.after["rms_force"] < weight.before["rms_force"])
        True
        """
        from .loads import motion_counterweight
        return motion_counterweight(self, radius, bodies)

    def __len__(self):
        return len(self.crank_angle)

    def __repr__(self):
        return (f"LooperMotion({len(self)} crank angles {angle_range_text(self.crank_angle)}, branch {self.branch}, "
                f"omega {self.omega:g} rad/s; u2 {angle_range_text(self.rocker_angles[:, 0])}, "
                f"v2 {angle_range_text(self.rocker_angles[:, 1])}; ball |v| max "
                f"{np.max(np.linalg.norm(self.ball_velocity, axis=1)):.6g})")

    @property
    def looper_tip(self):
        """PointMotion of the looper tip (position, velocity, acceleration (N, 3) each, fixed axes)."""
        return self.point(self.drive.looper_link, self.drive.looper_tip)

    def path_bspline(self, which="ball", tol=1e-8):
        """The path of the ball centre ('ball') or the looper tip ('tip') as a C2 quintic B-spline in the crank
        angle (rad), over the requested crank angles' range, within tol times the mechanism's scale (the
        smaller of the torus and sphere sizes) of the path, measured against exact solutions of the drive (the
        distance to the path, at the path's point one Newton step from the spline's angle; at the same crank
        angle the spline and the drive's position may differ by up to about three times as much).

        Built from exact positions and their first and second derivatives in the crank angle (the velocity and
        acceleration at omega = 1) at its knots, refined until the measured distance to the path is below
        0.9 tol x scale (spatialkin.tracing.curve.bspline.fit); periodic when the range is a full turn.

        Returns
        -------
        scipy.interpolate.BSpline
            ``deviation`` (mm, or the drive's length unit) and ``checked`` as in ``Curve.to_bspline``.
        """
        check_choice("which", which, ("ball", "tip"))
        tol = check_positive("tol", tol, strict=True)
        lo, hi = float(np.min(self.crank_angle)), float(np.max(self.crank_angle))
        if not hi > lo:
            raise ValueError("a path B-spline needs at least two distinct crank angles")
        full = hi - lo >= 2 * math.pi * (1 - 1e-12)

        def evaluate(theta):
            m = self.drive.solve(theta, omega=1.0, branch=self.branch)
            if which == "ball":
                return m.ball_center, m.ball_velocity, m.ball_acceleration
            tip = m.looper_tip
            return tip.position, tip.velocity, tip.acceleration

        scale = min(self.drive.torus.size, self.drive.sphere.size)
        return fit_spline(evaluate, lo, lo + 2 * math.pi if full else hi, tol * scale, periodic=full)

    def angular_velocity(self, link):
        """Angular velocity (N, 3) of a link in fixed axes (rad per unit time); ValueError naming `link` when it is
        not one of LINKS."""
        check_choice("link", link, LINKS)
        return self.links()[link].omega

    def angular_acceleration(self, link):
        """Angular acceleration (N, 3) of a link in fixed axes (rad per unit time squared); ValueError naming
        `link` when it is not one of LINKS."""
        check_choice("link", link, LINKS)
        return self.links()[link].alpha


def ranges_of(grid, mask):
    """Contiguous intervals (start, end) of grid values where mask holds (grid uniform and periodic)."""
    if not np.any(mask):
        return []
    step = grid[1] - grid[0]
    out, start = [], None
    for g, m in zip(grid, mask):
        if m and start is None:
            start = g
        if not m and start is not None:
            out.append((start, g - step))
            start = None
    if start is not None:
        out.append((start, grid[-1]))
    return out

