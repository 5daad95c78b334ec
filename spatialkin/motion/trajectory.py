"""Layer 3: the trajectory pipeline - a point (or any quantity) moving along a curve parametrised by s.

A mechanism's motion is known along a curve in its own parameter s (arc length of an intersection curve,
the arc length of a crank pin's circle, ...): each quantity q comes with its s-derivatives q' and q''.
A driver coordinate (the crank angle) turning at a constant rate omega fixes the map from s to time:

    ds/dt = omega / phi'(s),        d2s/dt2 = -omega^2 phi''(s) / phi'(s)^3

and then dq/dt = q' ds/dt, d2q/dt2 = q'' (ds/dt)^2 + q' d2s/dt2. Spatial mechanisms and the planar module
both produce and consume this.
"""
import numpy as np

__all__ = ["Trajectory", "time_map", "to_time"]


def time_map(driver_d1, driver_d2, omega):
    """(ds/dt, d2s/dt2) (N,) for a driver coordinate with s-derivatives driver_d1, driver_d2 (N,) turning at
    the constant rate omega. Infinite where driver_d1 = 0 (a dead position of the driver)."""
    d1 = np.asarray(driver_d1, dtype=float)
    d2 = np.asarray(driver_d2, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        sdot = omega / d1
        sddot = -(omega ** 2) * d2 / d1 ** 3
    return sdot, sddot


def to_time(d1, d2, sdot, sddot):
    """Time derivatives (first, second) of a quantity from its s-derivatives d1, d2: shaped like sdot
    (scalars) or like sdot plus a trailing vector axis."""
    d1 = np.asarray(d1, dtype=float)
    d2 = np.asarray(d2, dtype=float)
    sd, sdd = np.asarray(sdot, dtype=float), np.asarray(sddot, dtype=float)
    if d1.ndim > sd.ndim:          # vector quantities (..., k): one s-rate per point
        sd, sdd = sd[..., None], sdd[..., None]
    return d1 * sd, d2 * sd ** 2 + d1 * sdd


class Trajectory:
    """A point moving along a curve: position (N, k) and its s-derivatives, with the map from s to time.

    Attributes
    ----------
    position, d1, d2 : ndarray (N, k)
        The point and its first and second derivatives in s.
    sdot, sddot : ndarray (N,)
        ds/dt and d2s/dt2.
    """

    def __init__(self, position, d1, d2, sdot, sddot):
        self.position = np.asarray(position, dtype=float)
        self.d1 = np.asarray(d1, dtype=float)
        self.d2 = np.asarray(d2, dtype=float)
        self.sdot = np.asarray(sdot, dtype=float)
        self.sddot = np.asarray(sddot, dtype=float)
        self.velocity, self.acceleration = to_time(self.d1, self.d2, self.sdot, self.sddot)

    def __len__(self):
        return len(self.position)

    def __repr__(self):
        return (f"Trajectory({len(self)} points in {self.position.shape[-1]}-D, speed "
                f"{self.speed.min():.6g}..{self.speed.max():.6g})")

    @property
    def speed(self):
        return np.linalg.norm(self.velocity, axis=-1)

    @property
    def acceleration_magnitude(self):
        return np.linalg.norm(self.acceleration, axis=-1)
