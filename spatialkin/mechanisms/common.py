"""Shared pieces of the mechanisms: argument checks and the motion of a point."""
import math
from dataclasses import dataclass

import numpy as np


@dataclass
class PointMotion:
    """Position, velocity and acceleration (N, 3) of a point of a link, in fixed axes."""
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


def check_branch(branch):
    if branch not in (0, 1):
        raise ValueError(f"branch must be 0 or 1, got {branch!r}")


def check_drive(crank_angles, omega, branch):
    """Validated crank angles (N,) for solve(crank_angles, omega, branch)."""
    check_branch(branch)
    angles = np.atleast_1d(np.asarray(crank_angles, dtype=float))
    if angles.ndim != 1 or not np.all(np.isfinite(angles)):
        raise ValueError("crank_angles must be a finite 1-D array")
    if not math.isfinite(omega) or omega == 0:
        raise ValueError(f"omega must be finite and non-zero, got {omega!r}")
    return angles
