"""Frames: an origin and a proper rotation that place a surface or a link in global coordinates."""
import math

import numpy as np

from .._lib.validation import check_frame, check_point_array, check_real, check_vector
from .vectors import cross


def unit(name, vector):
    """The unit vector (3,) along a finite non-zero 3-vector of any length, or ValueError (TypeError) naming it: the
    vector is first scaled by a power of two that brings its largest entry into [1, 2) (exact), so that its norm
    neither overflows nor underflows."""
    v = check_vector(name, vector)
    top = float(np.max(np.abs(v)))
    if top == 0.0:
        raise ValueError(f"{name} must be a non-zero vector")
    v = np.ldexp(v, 1 - math.frexp(top)[1])
    return v / np.linalg.norm(v)


def rotation_about(axis, angle):
    """Rotation matrix by an angle about an axis through the origin, by the right-hand rule (Rodrigues).

    Parameters
    ----------
    axis : array_like, shape (3,)
        Direction of the axis, any non-zero length (it is normalised).
    angle : float
        Angle of the turn in radians, anticlockwise seen from the tip of `axis`.

    Returns
    -------
    ndarray, shape (3, 3)
        The proper rotation R = I + sin(angle) K + (1 - cos(angle)) K^2, K the cross-product matrix of the unit
        axis: R @ x turns the vector x.

    Raises
    ------
    ValueError
        Naming `axis` when it is not a finite 3-vector or is zero, naming `angle` when it is not finite.
    TypeError
        Naming `axis` when it is not an array of real numbers, `angle` when it is not a real number.

    Examples
    --------
    A quarter turn about z takes x to y:

    >>> import numpy as np
    >>> import spatialkin as sk
    >>> R = sk.rotation_about((0.0, 0.0, 2.0), np.pi / 2)
    >>> R.shape
    (3, 3)
    >>> np.allclose(R @ (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    True
    >>> sk.rotation_about((0.0, 0.0, 0.0), 1.0)
    Traceback (most recent call last):
    ...
    ValueError: axis must be a non-zero vector
    """
    k = unit("axis", axis)
    angle = check_real("angle", angle, finite=True, strict=True)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * (kx @ kx)


def rotation_to_z(z_axis):
    """A rotation whose third column (local z) is the unit vector along z_axis.

    The first two columns are completed deterministically: local x is the unit vector along e x z, e the
    coordinate axis least aligned with z, and local y = z x x.

    Parameters
    ----------
    z_axis : array_like, shape (3,)
        Direction of the local z axis in global coordinates, any non-zero length.

    Returns
    -------
    ndarray, shape (3, 3)
        Proper rotation (orthonormal, determinant +1); its columns are the local x, y, z axes.

    Raises
    ------
    ValueError
        Naming `z_axis` when it is not a finite 3-vector or is zero.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> R = sk.rotation_to_z((1.0, 1.0, 0.0))
    >>> np.allclose(R[:, 2], np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0))
    True
    >>> np.allclose(R.T @ R, np.eye(3)), round(float(np.linalg.det(R)), 6)
    (True, 1.0)
    """
    z = unit("z_axis", z_axis)
    helper = np.eye(3)[np.argmin(np.abs(z))]
    x = cross(helper, z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, cross(z, x), z])


def _read_only(x):
    x.flags.writeable = False
    return x


class Frame:
    """A placement of local coordinates in global ones: global = origin + rotation @ local.

    Surfaces are placed by a frame (a torus or a cone about its local z axis, a sphere centred at its origin, a
    plane spanned by its local x and y); mechanisms place their shafts by frames. Both arrays are stored
    read-only.

    Parameters
    ----------
    origin : array_like, shape (3,), optional
        Position of the local origin in global coordinates (the user's length unit), each coordinate within 1e32
        of 0 (spatialkin._lib.validation.LENGTH_MAX); default the global origin.
    rotation : array_like, shape (3, 3), optional
        Proper rotation (orthonormal within 1e-9 entrywise, determinant +1); its columns are the local x, y, z
        axes in global coordinates. Default: the identity.

    Attributes
    ----------
    origin : ndarray, shape (3,)
    rotation : ndarray, shape (3, 3)

    Raises
    ------
    ValueError
        Naming `origin` or `rotation`: non-finite entries, a wrong shape, an origin beyond the supported lengths,
        a rotation that is not orthonormal or is left-handed (a reflection).
    TypeError
        Naming `origin` or `rotation` when it is not an array of real numbers.

    See Also
    --------
    rotation_about, rotation_to_z : rotations to build a frame from.

    Examples
    --------
    A frame at (1, 2, 3) turned a quarter turn about z: its local x is the global y.

    >>> import numpy as np
    >>> import spatialkin as sk
    >>> frame = sk.Frame((1.0, 2.0, 3.0), sk.rotation_about((0.0, 0.0, 1.0), np.pi / 2))
    >>> np.allclose(frame.to_global((1.0, 0.0, 0.0)), (1.0, 3.0, 3.0))
    True
    >>> local = [[0.5, 0.0, 0.0], [0.0, 0.0, 2.0]]
    >>> np.allclose(frame.to_local(frame.to_global(local)), local)
    True
    >>> np.allclose(sk.Frame.from_z_axis((0.0, 0.0, 0.0), (0.0, 3.0, 0.0)).rotation[:, 2], (0.0, 1.0, 0.0))
    True
    >>> sk.Frame(rotation=np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    ValueError: rotation must be right-handed (det = +1), got a reflection (det = -1)
    """

    __slots__ = ("origin", "rotation")

    def __init__(self, origin=(0.0, 0.0, 0.0), rotation=None):
        origin, rot = check_frame(origin, np.eye(3) if rotation is None else rotation)
        origin.flags.writeable = False
        rot.flags.writeable = False
        self.origin = origin
        self.rotation = rot

    def __getstate__(self):
        return self.origin, self.rotation

    def __setstate__(self, state):
        """Unpickled (a worker process's copy) as made: its arrays read-only again (numba compiles a kernel anew for
        each read-only flag of its arguments; a pickled array comes back writable)."""
        self.origin, self.rotation = (_read_only(x) for x in state)

    @classmethod
    def from_z_axis(cls, origin, z_axis):
        """A frame at origin whose local z points along z_axis (its x and y as rotation_to_z completes them).

        Parameters
        ----------
        origin : array_like, shape (3,)
        z_axis : array_like, shape (3,)
            Any non-zero length.

        Returns
        -------
        Frame

        Raises
        ------
        ValueError
            Naming the argument that is not a finite 3-vector, or a zero z_axis.
        """
        return cls(origin, rotation_to_z(z_axis))

    def to_global(self, local_points):
        """Global coordinates (..., 3) of local points (..., 3): origin + rotation @ p for each point p. ValueError
        naming `local_points` where they are not finite or not of shape (..., 3); TypeError where they are not real
        numbers."""
        return self.global_of(check_point_array("local_points", local_points))

    def to_local(self, points):
        """Local coordinates (..., 3) of global points (..., 3): rotation.T @ (p - origin) for each point p.
        ValueError naming `points` where they are not finite or not of shape (..., 3); TypeError where they are not
        real numbers."""
        return self.local_of(check_point_array("points", points))

    def global_of(self, local_points):
        """to_global of points (..., 3) the library has made itself (float arrays, finite): not checked again."""
        return self.origin + local_points @ self.rotation.T

    def local_of(self, points):
        """to_local of points (..., 3) the library has made itself (float arrays, finite): not checked again."""
        return (points - self.origin) @ self.rotation

    def __repr__(self):
        return f"Frame(origin={self.origin.tolist()}, rotation={self.rotation.tolist()})"

