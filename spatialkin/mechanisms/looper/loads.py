"""Forces in the looper drive over its cycle: the crank torque, every joint's load and the shaking force and
moment, by Newton-Euler on its four moving links (spatialkin.dynamics).

The joints of the R-R-S-R-R chain, each named by what it is:

- ``crank_bearing``: frame - crank, revolute about the crank shaft, driven (the crank torque);
- ``crank_pin``: crank - coupler, revolute about the crank pin;
- ``ball``: coupler - rocker arm, spherical at the ball centre C (no moment);
- ``rocker_hinge``: rocker shaft - rocker arm, revolute about the arm's hinge;
- ``rocker_bearing``: frame - rocker shaft, revolute about the rocker shaft.

Units: kg, the drive's length unit L (mm for the reference drive) and s, with the crank rate omega in rad/s:
forces in kg L / s^2 (mN for mm), moments and torques in kg L^2 / s^2 (uN m for mm).
"""
import numpy as np

from ...dynamics import DRIVEN, REVOLUTE, SPHERICAL, Joint, inverse_dynamics
from ...dynamics.balance import counterweight
from ...dynamics.body import check_bodies
from ..._lib.validation import as_float_array

#: The drive's moving links (the keys of `bodies`).
LINKS = ("crank", "coupler", "rocker_shaft", "rocker_arm")
#: The joints' names, in the order of the chain.
JOINTS = ("crank_bearing", "crank_pin", "ball", "rocker_hinge", "rocker_bearing")


def drive_joints(motion):
    """The drive's joints (spatialkin.dynamics.Joint) at the motion's crank angles."""
    links = motion.links()
    crank, coupler, shaft, arm = (links[name] for name in LINKS)
    return [Joint("crank_bearing", None, "crank", DRIVEN, crank.origin, crank.rotation[:, :, 2]),
            Joint("crank_pin", "crank", "coupler", REVOLUTE, coupler.origin, -coupler.rotation[:, :, 1]),
            Joint("ball", "coupler", "rocker_arm", SPHERICAL, motion.ball_center),
            Joint("rocker_hinge", "rocker_shaft", "rocker_arm", REVOLUTE, arm.origin, -arm.rotation[:, :, 1]),
            Joint("rocker_bearing", None, "rocker_shaft", REVOLUTE, shaft.origin, shaft.rotation[:, :, 2])]


def motion_loads(motion, bodies=None, gravity=None, external=None):
    """The loads of a LooperMotion (see LooperMotion.loads): spatialkin.dynamics.Loads with ``crank_torque``."""
    bodies = check_bodies(bodies, LINKS)
    if gravity is not None:
        gravity = as_float_array("gravity", gravity)
        if gravity.shape != (3,) or not np.all(np.isfinite(gravity)):
            raise ValueError(f"gravity must be 3 finite numbers (L / s^2, fixed axes), got {gravity.tolist()}")
    loads_on = None
    if external is not None:
        if not callable(external):
            raise ValueError("external must be a function of the crank angles (N,) returning (force (N, 3), "
                             "moment (N, 3)) on the looper link")
        force, moment = (np.broadcast_to(np.asarray(x, dtype=float), (len(motion), 3))
                         for x in external(motion.crank_angle))
        if not (np.all(np.isfinite(force)) and np.all(np.isfinite(moment))):
            raise ValueError("external returned values that are not finite")
        loads_on = {motion.drive.looper_link: (force, motion.looper_tip.position, moment)}
    loads = inverse_dynamics(motion.links(), drive_joints(motion), bodies, gravity, loads_on)
    loads.crank_torque = loads.torque["crank_bearing"]
    return loads


def motion_counterweight(motion, radius, bodies=None):
    """The crank counterweight of least RMS shaking force (see LooperMotion.counterweight)."""
    return counterweight(lambda given: motion_loads(motion, given), bodies, "crank",
                         motion.links()["crank"].rotation[:, :, :2], motion.omega, radius,
                         lambda loads: loads.crank_torque)


#: Each joint's load as a designer draws it: the two components (in its child link's axes) normal to the joint's
#: axis (the ball joint: in the rocker arm's plane of motion, normal to its hinge).
BEARING_PLANES = {"crank_bearing": (0, 1), "crank_pin": (0, 2), "ball": (0, 2), "rocker_hinge": (0, 2),
                  "rocker_bearing": (0, 1)}
