"""What a designer needs to know about a looper drive: does the crank turn fully, where are its dead
positions and the points where assembly branches meet, how far does the rocker swing, how well is force
transmitted over the cycle."""
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ...kernels.march import curve as kc
from ...tracing.curve.status import SINGULAR

#: Samples per traced loop when looking for dead positions.
LOOP_SAMPLES = 4096
#: Crank angles whose assembly margin is below this (relative to the size) are left out of the analysis of
#: a crank that cannot turn fully: there the two branches are about to merge.
CLEARANCE = 1e-3


@dataclass
class LooperAnalysis:
    """Angles in radians.

    turns_fully : the crank can turn all round on this branch (no blocked crank angles, u1' keeps its sign)
    dead_positions : crank angles where u1' = 0 on a traced loop (the crank's extreme positions)
    branch_points : crank angles where torus and sphere are tangent (N1 || N2): assembly branches meet
    blocked_ranges : crank-angle intervals where the mechanism cannot be assembled
    u2_range, v2_range : (min, max) of the rocker angles at the analysed crank angles (``samples`` of the turn,
        or a given motion's; spatialkin.design.LooperDesign.sensitivities gives the swing's exact extremes)
    transmission_angle : (N,) 90 deg minus the pressure angle at C. The coupler (revolute at the pin,
        ball at C) can push C only with forces in the plane of the coupler line and the pin axis (their
        moment about the pin axis must vanish); the pressure angle is the angle between C's velocity and
        that plane. 90 deg is ideal, 0 means the coupler cannot drive C at all.
    min_transmission : (value, crank angle) of the smallest transmission angle
    """
    turns_fully: bool
    dead_positions: list
    branch_points: list
    blocked_ranges: list
    u2_range: tuple
    v2_range: tuple
    crank_angles: np.ndarray = field(repr=False)
    transmission_angle: np.ndarray = field(repr=False)
    min_transmission: tuple = (0.0, 0.0)

    def __repr__(self):
        deg = np.degrees
        angles = lambda xs: "[" + ", ".join(f"{deg(x):.4f}" for x in xs) + "]"      # noqa: E731
        return (f"LooperAnalysis(turns_fully={self.turns_fully}, dead_positions={angles(self.dead_positions)} deg, "
                f"branch_points={angles(self.branch_points)} deg, blocked_ranges="
                f"[{', '.join(angles(r) for r in self.blocked_ranges)}] deg, "
                f"u2_range={angles(self.u2_range)} deg, v2_range={angles(self.v2_range)} deg, "
                f"min_transmission={deg(self.min_transmission[0]):.3f} deg at {deg(self.min_transmission[1]):.2f} deg)")


def crank_rates(drive, ys):
    """u1' (N,) along torus ∩ sphere at the states ys (N, 4) (NaN where the curve's frame is singular)."""
    ys = np.ascontiguousarray(ys, dtype=float)
    n = len(ys)
    dy, ddy, d1, d2 = np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 3)), np.empty((n, 3))
    ok = np.zeros(n, dtype=np.bool_)
    kc.curve_derivatives_many(ys, drive.torus.data, drive.sphere.data, 1.0, dy, ddy, d1, d2, ok)
    return np.where(ok, dy[:, 0], np.nan)


def dead_positions(drive):
    """Crank angles where u1' changes sign along any traced loop of torus ∩ sphere: each sign change between
    LOOP_SAMPLES samples solved for its arc length by Brent's method, the crank angle read there (stationary in s,
    so exact to the round-off)."""
    out = []
    for c in drive.loops():
        if c.length == 0:
            continue
        s = np.linspace(0.0, c.length, LOOP_SAMPLES)
        rate = crank_rates(drive, c.parameters(s))
        for i in np.nonzero(rate[:-1] * rate[1:] < 0)[0]:
            root = brentq(lambda x: float(crank_rates(drive, c.parameters(np.array([x])))[0]), s[i], s[i + 1],
                          xtol=1e-15 * max(c.length, 1.0), rtol=4.0 * np.finfo(float).eps)
            out.append(float(np.mod(c.parameters(np.array([root]))[0, 0], 2 * np.pi)))
    return sorted(out)


def branch_points(drive):
    """Crank angles at the ends of traced loops that stop at a singular point (N1 || N2)."""
    out = []
    for c in drive.loops():
        if c.status == SINGULAR:
            out += [float(np.mod(c.params[k, 0], 2 * np.pi)) for k in (0, -1)]
    return sorted(out)


def clear_all_round(drive, samples=3601):
    """True when the coupler's circle crosses the rocker sphere transversally at every crank angle (assembly
    margin above CLEARANCE x size all round). Then the two assemblies are smooth functions of the crank angle:
    a dead position (u1' = 0) or a branch point (N1 || N2) needs the circle tangent to the sphere, where the
    distance from the rocker centre along the circle is extreme, that is a zero margin. So neither exists
    and no loop needs tracing to show it."""
    angles = np.linspace(0.0, 2 * np.pi, samples)
    return bool(np.min(drive.assembly_margin(angles)) > CLEARANCE * drive.size)


#: Most crank angles of a turn analysed (a step of 3.6e-5 degrees).
ANALYSIS_SAMPLES_MAX = 10_000_001


def analyse(drive, branch=0, samples=3601, motion=None):
    """LooperAnalysis of a LooperDrive on one branch; the transmission angle over `samples` crank angles of a
    turn (those clear of the blocked ranges), or over the crank angles of a given motion of this drive and
    branch (reused, not solved again)."""
    blocked = drive.blocked_ranges
    if not blocked and clear_all_round(drive, samples):
        dead, meets = [], []        # nothing to find: the loops (sk.intersect) are not traced
    else:
        dead = dead_positions(drive)
        meets = branch_points(drive)
    turns = not blocked and not dead
    if motion is None:
        angles = np.linspace(0.0, 2 * np.pi, samples)
        if not turns:       # keep clear of the blocked ranges, where the two branches merge
            angles = angles[drive.assembly_margin(angles) > CLEARANCE * drive.size]
        motion = drive.solve(angles, branch=branch)
    elif motion.drive is not drive or motion.branch != branch:
        raise ValueError("motion must be a motion of this drive on the analysed branch")
    angles = motion.crank_angle
    coupler = motion.links()["coupler"]
    line = motion.ball_center - coupler.origin
    pin_axis = coupler.rotation[:, :, 1]
    normal = np.cross(line, pin_axis)
    vel = motion.ball_velocity
    sin = np.abs(np.einsum("ij,ij->i", normal, vel)) / (np.linalg.norm(normal, axis=1) * np.linalg.norm(vel, axis=1))
    mu = np.pi / 2 - np.arcsin(np.clip(sin, 0.0, 1.0))
    k = int(np.argmin(mu))
    u2, v2 = motion.rocker_angles.T
    return LooperAnalysis(turns_fully=turns, dead_positions=dead, branch_points=meets, blocked_ranges=blocked,
                          u2_range=(float(u2.min()), float(u2.max())), v2_range=(float(v2.min()), float(v2.max())),
                          crank_angles=angles, transmission_angle=mu,
                          min_transmission=(float(mu[k]), float(angles[k])))
