"""Components known in closed form: a circle or a segment along which the two surfaces touch (status 'tangent'; the
tracer cannot follow them, the normals being parallel all along), a circle about the common axis of two surfaces of
revolution (status 'closed'), a single point where they touch (status 'contact'). Each is a CurveResult whose dense
output evaluates the closed form exactly; a circle's or a segment's (and a conic's, spatialkin.tracing.closed.conic) is
a SampledResult, whose stored points and parameters are made on first access (from the dense output, the same
arrays whenever they are made).
"""
import dataclasses
import functools
import math

import numpy as np

from ...kernels.curve.stored import unwrap_turns
from ...kernels.geometry import surfaces as ks
from ...geometry.vectors import cross
from .dense import CurveSolution
from .result import CurveResult
from .status import MESSAGES, outcome

#: Stored points of a circle or a segment in closed form.
EXACT_SAMPLES = 65
#: The unit vectors along the coordinate axes (rows).
AXES = np.eye(3)
AXES.flags.writeable = False


@functools.lru_cache(maxsize=None)
def counting(count):
    """0.0, 1.0, ..., count - 1 (count,), shared and read-only (np.arange(float(count)), made once per count)."""
    out = np.arange(float(count))
    out.flags.writeable = False
    return out


def even(start, stop, count):
    """np.linspace(start, stop, count) (float start and stop, count >= 2), bit for bit (its own arithmetic:
    k x ((stop - start) / (count - 1)) + start, the last set to stop) without its call overhead; a zero step
    (below the smallest normal float) goes to np.linspace itself."""
    step = (stop - start) / (count - 1)
    if step == 0:
        return np.linspace(start, stop, count)
    out = counting(count) * step
    out += start
    out[-1] = stop
    return out


#: The fields of a SampledResult taken from its dense output's samples (ExactSolution.samples) on first access.
SAMPLED_FIELDS = ("points", "s", "params")
#: CurveResult's fields with a default value, and those with a default factory (name: factory; a SampledResult
#: not given one makes it on first access, as the sampled fields).
_DEFAULTS = {f.name: f.default for f in dataclasses.fields(CurveResult) if f.default is not dataclasses.MISSING}
_FACTORIES = {f.name: f.default_factory for f in dataclasses.fields(CurveResult)
              if f.default_factory is not dataclasses.MISSING}
#: All of CurveResult's field names, and those a SampledResult must be given.
_FIELDS = frozenset(f.name for f in dataclasses.fields(CurveResult))
_REQUIRED = _FIELDS - set(_DEFAULTS) - set(_FACTORIES) - set(SAMPLED_FIELDS)
#: The same, for a SampledResult given its message's maker (message_of) instead of its message.
_REQUIRED_UNSAID, _FIELDS_UNSAID = _REQUIRED - {"message"}, _FIELDS - {"message"}


class SampledResult(CurveResult):
    """A CurveResult of a closed form whose points, s and params, unless given (all three), are its dense output's
    stored samples (``sol.samples()`` and ``sol.knots``: the exact points and the surfaces' parameters at the
    knots), made on first access: what sk.intersect returns costs no sampling until a caller reads them, and reads
    the same arrays then. The fields with a default factory (nodes, solver_gap) are made on first access too, and
    so is the message when its maker is given instead (message_of: a callable of no argument that pickles, such
    as a functools.partial of a module-level function; called once, on first access)."""

    def __init__(self, *, points=None, s=None, params=None, message_of=None, **fields):
        # CurveResult's own init with its defaults and its checks (__post_init__), its fields written as its
        # generated init writes them (to the instance's dict), at half its cost (tests: test_exact.py)
        required, known = (_REQUIRED, _FIELDS) if message_of is None else (_REQUIRED_UNSAID, _FIELDS_UNSAID)
        if not (required <= fields.keys() <= known):          # (the defaults are neither required nor unknown)
            raise TypeError(f"SampledResult: missing {sorted(required - fields.keys())} or unknown "
                            f"{sorted(fields.keys() - known)} fields")
        state = self.__dict__
        state.update(_DEFAULTS)
        state.update(fields)
        if message_of is not None:
            state["_message_of"] = message_of
        if points is not None:                  # (all three given, or none: read through __getattr__)
            state.update(points=points, s=s, params=params)
        self.__post_init__()

    def first_point(self):
        """The first stored point (3,), without sampling the others where they are not made yet (the dense output's
        first_point: the same bits as its samples' first row)."""
        return self.__dict__["points"][0] if "points" in self.__dict__ else self.sol.first_point()

    def __getattr__(self, name):
        """A sampled field, a default factory's or the message not made yet (Python asks only for attributes the
        instance does not hold)."""
        state = self.__dict__
        if "sol" in state:
            if name in SAMPLED_FIELDS:
                sol = state["sol"]
                points, params = sol.samples()
                state.update(points=points, s=sol.knots, params=params)
                return state[name]
            if name == "message" and "_message_of" in state:
                state["message"] = message = state["_message_of"]()
                return message
            make = _FACTORIES.get(name)
            if make is not None:
                state[name] = value = make()
                return value
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")


