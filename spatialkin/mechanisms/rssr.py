"""The classic spatial four-link crank-rocker RSSR (the mechanism [Looper] starts from), through the same pipeline:
the configuration curve F(phi, psi) = |C(psi) - B(phi)|^2 - L^2 = 0 traced once by arc length (solve_ivp on
a jitted right-hand side), re-parametrised by the crank angle, differentiated analytically, mapped to time
by the trajectory pipeline and to the links by the serial-chain propagation.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the RSSR as sphere ∩ sphere ∩ circle.
"""
import math

import numpy as np

from ..geometry.frame import Frame
from ..kernels.mechanisms import rssr as kl
from ..motion.kinematics import serial_chain
from ..continuation import CurveKernels, solve_at, trace_cycle
from ..motion.trajectory import time_map, to_time
from .._lib.validation import check_positive
from .common import PointMotion, angle_range_text, check_branch, check_drive

#: solve_ivp tolerance and method of the configuration-curve trace (a predictor: positions are solved by Newton).
TRACE_RTOL = 1e-10
TRACE_METHOD = "DOP853"
#: Arc-length budget of the configuration curve per radian of crank angle (the curve is bounded).
LENGTH_BUDGET = 1e3
#: Samples of the rocker angle when assembling at the first crank angle.
ASSEMBLY_SAMPLES = 720
#: Newton tolerance on F (length^2) relative to the mechanism size squared.
RESIDUAL_TOL = 1e-15
_Z = (0.0, 0.0, 1.0)


def rssr_kernels():
    """The RSSR's configuration-curve kernels (read when used: spatialkin._lib.jit may switch their form)."""
    return CurveKernels(kl.implicit_curve_rhs, kl.rssr_events, kl.rssr_advance)


class RSSR:
    """Spatial crank-rocker: crank (revolute about the crank frame's z), coupler with ball joints at both
    ends, rocker (revolute about the rocker frame's z).

    Parameters
    ----------
    crank_radius, coupler_length, rocker_radius : float
        a = |O1 B|, L = |B C|, c = |O2 C|.
    crank_frame, rocker_frame : Frame
        Origins on the axes, local z along them; angles phi, psi measured from local x.
    """

    def __init__(self, crank_radius, coupler_length, rocker_radius, crank_frame=None, rocker_frame=None):
        self.crank_radius = check_positive("crank_radius", crank_radius)
        self.coupler_length = check_positive("coupler_length", coupler_length)
        self.rocker_radius = check_positive("rocker_radius", rocker_radius)
        self.crank_frame = crank_frame if crank_frame is not None else Frame()
        self.rocker_frame = rocker_frame if rocker_frame is not None else Frame()
        p = np.zeros(kl.PARAMS_SIZE)
        p[kl.O1:kl.O1 + 3] = self.crank_frame.origin
        p[kl.T1:kl.T1 + 9] = self.crank_frame.rotation.ravel()
        p[kl.A] = self.crank_radius
        p[kl.O2:kl.O2 + 3] = self.rocker_frame.origin
        p[kl.T2:kl.T2 + 9] = self.rocker_frame.rotation.ravel()
        p[kl.C] = self.rocker_radius
        p[kl.L] = self.coupler_length
        self.params = p
        self.size = self.crank_radius + self.coupler_length + self.rocker_radius
        self._cycles = {}

    def __repr__(self):
        return (f"RSSR(crank_radius={self.crank_radius:g}, coupler_length={self.coupler_length:g}, "
                f"rocker_radius={self.rocker_radius:g}, crank_frame={self.crank_frame!r}, "
                f"rocker_frame={self.rocker_frame!r})")

    def residual(self, phi, psi):
        """F and its gradient (2,) at one (phi, psi)."""
        grad, hess = np.empty(2), np.empty((2, 2))
        f = kl.rssr_residual(self.params, np.array([phi, psi], dtype=float), grad, hess)
        return f, grad

    def assemble(self, phi, branch=0):
        """(phi, psi) on the branch (0: |C - B| grows with psi) by sampling psi and Newton."""
        branch = check_branch(branch)
        psi = np.linspace(-np.pi, np.pi, ASSEMBLY_SAMPLES + 1)
        f = np.array([self.residual(phi, q)[0] for q in psi])
        for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]:
            x = self._newton(np.array([[phi, psi[i]]]))
            if x is not None and self.branch_of(x)[0] == branch:
                return x[0]
        raise ValueError(f"the RSSR cannot be assembled on branch {branch} at crank angle "
                         f"{math.degrees(phi):.6g} deg: the coupler sphere misses the rocker circle")

    def branch_of(self, xs):
        xs = np.asarray(xs, dtype=float).reshape(-1, 2)
        return np.array([0 if self.residual(*x)[1][1] > 0 else 1 for x in xs])

    def _newton(self, xs):
        xs = np.ascontiguousarray(xs, dtype=float)
        ok = np.zeros(len(xs), dtype=np.bool_)
        kl.newton_psi(self.params, xs, RESIDUAL_TOL * self.size ** 2, 50, ok)
        return xs if np.all(ok) else None

    def cycle(self, branch=0):
        """The configuration curve over one crank turn, traced by arc length (a continuation Cycle)."""
        if branch not in self._cycles:
            x0 = self.assemble(0.0, branch)
            cycle = trace_cycle(rssr_kernels(), x0, (self.params,), 2 * np.pi,
                                LENGTH_BUDGET * 2 * np.pi, index=0, rtol=TRACE_RTOL, method=TRACE_METHOD)
            if cycle.locks:
                raise ValueError("the crank of this RSSR cannot turn fully: dead position at crank angle "
                                 f"{math.degrees(cycle.locks[0][0]):.6g} deg")
            self._cycles[branch] = cycle
        return self._cycles[branch]

    def solve(self, crank_angles, omega=1.0, branch=0):
        """Motion at exactly the given crank angles; see RSSRMotion."""
        phi, omega, branch = check_drive(crank_angles, omega, branch)
        inputs, path = self.cycle(branch).branch_samples()
        xs, = solve_at(phi, inputs, path, self._correct, index=0, period=2 * np.pi)
        return RSSRMotion(self, xs, 1.0, omega)

    def _correct(self, guess):
        """(states,): Newton at fixed crank angle from the predictions (solve_at's corrector)."""
        xs = self._newton(guess)
        if xs is None:
            raise ValueError("Newton at fixed crank angle failed")
        return (xs,)


