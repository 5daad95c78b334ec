"""Shared pieces of the mechanisms: argument checks and the motion of a point."""
import math
from dataclasses import dataclass

import numpy as np


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


def check_omega(omega):
    """omega as a finite, non-zero float, or ValueError naming it."""
    try:
        value = float(omega)
    except (TypeError, ValueError):
        raise ValueError(f"omega must be a real number (rad per unit time), got {omega!r}") from None
    if not math.isfinite(value) or value == 0:
        raise ValueError(f"omega must be finite and non-zero, got {omega!r}")
    return value


def check_branch(branch):
    if branch not in (0, 1):
        raise ValueError(f"branch must be 0 or 1, got {branch!r}")


def check_drive(crank_angles, omega, branch):
    """Validated crank angles (N,) for solve(crank_angles, omega, branch)."""
    check_branch(branch)
    check_omega(omega)
    return check_angles("crank_angles", crank_angles)


def check_angles(name, values):
    """Angles as a finite 1-D float array (a scalar is one angle), or ValueError naming the argument (also for
    an empty one: a motion has at least one position)."""
    try:
        angles = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be real numbers (radians), got {values!r}") from None
    if angles.ndim != 1 or not np.all(np.isfinite(angles)):
        raise ValueError(f"{name} must be a finite 1-D array")
    if angles.size == 0:
        raise ValueError(f"{name} is empty: give at least one angle")
    return angles