class ExactSolution(CurveSolution):
    """Closed-form dense output: subclasses give the points and unit tangents (``at``) and the curvature vectors
    (``bend``); the parameters are the surfaces' own (Surface.parameters) of the exact points."""

    _samples = None
    _first = None
    _knots = None

    @property
    def knots(self):
        """Arc lengths (N,) of the stored points (make_knots, on first use)."""
        if self._knots is None:
            self._knots = self.make_knots()
        return self._knots

    @knots.setter
    def knots(self, value):
        self._knots = value

    def make_knots(self):
        """The knots, for a subclass that gives none to CurveSolution.__init__."""
        raise NotImplementedError

    def samples(self):
        """(points (N, 3), params (N, 4)) at the knots: the exact points (a closed curve's last is its first) and
        their parameters on the two surfaces (surface_parameters), periodic u unwrapped along the curve (as the
        tracer's), made once."""
        if self._samples is None:
            points = self.sample_points()
            if self.closed:
                points[-1] = points[0]
            params = surface_parameters(self.surfaces, points)
            for k, surf in enumerate(self.surfaces):
                if surf.traits.periodic[0]:
                    unwrap_turns(params[:, 2 * k])
            self._samples = points, params
        return self._samples

    def sample_points(self):
        """The exact points (N, 3) at the knots (a new array)."""
        return self.points_at(self.knots)

    def first_point(self):
        """The first stored point (3,), without making the others (the same bits as samples()'s first row)."""
        if self._samples is not None:
            return self._samples[0][0]
        if self._first is None:
            self._first = self.first_sample()
        return self._first

    def first_sample(self):
        """The first stored point (3,), made alone as sample_points makes it."""
        return self.points_at(self.knots[:1])[0]

    def at(self, s):
        """(points (M, 3), unit tangents (M, 3)) at the wrapped arc lengths s (M,)."""
        raise NotImplementedError

    def points_at(self, s):
        """The points (M, 3) of ``at`` alone."""
        return self.at(s)[0]

    def bend(self, points):
        """Curvature vectors (M, 3) at the points (M, 3) of the curve."""
        raise NotImplementedError

    def evaluate(self, s, with_params=True):
        s = self.wrap(np.ravel(s))
        points, tangents = self.at(s)
        params = None
        if with_params:
            params = surface_parameters(self.surfaces, points)
        return s, points, tangents, params

    def derivatives(self, s):
        """(points, unit tangents, curvature vectors) (..., 3) at s, in closed form."""
        shape = np.shape(s)
        _, points, tangents, _ = self.evaluate(s, with_params=False)
        return tuple(x.reshape(shape + (3,)) for x in (points, tangents, self.bend(points)))


class CircleSolution(ExactSolution):
    """The circle of the given centre (3,), unit axis (3,) and radius, from the point centre + radius e1 (e1 normal
    to the axis, along the coordinate axis least aligned with it) counterclockwise about the axis. The centre and
    the axis may be given as 3 floats each: they are read as arrays, made on first use."""

    shape = "circle"

    def __init__(self, surfaces, centre, axis, radius, samples=EXACT_SAMPLES):
        self._given, self.radius = (centre, axis), float(radius)
        self.count = samples
        super().__init__(surfaces, 2 * np.pi * self.radius, True, None)      # (the knots and e1, e2 on first use)

    @functools.cached_property
    def centre(self):
        """The centre (3,)."""
        return np.asarray(self._given[0], dtype=float)

    @functools.cached_property
    def axis(self):
        """The unit axis (3,)."""
        return np.asarray(self._given[1], dtype=float)

    def make_knots(self):
        return even(0.0, self.length, self.count)

    @functools.cached_property
    def e1(self):
        """The unit vector (3,) from the centre to the point at s = 0."""
        e1 = cross(self.axis, AXES[np.argmin(np.abs(self.axis))])
        return e1 / math.sqrt(e1.dot(e1))                    # (np.linalg.norm's arithmetic)

    @functools.cached_property
    def e2(self):
        """axis x e1 (3,)."""
        return cross(self.axis, self.e1)

    def _turn(self, s):
        """(cos, sin) (M, 1) each of the angles at arc lengths s (M,)."""
        angle = s / self.radius
        return np.cos(angle)[:, None], np.sin(angle)[:, None]

    def at(self, s):
        c, n = self._turn(s)
        return self.centre + self.radius * (c * self.e1 + n * self.e2), -n * self.e1 + c * self.e2

    def points_at(self, s):
        c, n = self._turn(s)
        return self.centre + self.radius * (c * self.e1 + n * self.e2)

    def bend(self, points):
        return -(points - self.centre) / self.radius ** 2


