"""Frames: an origin and a proper rotation that place a surface or a link in global coordinates."""
import numpy as np

from .validation import check_frame, check_real, check_vector
from .vectors import cross


def rotation_about(axis, angle):
    """Rotation matrix (3, 3) by angle (radians) about axis (3,), right-hand rule (Rodrigues)."""
    k = check_vector("axis", axis)
    n = np.linalg.norm(k)
    if n == 0:
        raise ValueError("axis must be a non-zero vector")
    check_real("angle", angle, finite=True)
    k = k / n
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * (kx @ kx)


def rotation_to_z(z_axis):
    """A rotation whose third column is the unit vector along z_axis (the first two completed
    deterministically)."""
    z = check_vector("z_axis", z_axis)
    n = np.linalg.norm(z)
    if n == 0:
        raise ValueError("z_axis must be a non-zero vector")
    z = z / n
    helper = np.eye(3)[np.argmin(np.abs(z))]
    x = cross(helper, z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, cross(z, x), z])


class Frame:
    """A placement: global = origin + rotation @ local.

    Parameters
    ----------
    origin : array_like (3,)
        Position of the local origin in global coordinates.
    rotation : array_like (3, 3)
        Proper rotation; its columns are the local x, y, z axes in global coordinates.

    Raises
    ------
    ValueError
        For non-finite entries, wrong shapes, a non-orthonormal or a left-handed rotation.
    """

    __slots__ = ("origin", "rotation")

    def __init__(self, origin=(0.0, 0.0, 0.0), rotation=None):
        origin, rot = check_frame(origin, np.eye(3) if rotation is None else rotation)
        origin.flags.writeable = False
        rot.flags.writeable = False
        self.origin = origin
        self.rotation = rot

    @classmethod
    def from_z_axis(cls, origin, z_axis):
        """A frame at origin whose local z points along z_axis."""
        return cls(origin, rotation_to_z(z_axis))

    def to_global(self, local_points):
        """Map local points (..., 3) to global coordinates."""
        return self.origin + np.asarray(local_points, dtype=float) @ self.rotation.T

    def to_local(self, points):
        """Map global points (..., 3) to local coordinates."""
        return (np.asarray(points, dtype=float) - self.origin) @ self.rotation

    def __repr__(self):
        return f"Frame(origin={self.origin.tolist()}, rotation={self.rotation.tolist()})"
