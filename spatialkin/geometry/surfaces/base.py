"""The placed surface: a thin object over a packed float array (``surface.data``) that the jitted kernels of
``spatialkin.kernels.geometry.surfaces`` read, and the argument checks its kinds share.

Each kind (torus.py, sphere.py, plane.py, cylinder.py, cone.py) defines its class and its traits
(spatialkin.geometry.traits.SurfaceTraits) in its own module and registers them; ``Surface`` asks the registry for
the kind code and the kernel geometry it packs.
"""

import copy
import math

import numpy as np

from ..frame import Frame
from ...kernels.geometry import surfaces as ks
from ..traits import AXIS, LENGTH, check_surface, traits
from ..._lib.validation import (check_finite, check_length, check_positive, check_query_points, check_range,
                                check_real)

__all__ = ["Surface", "check_length", "check_positive", "check_range", "check_surface"]


class Surface:
    """Base of the placed surfaces: a frame, shape parameters and optional trims, packed for the kernels.

    A kind's class (Torus, Sphere, Plane, Cylinder, Cone) sets the shape parameters and the trims; its registered
    traits (spatialkin.geometry.traits) give the kind code and the kernel geometry packed into ``data`` (read-only).
    Every kind is a map M(u, v) = frame(local point) of its local parametrisation; ``point`` evaluates it,
    ``distance`` is the exact distance to the untrimmed surface.

    Parameters
    ----------
    frame : Frame or None
        Placement of the local coordinates (None: the global axes).
    p0, p1 : float
        The kind's two shape parameters as the kernels read them.
    u_range, v_range : (float, float) or None
        Trims (min, max) of u and v that the tracer watches as edges (ranges of a length: a plane's u and v, a
        cylinder's or cone's axial v), either end possibly infinite; None leaves the parameter untrimmed.
    region : tuple of tuples of spatialkin.geometry.trims.Limit
        The other trims (angular ranges, a plane's circle), cut from the traced curves afterwards.
    shown : ((float, float), (float, float)) or None
        The (u_range, v_range) the user gave, where they differ from the watched ones.

    Raises
    ------
    TypeError
        When `frame` is not a spatialkin.Frame.
    ValueError
        Naming `u_range` or `v_range` when it is not a pair min < max (no NaN) within the supported lengths
        (spatialkin._lib.validation.check_range).
    """

    def __init__(self, frame, p0=0.0, p1=0.0, u_range=None, v_range=None, region=(), shown=None):
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
        data[ks.BOUNDS:ks.BOUNDS + 2] = check_range("u_range", u_range, length=True)
        data[ks.BOUNDS + 2:ks.BOUNDS + 4] = check_range("v_range", v_range, length=True)
        data.flags.writeable = False
        self.data = data
        self.floats = tuple(data.tolist())
        self.region = tuple(region)
        self._shown = shown
        self._memo = {}

    def __getstate__(self):
        """Pickled, or copied, without the values derived from it (memo): a copy makes its own."""
        state = dict(self.__dict__)
        state.pop("_memo", None)
        return state

    def __setstate__(self, state):
        """Unpickled (a worker process's copy) as made: its packed data read-only again (numba compiles a kernel anew
        for each read-only flag of its arguments; a pickled array comes back writable)."""
        self.__dict__.update(state)
        self._memo = {}
        self.data.flags.writeable = False

    def memo(self, key, make):
        """The value make(surface) derived from the surface alone, made on the first request for key and kept: a
        surface never changes (its packed data is read-only), so the value never goes stale. The layers above keep
        their per-surface readings here (the scene's lengths, the closed forms' reading of the surface and its
        trims), so that a surface intersected many times is read once. A copy (with other data: with_data) and an
        unpickled one start with none."""
        memo = self._memo
        value = memo.get(key, memo)
        if value is memo:                   # (the memo itself: no value kept yet; None may be one)
            value = memo[key] = make(self)
        return value

    # --- the kind's traits --------------------------------------------------------------------------------------
    #: The kind's SurfaceTraits (spatialkin.geometry.traits), set on its class when the kind registers.
    traits = None

    @property
    def kind(self):
        """The kind code (data[KIND]), the key of the kind's traits."""
        return int(self.data[ks.KIND])

    @property
    def compact(self):
        """True when the surface is compact (closed and bounded): intersect() can seed it exhaustively."""
        return self.traits.compact

    @property
    def periodic_v(self):
        """True when v is periodic (2 pi), as u is for every kind but the plane."""
        return self.traits.periodic[1]

    # --- geometry ---------------------------------------------------------------------------------------------
    @property
    def size(self):
        """Characteristic length: the radius, the outer radius of a torus, 1 for an unbounded plane."""
        return float(self.traits.size(self))

    #: The packed data as a tuple of Python floats (read on the Python paths: indexing the array makes numpy scalars).
    floats = ()

    def with_data(self, data):
        """A copy of the surface whose packed data is data (DATA_SIZE,), read-only as every surface's."""
        out = copy.copy(self)                   # (copied as pickled: without the memo)
        out.data = np.array(data, dtype=float)
        out.data.flags.writeable = False
        out.floats = tuple(out.data.tolist())
        return out

    def with_bounds(self, bounds):
        """A copy of the surface whose watched trims (``bounds``) are bounds ((u_min, u_max), (v_min, v_max)), shown
        as its u_range and v_range where those are lengths (an angular trim stays as given)."""
        data = self.data.copy()
        data[ks.BOUNDS:ks.BOUNDS + 4] = [x for pair in bounds for x in pair]
        out = self.with_data(data)
        if self._shown is not None:
            out._shown = tuple(tuple(map(float, new)) if unit == LENGTH else shown
                               for new, shown, unit in zip(bounds, self._shown, self.traits.units))
        return out

    @property
    def bounds(self):
        """((u_min, u_max), (v_min, v_max)): the trims the tracer watches as edges (ranges of a length), infinite
        where there is none; the angular trims and a plane's circle are in ``region``."""
        b0, b1, b2, b3 = self.floats[ks.BOUNDS:ks.BOUNDS + 4]
        return (b0, b1), (b2, b3)

    @property
    def u_range(self):
        """(min, max) of u as trimmed (radians for an angle, the user's unit for a plane's u), or (-inf, inf)."""
        if self._shown is not None:
            return self._shown[0]
        return self.floats[ks.BOUNDS:ks.BOUNDS + 2]

    @property
    def v_range(self):
        """(min, max) of v as trimmed (a plane's v, a cylinder's or cone's axial v, a sphere's latitude, a torus's
        tube angle), or (-inf, inf) when untrimmed."""
        if self._shown is not None:
            return self._shown[1]
        return self.floats[ks.BOUNDS + 2:ks.BOUNDS + 4]

    @property
    def trimmed(self):
        """True when any trim is set (a range of u or v, a plane's circle)."""
        return bool(self.region) or bool(np.isfinite(self.data[ks.BOUNDS:ks.BOUNDS + 4]).any())

    def point(self, u, v):
        """Points of the surface at parameters (u, v), in global coordinates.

        Parameters
        ----------
        u, v : float or array_like
            Surface parameters, broadcast together to a shape (...): angles in radians (both of a torus; a sphere's
            longitude u and latitude v; u of a cylinder or cone), lengths in the user's unit (a plane's u and v, the
            axial v of a cylinder or cone). The trims (u_range, v_range) are not applied.

        Returns
        -------
        ndarray, shape (..., 3)
            The points M(u, v), in the user's length unit.

        Raises
        ------
        ValueError
            Naming `u` or `v` when it is not finite; when u and v do not broadcast together (numpy's message).
        TypeError
            Naming `u` or `v` when it is not real numbers.

        Examples
        --------
        >>> import numpy as np
        >>> import spatialkin as sk
        >>> torus = sk.Torus(2.0, 0.5)
        >>> np.allclose(torus.point(0.0, 0.0), (2.5, 0.0, 0.0))
        True
        >>> torus.point(np.linspace(0.0, np.pi, 5), 0.0).shape
        (5, 3)
        >>> u, v = np.meshgrid(np.linspace(0.0, 2 * np.pi, 4), np.linspace(-1.0, 1.0, 3))
        >>> torus.point(u, v).shape
        (3, 4, 3)
        >>> np.allclose(torus.distance(torus.point(u, v)), 0.0)
        True
        """
        u, v = np.broadcast_arrays(check_finite("u", u), check_finite("v", v))
        uv = np.ascontiguousarray(np.stack([u.ravel(), v.ravel()], axis=1))
        out = np.empty((uv.shape[0], 3))
        ks.evaluate(self.data, uv, out)
        return out.reshape(u.shape + (3,))

    def derivatives(self, u, v):
        """Point and derivatives at one (u, v): array (6, 3), rows point, S_u, S_v, S_uu, S_uv, S_vv."""
        out = np.empty((6, 3))
        ks.derivatives(self.data, check_real("u", u, finite=True, strict=True),
                       check_real("v", v, finite=True, strict=True), out)
        return out

    def normal(self, u, v):
        """Unit normal S_u x S_v / |S_u x S_v| at one (u, v) (outward for sphere, torus and cylinder)."""
        d = self.derivatives(u, v)
        n = np.cross(d[1], d[2])
        return n / np.linalg.norm(n)

    def distance(self, points):
        """Exact unsigned distance from global points to the untrimmed surface.

        Parameters
        ----------
        points : array_like, shape (..., 3)
            Global points, in the user's length unit.

        Returns
        -------
        ndarray, shape (...)
            Distance of each point to the nearest point of the whole surface (its trims ignored), in the same
            unit: in closed form for every kind (no iteration), so it measures how far a point of an intersection
            curve lies off the surface.

        Raises
        ------
        ValueError
            Naming `points` when it does not have shape (..., 3) or is not finite.
        TypeError
            Naming `points` when it is not real numbers.

        Examples
        --------
        >>> import numpy as np
        >>> import spatialkin as sk
        >>> sphere = sk.Sphere(2.0, sk.Frame((1.0, 0.0, 0.0)))
        >>> sphere.distance([[1.0, 0.0, 0.0], [4.0, 0.0, 0.0], [1.0, 3.0, 0.0]]).round(6).tolist()
        [2.0, 1.0, 1.0]
        >>> sphere.distance(np.zeros((4, 5, 3))).shape
        (4, 5)
        >>> sphere.distance([1.0, 2.0])
        Traceback (most recent call last):
        ...
        ValueError: points must have shape (..., 3), got (2,)
        """
        pts = check_query_points("points", points)
        return distances_at(self, pts).reshape(pts.shape[:-1])

    def parameters(self, points):
        """Parameters (u, v) (..., 2) of the surface points nearest to global points (..., 3); u in (-pi, pi].
        ValueError naming `points` when it does not have shape (..., 3) or is not finite."""
        pts = check_query_points("points", points)
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        out = np.empty((flat.shape[0], 2))
        ks.inverse(self.data, flat, out)
        return out.reshape(pts.shape[:-1] + (2,))

    def with_frame(self, frame):
        """The same surface placed by another frame."""
        raise NotImplementedError

    def __repr__(self):
        return f"{type(self).__name__}({self._describe()}, frame={self.frame!r})"


