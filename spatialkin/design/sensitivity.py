"""Exact sensitivities of the looper drive's motion to its design parameters, by the implicit function
theorem on the closure equations, for the whole cycle in one pass.

At a fixed crank angle u1 the ball centre C lies on the torus and on the sphere:

    F(y; u1, p) = M1(u1, v1; p) - M2(u2, v2; p) = 0,   y = (v1, u2, v2),

so y is an implicit function of (u1, p) wherever F_y = [M1_v1, -M2_u2, -M2_v2] is regular (away from the
crank's dead positions and the points where assembly branches meet). Its Taylor coefficients in
(u1, p) follow degree by degree (:mod:`spatialkin.design.jet`): with the unknown coefficients of degree d
set to zero, the degree-d coefficients of F hold everything but F_y times them, so

    y_d = -F_y^{-1} F_d      (d = 1: dy/du1 = -F_y^{-1} F_u1 and dy/dp = -F_y^{-1} F_p),

and the same 3 x 3 matrix (one per crank angle, factorised once) gives dy/du1, d2y/du1^2, dy/dp,
d2y/du1 dp and d3y/du1^2 dp: the sensitivities of positions, velocities and accelerations (the crank
turning at the constant rate omega, d/dt = omega d/du1). Every output below is then computed in the same
arithmetic and carries its exact derivatives.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the closure, torus ∩ sphere. A. Griewank, A. Walther, Evaluating
Derivatives, SIAM 2008, ch. 13 (Taylor arithmetic of implicit functions).
"""
from dataclasses import dataclass, field

import numpy as np

from .jet import Jet, atan2, cross, dot, matvec
from .params import PARAMETERS

#: Taylor orders in the crank angle: value, first and second derivative (velocity, acceleration).
ORDERS = 3
#: Crank angles sampled for the smallest assembly margin (as LooperDrive checks assembly).
ASSEMBLY_SAMPLES = 3600
#: Newton steps refining a rocker turning point (u2' = 0) from the nearest sampled crank angle.
TURNING_NEWTON_STEPS = 3


def parameter_jets(values, free, orders):
    """{name: Jet ()} with eps_k on the k-th free parameter."""
    nfree = len(free)
    return {n: Jet.variable(values[n], orders, nfree, param=(free.index(n) + 1) if n in free else None)
            for n in PARAMETERS}