class SegmentSolution(ExactSolution):
    """The segment from p0 (3,) to p1 (3,)."""

    shape = "segment"

    def __init__(self, surfaces, p0, p1, samples=EXACT_SAMPLES):
        self.p0, p1 = (np.asarray(x, dtype=float) for x in (p0, p1))
        length = float(np.linalg.norm(p1 - self.p0))
        self.direction = (p1 - self.p0) / max(length, 1e-300)
        self.count = samples
        super().__init__(surfaces, length, False, None)         # (the knots on first use)

    def make_knots(self):
        return even(0.0, self.length, self.count)

    def at(self, s):
        return self.p0 + s[:, None] * self.direction, np.broadcast_to(self.direction, (len(s), 3)).copy()

    def bend(self, points):
        return np.zeros_like(points)


class PointSolution(ExactSolution):
    """A single point (3,): every arc length is at it; it has no tangent nor curvature (NaN)."""

    shape = "point"

    def __init__(self, surfaces, point):
        self.point = np.asarray(point, dtype=float)
        super().__init__(surfaces, 0.0, False, np.zeros(1))

    def wrap(self, s):
        return np.zeros(np.shape(super().wrap(s)))         # (s checked as on any open curve: finite, in [0, 0])

    def at(self, s):
        return np.broadcast_to(self.point, (len(s), 3)).copy(), np.full((len(s), 3), np.nan)

    def bend(self, points):
        return np.full(np.shape(points), np.nan)

    def closest(self, points):
        pts = np.asarray(points, dtype=float)
        return np.zeros(pts.shape[:-1]), np.linalg.norm(pts - self.point, axis=-1)


def exact_curve(surfaces, tolerance, circle=None, segment=None, event="tangent", topology=None):
    """The CurveResult of a circle (centre (3,), unit axis (3,), radius) or a segment (p0 (3,), p1 (3,)) in closed
    form; `event` is 'tangent' (the surfaces touch all along it) or 'axis_circle' (a circle about their common
    axis), its status and message from spatialkin.tracing.curve.status.MESSAGES; tolerance as in Curve; topology the
    search that found it (CurveResult.topology)."""
    sol = CircleSolution(surfaces, *circle) if circle is not None else SegmentSolution(surfaces, *segment)
    return SampledResult(closed=sol.closed, length=sol.length, status=MESSAGES[event][0], tolerance=tolerance,
                         sol=sol, topology=topology, message_of=functools.partial(event_message, event, sol.shape))


def event_message(event, shape):
    """The message of the event of exact_curve for a curve of the given shape (made on first access)."""
    return outcome(event, shape=shape)[1]


def surface_parameters(surfaces, points):
    """(u1, v1, u2, v2) (N, 4) of the points (N, 3, finite: made here) on the two surfaces (Surface.parameters of
    each, u wrapped, without its argument checks)."""
    points = np.ascontiguousarray(points, dtype=float)
    uv = np.empty((len(points), 2))
    out = np.empty((len(points), 4))
    for k in range(2):
        ks.inverse(surfaces[k].data, points, uv)
        out[:, 2 * k:2 * k + 2] = uv
    return out


def contact_point(surfaces, point, tolerance, event="contact"):
    """The CurveResult of a single point (3,) where the surfaces touch (status 'contact', length 0), or, with
    event 'edge_point', where two faces meet in one point of their edges (status 'boundary', length 0)."""
    point = np.asarray(point, dtype=float)
    sol = PointSolution(surfaces, point)
    status, message = outcome(event, point=point.tolist())
    return CurveResult(points=point.reshape(1, 3), s=np.zeros(1), params=sol.parameters(np.zeros(1)), closed=False,
                       length=0.0, status=status, message=message, tolerance=tolerance, sol=sol)