class RSSRMotion:
    def __len__(self):
        return len(self.crank_angle)

    def __repr__(self):
        return (f"RSSRMotion({len(self)} crank angles {angle_range_text(self.crank_angle)}, omega {self.omega:g}; "
                f"rocker {angle_range_text(self.rocker_angle)})")

    """RSSR motion at given crank angles: crank_angle, rocker_angle, rocker_rate, rocker_acceleration (N,),
    crank_pin and ball_center (PointMotion, fixed axes)."""

    def __init__(self, mech, xs, sign, omega):
        n = len(xs)
        d1, d2 = np.empty((n, 2)), np.empty((n, 2))
        ok = np.zeros(n, dtype=np.bool_)
        kl.implicit_curve_derivatives(mech.params, xs, sign, d1, d2, ok)
        sdot, sddot = time_map(d1[:, 0], d2[:, 0], omega)
        rates, accels = to_time(d1, d2, sdot, sddot)
        self.omega = float(omega)
        self.crank_angle, self.rocker_angle = xs[:, 0], xs[:, 1]
        self.rocker_rate, self.rocker_acceleration = rates[:, 1], accels[:, 1]
        crank, = serial_chain(mech.crank_frame.origin, mech.crank_frame.rotation, [((0, 0, 0), _Z)],
                              xs[:, :1], rates[:, :1], accels[:, :1])
        rocker, = serial_chain(mech.rocker_frame.origin, mech.rocker_frame.rotation, [((0, 0, 0), _Z)],
                               xs[:, 1:], rates[:, 1:], accels[:, 1:])
        self.crank_pin = PointMotion(*crank.point((mech.crank_radius, 0, 0)))
        self.ball_center = PointMotion(*rocker.point((mech.rocker_radius, 0, 0)))