# --- pieces the kinds share --------------------------------------------------------------------------------
def distances_at(surface, points):
    """Distances (N,) of points (..., 3), finite floats, to the untrimmed surface: Surface.distance without its
    argument checks, for points the library made."""
    points = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)
    out = np.empty(len(points))
    ks.distances(surface.data, points, out)
    return out


def trims_given(surface):
    """(u_range, v_range) as given to the constructor of a kind whose trims are all angles (None: untrimmed)."""
    return tuple(None if not math.isfinite(r[0]) else r for r in (surface.u_range, surface.v_range))


def trims_described(surface):
    """', u_range=..., v_range=...' of the trims that are set, for a repr."""
    return "".join(f", {name}={r}" for name, r in zip(("u_range", "v_range"), (surface.u_range, surface.v_range))
                   if math.isfinite(r[0]))


def own_axis(surface):
    """(AXIS, origin, local z): the symmetry of a surface of revolution about its own z axis."""
    return AXIS, surface.frame.origin, surface.frame.rotation[:, 2]


def quadric_jets(q, diag, value):
    """(F, grad F, hess F) of F = sum_i diag_i q_i^2 / 2 + const at local points q (N, 3), given F's values."""
    hess = np.zeros((len(q), 3, 3))
    hess[:] = np.diag(diag)
    return value, q * diag, hess

