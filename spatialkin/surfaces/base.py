"""The placed surface: a thin object over a packed float array (``surface.data``) that the jitted kernels of
``spatialkin.kernels.surfaces`` read, and the argument checks its kinds share.

Each kind (torus.py, sphere.py, plane.py, cylinder.py, cone.py) defines its class and its traits
(spatialkin.tracing.traits.SurfaceTraits) in its own module and registers them; ``Surface`` asks the registry for
the kind code and the kernel geometry it packs.
"""

import numpy as np

from ..frame import Frame
from ..kernels import surfaces as ks
from ..tracing.traits import AXIS, check_surface, traits
from ..validation import check_positive, check_range

__all__ = ["Surface", "check_positive", "check_range", "check_surface"]


class Surface:
    """Base of the placed surfaces. A kind's class sets the shape parameters and the bounds; its registered
    traits (spatialkin.tracing.traits) give the kind code and the kernel geometry packed into ``data``."""

    def __init__(self, frame, p0=0.0, p1=0.0, u_range=None, v_range=None):
        if frame is None:
            frame = Frame()
        if not isinstance(frame, Frame):
            raise TypeError(f"frame must be a spatialkin.Frame, got {type(frame).__name__}")
        kind = traits(type(self))
        self.frame = frame
        data = np.zeros(ks.DATA_SIZE)
        data[ks.KIND] = kind.code
        data[ks.GEOMETRY] = kind.geometry
        data[ks.P0] = p0
        data[ks.P1] = p1
        data[ks.ORIGIN:ks.ORIGIN + 3] = frame.origin
        data[ks.ROT:ks.ROT + 9] = frame.rotation.ravel()
        data[ks.BOUNDS:ks.BOUNDS + 2] = check_range("u_range", u_range)
        data[ks.BOUNDS + 2:ks.BOUNDS + 4] = check_range("v_range", v_range)
        data.flags.writeable = False
        self.data = data

    # --- the kind's traits --------------------------------------------------------------------------------------
    @property
    def kind(self):
        """The kind code (data[KIND]), the key of the kind's traits."""
        return int(self.data[ks.KIND])

    @property
    def compact(self):
        """True when the surface is compact (closed and bounded): intersect() can seed it exhaustively."""
        return traits(self).compact

    @property
    def periodic_v(self):
        """True when v is periodic (2 pi), as u is for every kind but the plane."""
        return traits(self).periodic[1]

    # --- geometry ---------------------------------------------------------------------------------------------
    @property
    def size(self):
        """Characteristic length: the radius, the outer radius of a torus, 1 for an unbounded plane."""
        return float(traits(self).size(self))

    @property
    def u_range(self):
        data = self.data
        return data[ks.BOUNDS], data[ks.BOUNDS + 1]         # (indexed: a tuple of a slice costs 7x as much)

    @property
    def v_range(self):
        data = self.data
        return data[ks.BOUNDS + 2], data[ks.BOUNDS + 3]

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


# --- pieces the kinds' traits share --------------------------------------------------------------------------------
def own_axis(surface):
    """(AXIS, origin, local z): the symmetry of a surface of revolution about its own z axis."""
    return AXIS, surface.frame.origin, surface.frame.rotation[:, 2]


def quadric_jets(q, diag, value):
    """(F, grad F, hess F) of F = sum_i diag_i q_i^2 / 2 + const at local points q (N, 3), given F's values."""
    hess = np.zeros((len(q), 3, 3))
    hess[:] = np.diag(diag)
    return value, q * diag, hess

