"""Shared pieces of the mechanisms: argument checks and the motion of a point."""
import math
from dataclasses import dataclass

import numpy as np

from .._lib.validation import check_angles, check_choice, check_omega


@dataclass(repr=False)
class PointMotion:
    """Position, velocity and acceleration (N, 3) of a point of a link, in fixed axes."""
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray

    def __repr__(self):
        speed = np.max(np.linalg.norm(self.velocity, axis=-1))
        return (f"PointMotion({len(self.position)} positions, |v| max {speed:.6g}, "
                f"|a| max {np.max(np.linalg.norm(self.acceleration, axis=-1)):.6g})")


def angle_range_text(values):
    """'a..b deg' of angles in radians (for reprs)."""
    values = np.asarray(values, dtype=float)
    if values.size == 0:
        return "none"
    return f"{math.degrees(float(values.min())):.6g}..{math.degrees(float(values.max())):.6g} deg"


def check_branch(branch):
    """The assembly branch, 0 or 1, or ValueError naming it."""
    return check_choice("branch", branch, (0, 1))


def check_drive(crank_angles, omega, branch):
    """(crank angles (N,), omega, branch) of solve(crank_angles, omega, branch), validated (branch as the int 0 or
    1)."""
    branch = check_branch(branch)
    omega = check_omega(omega)
    return check_angles("crank_angles", crank_angles), omega, branch