def rotation_jet(rx, ry, rz):
    """Jet (3, 3) of Rz(rz) Ry(ry) Rx(rx)."""
    cx, sx, cy, sy, cz, sz = rx.cos(), rx.sin(), ry.cos(), ry.sin(), rz.cos(), rz.sin()
    rows = [[cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
            [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
            [-sy, cy * sx, cy * cx]]
    return Jet.stack([Jet.stack(r, axis=-1) for r in rows], axis=-2)


class Closure:
    """The closure equations of one design, evaluated in jet arithmetic.

    Parameters
    ----------
    design : LooperDesign
    free : tuple of str
        Parameters to differentiate by (P of them).
    orders : int
        Taylor orders in the crank angle (3: up to the second derivative).
    """

    def __init__(self, design, free, orders=ORDERS):
        self.design, self.free, self.orders = design, tuple(free), orders
        self.p = parameter_jets(design.values, self.free, orders)
        p = self.p
        self.rocker_rotation = rotation_jet(p["rocker_rx"], p["rocker_ry"], p["rocker_rz"])
        self.rocker_origin = Jet.stack([p["rocker_x"], p["rocker_y"], p["rocker_z"]], axis=-1)
        self.crank_origin = np.asarray(design.crank_frame.origin)
        self.crank_rotation = np.asarray(design.crank_frame.rotation)

    # --- the surfaces ------------------------------------------------------------------------------
    def torus(self, u1, v1):
        """M1 (N, 3) as a jet."""
        p = self.p
        ring = p["crank_radius"] + p["coupler_length"] * v1.cos()
        local = Jet.stack([ring * u1.cos(), ring * u1.sin(), p["coupler_length"] * v1.sin()], axis=-1)
        return matvec(self.crank_rotation, local) + self.crank_origin

    def sphere(self, u2, v2):
        """M2 (N, 3) as a jet."""
        p = self.p
        c = v2.cos()
        local = Jet.stack([c * u2.cos(), c * u2.sin(), v2.sin()], axis=-1) * p["rocker_length"]
        return matvec(self.rocker_rotation, local) + self.rocker_origin

    def jacobian(self, states):
        """F_y (N, 3, 3) at states (N, 4) (plain values)."""
        u1, v1, u2, v2 = states.T
        r1, R2 = self.design.values["coupler_length"], self.design.values["rocker_length"]
        t2 = self.rocker_rotation.value
        m1_v1 = r1 * np.stack([-np.sin(v1) * np.cos(u1), -np.sin(v1) * np.sin(u1), np.cos(v1)], axis=-1)
        m2_u2 = R2 * np.stack([-np.cos(v2) * np.sin(u2), np.cos(v2) * np.cos(u2), np.zeros_like(u2)], axis=-1)
        m2_v2 = R2 * np.stack([-np.sin(v2) * np.cos(u2), -np.sin(v2) * np.sin(u2), np.cos(v2)], axis=-1)
        return np.stack([m1_v1 @ self.crank_rotation.T, -(m2_u2 @ t2.T), -(m2_v2 @ t2.T)], axis=-1)

    def solve(self, states):
        """Jets of (u1, v1, u2, v2) at states (N, 4) on torus ∩ sphere: the implicit function theorem.

        Returns
        -------
        list of 4 Jet (N,)
        """
        states = np.asarray(states, dtype=float)
        orders, nfree = self.orders, len(self.free)
        u1 = Jet.variable(states[:, 0], orders, nfree, t=True)
        y = [Jet.constant(states[:, k], orders, nfree) for k in (1, 2, 3)]
        jac = self.jacobian(states)
        for degree in range(1, orders + 1):
            f = (self.torus(u1, y[0]) - self.sphere(y[1], y[2])).coef       # (N, 3, T, P + 1)
            rhs = np.concatenate([f[:, :, degree, :1] if degree < orders else np.zeros((len(states), 3, 1)),
                                  f[:, :, degree - 1, 1:]], axis=-1)
            step = -np.linalg.solve(jac, rhs)                                  # (N, 3, 1 + P)
            for k in range(3):
                if degree < orders:
                    y[k].coef[:, degree, 0] = step[:, k, 0]
                y[k].coef[:, degree - 1, 1:] = step[:, k, 1:]
        return [u1] + y

    # --- points of the links -----------------------------------------------------------------------
    def looper_tip(self, u2, v2):
        """The looper tip (N, 3) as a jet."""
        p = self.p
        tx, ty, tz = p["tip_x"], p["tip_y"], p["tip_z"]
        if self.design.looper_link == "rocker_arm":
            c, s = v2.cos(), v2.sin()
            w = [c * tx - s * tz, ty + 0.0 * c, s * tx + c * tz]         # Ry(-v2) tip
        else:
            zero = 0.0 * u2
            w = [tx + zero, ty + zero, tz + zero]
        cu, su = u2.cos(), u2.sin()
        local = Jet.stack([cu * w[0] - su * w[1], su * w[0] + cu * w[1], w[2]], axis=-1)   # Rz(u2)
        return matvec(self.rocker_rotation, local) + self.rocker_origin

    def transmission_angle(self, u1, ball):
        """Transmission angle (N,) as a jet (valid to one order fewer in u1 than ball): the angle between C's
        velocity and the normal of the plane of the coupler line and the pin axis (see
        spatialkin.mechanisms.looper.analysis)."""
        p = self.p
        pin = matvec(self.crank_rotation,
                     Jet.stack([u1.cos() * p["crank_radius"], u1.sin() * p["crank_radius"], 0.0 * u1], axis=-1))
        pin = pin + self.crank_origin
        axis = matvec(self.crank_rotation, Jet.stack([u1.sin(), -u1.cos(), 0.0 * u1], axis=-1))
        normal = cross(ball - pin, axis)
        velocity = ball.derivative()
        along = dot(normal, velocity)
        along = along * np.sign(along.value)
        across = dot(cross(normal, velocity), cross(normal, velocity)).sqrt()
        return atan2(across, along)


@dataclass
class Sensitivities:
    """Outputs of a looper design over crank angles and their exact derivatives by the free parameters.

    Every ``d_<output>`` has the output's shape plus a last axis of length P (the free parameters, in the
    order of ``free``). Lengths in the design's unit, angles in radians, time in the unit of 1/omega.

    Attributes
    ----------
    free : tuple of str (P,)
    crank_angles : (N,)
    states : (N, 4)                             (u1, v1, u2, v2)
    ball_center, ball_velocity, ball_acceleration : (N, 3); d_*: (N, 3, P)
    tip, tip_velocity, tip_acceleration : (N, 3); d_*: (N, 3, P)     the looper tip
    rocker_angles, rocker_rates, rocker_accelerations : (N, 2) (u2, v2); d_*: (N, 2, P)
    transmission_angle : (N,); d_transmission_angle : (N, P)
    min_transmission : float, the smallest over the crank angles; d_min_transmission : (P,) (at the argmin)
    turning_points : (K,) crank angles where u2' = 0 (the rocker's dead positions, where it reverses),
        refined by Newton; d_turning_points : (K, P). The crank's own dead positions (a drive that cannot
        turn fully) are LooperDesign.dead_positions().
    turning_u2 : (K,) u2 there; d_turning_u2 : (K, P)
    swing : float, max - min of u2 over the turn (between turning points); d_swing : (P,)
    assembly_margin : float, the smallest assembly margin over a full turn (length; > 0: assemblable at
        every crank angle); d_assembly_margin : (P,)
    """
    free: tuple
    omega: float
    crank_angles: np.ndarray
    states: np.ndarray
    ball_center: np.ndarray
    d_ball_center: np.ndarray
    ball_velocity: np.ndarray
    d_ball_velocity: np.ndarray
    ball_acceleration: np.ndarray
    d_ball_acceleration: np.ndarray
    tip: np.ndarray
    d_tip: np.ndarray
    tip_velocity: np.ndarray
    d_tip_velocity: np.ndarray
    tip_acceleration: np.ndarray
    d_tip_acceleration: np.ndarray
    rocker_angles: np.ndarray
    d_rocker_angles: np.ndarray
    rocker_rates: np.ndarray
    d_rocker_rates: np.ndarray
    rocker_accelerations: np.ndarray
    d_rocker_accelerations: np.ndarray
    transmission_angle: np.ndarray
    d_transmission_angle: np.ndarray
    min_transmission: float = float("nan")
    d_min_transmission: np.ndarray = field(default=None)
    turning_points: np.ndarray = field(default=None)
    d_turning_points: np.ndarray = field(default=None)
    turning_u2: np.ndarray = field(default=None)
    d_turning_u2: np.ndarray = field(default=None)
    swing: float = float("nan")
    d_swing: np.ndarray = field(default=None)
    assembly_margin: float = float("nan")
    d_assembly_margin: np.ndarray = field(default=None)

    def jacobian(self, name):
        """d_<name>, the derivative array of an output (its shape + (P,))."""
        return getattr(self, "d_" + name)


def kinematic_outputs(closure, states, omega):
    """Position, velocity, acceleration outputs and their parameter derivatives at states (N, 4)."""
    u1, v1, u2, v2 = closure.solve(states)
    ball = closure.torus(u1, v1)
    tip = closure.looper_tip(u2, v2)
    rocker = Jet.stack([u2, v2], axis=-1)
    mu = closure.transmission_angle(u1, ball)
    out = {}
    for name, jet in (("ball", ball), ("tip", tip), ("rocker", rocker)):
        for k, suffix in enumerate(("position", "velocity", "acceleration")):
            out[(name, suffix)] = (omega ** k * jet.d_du(k), omega ** k * jet.d_dp(k))
    out["mu"] = (mu.d_du(0), mu.d_dp(0))
    out["jets"] = (u1, v1, u2, v2)
    return out


def sensitivities(design, crank_angles, omega=1.0, free=None, turning=True):
    """Sensitivities of a LooperDesign's outputs at the given crank angles (one drive.solve, one pass).

    Parameters
    ----------
    design : LooperDesign
    crank_angles : array_like (N,)
        Crank angles (rad). With turning=True they must increase and should sample a full turn: the swing,
        the turning points (refined by Newton) and the smallest transmission angle are taken over them.
    omega : float
        Crank rate (rad per unit time).
    free : tuple of str, optional
        Parameters to differentiate by; default design.free.
    turning : bool
        Refine the rocker's turning points, swing and assembly margin.

    Returns
    -------
    Sensitivities

    Raises
    ------
    ValueError
        For crank angles that do not increase (turning=True), crank angles where the drive cannot be assembled
        (LooperDrive.solve), or Newton failing at a turning point of the rocker.
    """
    free = design.free if free is None else free
    drive = design.drive()
    angles = np.atleast_1d(np.asarray(crank_angles, dtype=float))
    if turning and (angles.ndim != 1 or len(angles) < 3 or np.any(np.diff(angles) <= 0)):
        raise ValueError("crank_angles must increase (at least 3, over a full turn) to find the turning points; "
                         "pass turning=False for arbitrary angles")
    motion = drive.solve(angles, omega=omega, branch=design.branch)
    closure = Closure(design, free)
    out = kinematic_outputs(closure, motion.states, omega)
    mu, d_mu = out["mu"]
    k = int(np.argmin(mu))
    kw = dict(free=tuple(free), omega=float(omega), crank_angles=angles, states=motion.states,
              transmission_angle=mu, d_transmission_angle=d_mu,
              min_transmission=float(mu[k]), d_min_transmission=d_mu[k])
    names = {"ball": ("ball_center", "ball_velocity", "ball_acceleration"),
             "tip": ("tip", "tip_velocity", "tip_acceleration"),
             "rocker": ("rocker_angles", "rocker_rates", "rocker_accelerations")}
    for link, triple in names.items():
        for suffix, name in zip(("position", "velocity", "acceleration"), triple):
            kw[name], kw["d_" + name] = out[(link, suffix)]
    if turning:
        kw.update(turning_outputs(drive, closure, out["jets"]))
        kw.update(margin_outputs(closure))
    return Sensitivities(**kw)


def turning_outputs(drive, closure, jets):
    """The rocker's turning points (u2' = 0, its dead positions), each refined by Newton from the sampled
    crank angles, with the swing between them. The derivative of a turning point's crank angle is
    -d(u2')/dp / u2''; that of u2 there is du2/dp (u2' = 0: the envelope theorem).

    jets: the jets (u1, v1, u2, v2) (N,) of a full turn of samples in increasing crank angle."""
    u2 = jets[2]
    rate = u2.d_du(1)
    nfree = len(closure.free)
    # sign changes between consecutive samples where the rate is not exactly zero; a sample where it is (a
    # turning point right on a sample, as a fit to a target timing puts it) lies inside such a bracket
    nz = np.nonzero(rate)[0]
    j = np.nonzero(rate[nz[:-1]] * rate[nz[1:]] < 0)[0]
    if not len(j):
        empty = np.empty((0, nfree))
        return dict(turning_points=np.empty(0), d_turning_points=empty, turning_u2=np.empty(0),
                    d_turning_u2=empty, swing=float("nan"), d_swing=np.full(nfree, np.nan))
    near = np.array([a + int(np.argmin(np.abs(rate[a:b + 1]))) for a, b in zip(nz[j], nz[j + 1])])
    ys = np.stack([j.value[near] for j in jets], axis=-1)
    tangent = np.stack([j.d_du(1)[near] for j in jets], axis=-1)
    curvature = np.stack([j.d_du(2)[near] for j in jets], axis=-1)
    step = -u2.d_du(1)[near] / u2.d_du(2)[near]
    for _ in range(TURNING_NEWTON_STEPS):
        # second-order prediction along the curve, then Newton at the fixed crank angle onto torus ∩ sphere
        predicted = ys + tangent * step[:, None] + 0.5 * curvature * (step ** 2)[:, None]
        states = drive._at_crank_angles(predicted)     # the drive's own Newton at fixed u1 (jitted kernel)
        if states is None:
            raise ValueError("Newton at fixed crank angle failed at a turning point of the rocker")
        jet = closure.solve(states)
        ys = states
        tangent = np.stack([j.d_du(1) for j in jet], axis=-1)
        curvature = np.stack([j.d_du(2) for j in jet], axis=-1)
        step = -jet[2].d_du(1) / jet[2].d_du(2)
    u2 = jet[2]
    d_phi = -u2.d_dp(1) / u2.d_du(2)[:, None]
    value, d_value = u2.d_du(0), u2.d_dp(0)
    hi, lo = int(np.argmax(value)), int(np.argmin(value))
    return dict(turning_points=ys[:, 0], d_turning_points=d_phi, turning_u2=value, d_turning_u2=d_value,
                swing=float(value[hi] - value[lo]), d_swing=d_value[hi] - d_value[lo])


def margin_jet(closure, u1):
    """The assembly margin (see LooperDrive.assembly_margin) at crank angles u1 (a Jet (N,)) as a jet: how far
    the rocker length lies inside the range of distances from the rocker centre to the coupler's circle."""
    p = closure.p
    rel_origin = Jet.stack([p["rocker_x"], p["rocker_y"], p["rocker_z"]], axis=-1) - closure.crank_origin
    q = matvec(closure.crank_rotation.T, rel_origin)                        # rocker centre, crank frame
    c, s = u1.cos(), u1.sin()
    zero = 0.0 * u1
    radial = Jet.stack([c, s, zero], axis=-1)
    axis = Jet.stack([-s, c, zero], axis=-1)
    rel = Jet(q.coef[None]) - radial * Jet(p["crank_radius"].coef[None])
    h = dot(rel, axis)
    inplane_vec = rel - axis * Jet(h.coef[:, None])
    inplane = dot(inplane_vec, inplane_vec).sqrt()
    r1, R2 = p["coupler_length"], p["rocker_length"]
    d_min = ((inplane - r1) * (inplane - r1) + h * h).sqrt()
    d_max = ((inplane + r1) * (inplane + r1) + h * h).sqrt()
    a, b = R2 - d_min, d_max - R2
    return Jet(np.where((a.value < b.value)[:, None, None], a.coef, b.coef))


def margin_outputs(closure, samples=ASSEMBLY_SAMPLES):
    """The smallest assembly margin over a full turn and its derivative (taken at the sampled argmin)."""
    plain = Closure(closure.design, closure.free, orders=1)
    u1 = Jet.constant(np.linspace(0.0, 2 * np.pi, samples, endpoint=False), 1, len(closure.free))
    margin = margin_jet(plain, u1)
    k = int(np.argmin(margin.value))
    return dict(assembly_margin=float(margin.value[k]), d_assembly_margin=margin.d_dp(0)[k])


def dead_positions(design, free=None):
    """The crank's dead positions of a drive that cannot turn fully, with their exact derivatives.

    There the coupler's circle touches the rocker sphere (the assembly margin m(u1, p) is zero, the two
    assembly branches meet and the crank reverses): the ends of LooperDrive.blocked_ranges. By the implicit
    function theorem on m(u1*, p) = 0, du1*/dp = -m_p / m_u1.

    Parameters
    ----------
    design : LooperDesign
    free : tuple of str, optional
        Parameters to differentiate by; default design.free.

    Returns
    -------
    angles : (K,) crank angles (rad, in [0, 2 pi)); empty when the crank turns fully
    d_angles : (K, P)
    """
    free = design.free if free is None else tuple(free)
    edges = np.array([a for pair in design.drive().blocked_ranges for a in pair], dtype=float)
    closure = Closure(design, free, orders=2)
    if not len(edges):
        return edges, np.empty((0, len(free)))
    margin = margin_jet(closure, Jet.variable(edges, 2, len(free), t=True))
    return edges, -margin.d_dp(0) / margin.d_du(1)[:, None]
