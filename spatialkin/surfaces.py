"""Placed surfaces: torus (ring, horn, spindle), sphere, plane, cylinder and cone.

Each surface is a thin object over a packed float array (``surface.data``) that the jitted kernels of
``spatialkin.kernels.surfaces`` read; see that module for the local parametrisations.
"""
import math

import numpy as np

from .frame import Frame
from .kernels import surfaces as ks
from .validation import check_positive as check_length, check_range

__all__ = ["Surface", "Torus", "Sphere", "Plane", "Cylinder", "Cone"]


def check_surface(name, value):
    if not isinstance(value, Surface):
        raise TypeError(f"{name} must be a spatialkin surface (Torus, Sphere, Plane, Cylinder, Cone), "
                        f"got {type(value).__name__}")
    return value


class Surface:
    """Base of the placed surfaces. Subclasses set ``kind``, the shape parameters and the bounds."""

    kind = -1
    #: True when the surface is compact (closed and bounded): intersect() can seed it exhaustively.
    compact = False
    #: True when u and v are both periodic (2 pi).
    periodic_v = False

    def __init__(self, frame, p0=0.0, p1=0.0, u_range=None, v_range=None):
        if frame is None:
            frame = Frame()
        if not isinstance(frame, Frame):
            raise TypeError(f"frame must be a spatialkin.Frame, got {type(frame).__name__}")
        self.frame = frame
        data = np.zeros(ks.DATA_SIZE)
        data[ks.KIND] = self.kind
        data[ks.P0] = p0
        data[ks.P1] = p1
        data[ks.ORIGIN:ks.ORIGIN + 3] = frame.origin
        data[ks.ROT:ks.ROT + 9] = frame.rotation.ravel()
        data[ks.BOUNDS:ks.BOUNDS + 2] = check_range("u_range", u_range)
        data[ks.BOUNDS + 2:ks.BOUNDS + 4] = check_range("v_range", v_range)
        data.flags.writeable = False
        self.data = data

    # --- geometry ---------------------------------------------------------------------------------
    @property
    def size(self):
        """Characteristic length: the radius, the outer radius of a torus, 1 for an unbounded plane."""
        return float(ks.size(self.data))

    @property
    def u_range(self):
        return tuple(self.data[ks.BOUNDS:ks.BOUNDS + 2])

    @property
    def v_range(self):
        return tuple(self.data[ks.BOUNDS + 2:ks.BOUNDS + 4])

    def point(self, u, v):
        """Global points (..., 3) at parameters u, v (broadcast together)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        uv = np.ascontiguousarray(np.stack([u.ravel(), v.ravel()], axis=1))
        out = np.empty((uv.shape[0], 3))
        ks.evaluate(self.data, uv, out)
        return out.reshape(u.shape + (3,))

    def derivatives(self, u, v):
        """Point and derivatives at one (u, v): array (6, 3), rows point, S_u, S_v, S_uu, S_uv, S_vv."""
        out = np.empty((6, 3))
        ks.derivatives(self.data, float(u), float(v), out)
        return out

    def normal(self, u, v):
        """Unit normal S_u x S_v / |S_u x S_v| at one (u, v) (outward for sphere, torus and cylinder)."""
        d = self.derivatives(u, v)
        n = np.cross(d[1], d[2])
        return n / np.linalg.norm(n)

    def distance(self, points):
        """Exact unsigned distance (...,) from global points (..., 3) to the untrimmed surface."""
        pts = np.asarray(points, dtype=float)
        if pts.shape[-1:] != (3,):
            raise ValueError(f"points must have shape (..., 3), got {pts.shape}")
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        out = np.empty(flat.shape[0])
        ks.distances(self.data, flat, out)
        return out.reshape(pts.shape[:-1])

    def parameters(self, points):
        """Parameters (..., 2) of the surface points nearest to global points (..., 3); u in (-pi, pi]."""
        pts = np.asarray(points, dtype=float)
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        out = np.empty((flat.shape[0], 2))
        ks.inverse(self.data, flat, out)
        return out.reshape(pts.shape[:-1] + (2,))

    def with_frame(self, frame):
        """The same surface placed by another frame."""
        raise NotImplementedError

    def __repr__(self):
        return f"{type(self).__name__}({self._describe()}, frame={self.frame!r})"


class Torus(Surface):
    """Torus about the local z axis: ring (minor < major), horn (minor = major) or spindle (minor > major).

    M(u, v) = frame((R + r cos v) cos u, (R + r cos v) sin u, r sin v); u around the axis, v around the tube.
    """

    kind = ks.TORUS
    compact = True
    periodic_v = True

    def __init__(self, major_radius, minor_radius, frame=None):
        self.major_radius = check_length("major_radius", major_radius)
        self.minor_radius = check_length("minor_radius", minor_radius)
        super().__init__(frame, self.major_radius, self.minor_radius)

    @property
    def shape(self):
        """'ring', 'horn' or 'spindle'."""
        if self.minor_radius < self.major_radius:
            return "ring"
        return "horn" if self.minor_radius == self.major_radius else "spindle"

    def with_frame(self, frame):
        return Torus(self.major_radius, self.minor_radius, frame)

    def _describe(self):
        return f"major_radius={self.major_radius}, minor_radius={self.minor_radius}"


class Sphere(Surface):
    """Sphere of the given radius centred at frame.origin; local z is the pole axis of (u, v).

    M(u, v) = frame(R cos v cos u, R cos v sin u, R sin v); u longitude, v latitude.
    """

    kind = ks.SPHERE
    compact = True

    def __init__(self, radius, frame=None):
        self.radius = check_length("radius", radius)
        super().__init__(frame, self.radius)

    @property
    def center(self):
        return self.frame.origin

    def with_frame(self, frame):
        return Sphere(self.radius, frame)

    def _describe(self):
        return f"radius={self.radius}"


class Plane(Surface):
    """Plane through frame.origin spanned by the local x and y axes: M(u, v) = frame(u, v, 0).

    u_range and v_range optionally trim it to a rectangle.
    """

    kind = ks.PLANE

    def __init__(self, frame=None, u_range=None, v_range=None):
        super().__init__(frame, u_range=u_range, v_range=v_range)

    def with_frame(self, frame):
        return Plane(frame, self.u_range, self.v_range)

    def _describe(self):
        return f"u_range={self.u_range}, v_range={self.v_range}"


class Cylinder(Surface):
    """Circular cylinder of the given radius about the local z axis: M(u, v) = frame(r cos u, r sin u, v).

    v_range optionally trims it along the axis.
    """

    kind = ks.CYLINDER

    def __init__(self, radius, frame=None, v_range=None):
        self.radius = check_length("radius", radius)
        super().__init__(frame, self.radius, 0.0, v_range=v_range)

    def with_frame(self, frame):
        return Cylinder(self.radius, frame, self.v_range)

    def _describe(self):
        return f"radius={self.radius}, v_range={self.v_range}"


class Cone(Surface):
    """Circular double cone with its apex at frame.origin about the local z axis:
    M(u, v) = frame(v tan(a) cos u, v tan(a) sin u, v), a the half angle; the apex (v = 0) is a singular
    point of the surface. v_range optionally trims it along the axis.
    """

    kind = ks.CONE

    def __init__(self, half_angle, frame=None, v_range=None):
        a = check_length("half_angle", half_angle)
        if a >= math.pi / 2:
            raise ValueError(f"half_angle must lie in (0, pi/2), got {a}")
        self.half_angle = a
        super().__init__(frame, 0.0, math.tan(a), v_range=v_range)

    def with_frame(self, frame):
        return Cone(self.half_angle, frame, self.v_range)

    def _describe(self):
        return f"half_angle={self.half_angle}, v_range={self.v_range}"
