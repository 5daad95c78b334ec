"""What tracing found: ``CurveResult``, the plain record of one component (scipy's OdeResult is the model), and
``sk.Curve``, the public curve built once from it, which evaluates through the record's dense output ``sol``
(spatialkin.tracing.curve.dense and .exact; scipy's OdeSolution) and measures its distances to the surfaces lazily."""
import dataclasses
import functools
import operator

import numpy as np

from ...kernels.geometry import surfaces as ks
from ..._lib.validation import TOO_LARGE, check_count, check_positive, check_query_points
from .bspline import fit as fit_spline
from .status import CURVE_STATUSES, END_PRECEDENCE, FAILED, check_status, describe, outcome
from ...geometry.traits import traits

#: Interior sample points closer than this (relative to the curve scale) to the closing point are dropped,
#: so that a closed curve has no near-duplicate of its first point before the exact copy at its end.
DUPLICATE_SPACING = 1e-9


class TracingError(RuntimeError):
    """Tracing could not start or go on: no curve point near the start, a singular start, nothing traced.

    Raised by ``sk.trace`` (and by the mechanisms built on it); ``sk.intersect`` handles it internally and
    raises TopologyError only when a component would be missed.

    Parameters
    ----------
    message : str
        What happened and where.
    where : ndarray, shape (3,), optional
        The point where tracing stopped or could not start (global coordinates), or None.
    status : str
        A short code of spatialkin.tracing.curve.status (default 'failed'), e.g. 'no_start' or 'singular'.

    Attributes
    ----------
    where : ndarray, shape (3,) or None
    status : str

    Raises
    ------
    ValueError
        For a status that table does not know.

    Examples
    --------
    >>> import spatialkin as sk
    >>> far_apart = (sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((5.0, 0.0, 0.0))))
    >>> try:
    ...     sk.trace(*far_apart, (2.5, 0.0, 0.0))
    ... except sk.TracingError as error:
    ...     print(error.status, error.where.tolist())
    no_start [2.5, 0.0, 0.0]
    """

    def __init__(self, message, where=None, status=FAILED):
        super().__init__(message)
        self.where = where
        self.status = check_status(status)

    @classmethod
    def of(cls, event, where=None, status=None, **fields):
        """The error of an event of spatialkin.tracing.curve.status.MESSAGES at where: its message, the template filled
        with fields, and its status (or the one given, for an event whose status depends on the case).

        Parameters
        ----------
        event : str
            A key of spatialkin.tracing.curve.status.MESSAGES.
        where : ndarray, shape (3,), optional
        status : str, optional
        **fields
            Values for the message's template.

        Returns
        -------
        TracingError
        """
        own, message = outcome(event, **fields)
        return cls(message, where=where, status=status or own)


#: The round-off of a stored point's gap to the surfaces, in ulps of its coordinates (CurveResult.gaps).
GAP_ROUNDOFF_ULPS = 4.0
EPS = np.finfo(float).eps


def point_gaps(a, b, points, tolerance):
    """(M,) gap of the points (M, 3) to the farther of the surfaces a and b, at most the tolerance, plus
    GAP_ROUNDOFF_ULPS of the coordinates (CurveResult.gaps)."""
    points = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)
    gap = np.empty(len(points))
    ks.farther_distances(a.data, b.data, points, float(tolerance), GAP_ROUNDOFF_ULPS * EPS, gap)
    return gap


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class CurveResult:
    """What tracing found about one component: a plain record; ``sol`` evaluates it. (A closed form's,
    spatialkin.tracing.curve.exact.SampledResult, makes its points, s and params on first read, the same arrays
    whenever that is.)

    The fields are the attributes of the same names of Curve (see there); ``topology`` is the search that found
    the component (sk.intersect; None for sk.trace), ``certificate`` what was verified (certify=True; else None).
    """

    points: np.ndarray
    s: np.ndarray
    params: np.ndarray
    closed: bool
    length: float
    status: str
    message: str
    tolerance: float
    sol: object
    nodes: np.ndarray = dataclasses.field(default_factory=lambda: np.empty((0, 3)))
    solver_gap: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    nfev: int = 0
    wall_time: float = 0.0
    topology: object = None
    certificate: object = None

    def first_point(self):
        """The first stored point (3,) (points[0])."""
        return self.points[0]

    @functools.cached_property
    def gaps(self):
        """(M,) how far off the curve each stored point may lie, as the de-duplication counts it: its distance to
        the farther of the two surfaces, at most the tolerance (a point farther is no point of the curve), plus
        GAP_ROUNDOFF_ULPS of its coordinates. Made on first read."""
        return point_gaps(*self.sol.surfaces, self.points, self.tolerance)

    @functools.cached_property
    def largest_gap(self):
        """The largest of the gaps."""
        return float(self.gaps.max())

    def __post_init__(self):
        state = self.__dict__                   # (frozen: written as object.__setattr__ writes, at a third of its cost)
        state["closed"], state["length"], state["tolerance"] = (bool(state["closed"]), float(state["length"]),
                                                                float(state["tolerance"]))
        state["nfev"], state["wall_time"] = int(state["nfev"]), float(state["wall_time"])
        if self.status not in CURVE_STATUSES:
            raise ValueError(f"a curve's status is one of {CURVE_STATUSES}, got {self.status!r}")


#: The step, relative to the length, of the central differences that give to_bspline C'' beside a node.
HERMITE_STEP = 1e-5
#: The record's fields a Curve shows as read-only attributes of the same names (all but the dense output; the
#: topology and the certificate are the Curve's own, sk.intersect's where it gives them).
RECORD_FIELDS = tuple(f.name for f in dataclasses.fields(CurveResult) if f.name != "sol")
#: The example curve of the fields' docstrings: a circle of radius 0.8 on the unit sphere.
_EXAMPLE = """
    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> curve, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
"""
#: The docstrings of the fields as Curve's attributes.
FIELD_DOCS = {
    "points": """Points on the curve, ndarray (N, 3), global coordinates in the user's length unit.

    Solver steps (or exact samples of a closed form), each corrected onto both surfaces by Newton; a closed
    curve's last point is its first, exactly.
""" + _EXAMPLE + """    >>> curve.points.shape[1], bool((curve.points[-1] == curve.points[0]).all())
    (3, True)
    >>> np.allclose(curve.points[:, 2], 0.6)
    True
""",
    "s": """Arc length at each point, ndarray (N,), increasing from 0 to ``length`` (the user's length unit).
""" + _EXAMPLE + """    >>> bool(curve.s[0] == 0.0), bool(curve.s[-1] == curve.length)
    (True, True)
    >>> bool((np.diff(curve.s) > 0).all())
    True
    >>> np.allclose(curve(curve.s), curve.points)
    True
""",
    "params": """Surface parameters (u1, v1, u2, v2) of each point, ndarray (N, 4).

    (u1, v1) in the chart of surface a, (u2, v2) in that of surface b (angles in radians; a plane's u and v and
    a cylinder's or cone's axial v in length units); periodic angles are continuous along the curve (not
    wrapped).
""" + _EXAMPLE + """    >>> sphere, plane = curve.surfaces
    >>> np.allclose(sphere.point(curve.params[:, 0], curve.params[:, 1]), curve.points)
    True
    >>> np.allclose(plane.point(curve.params[:, 2], curve.params[:, 3]), curve.points)
    True
""",
    "closed": """True for a closed loop (bool): the last point is the first, exactly; ``length`` is the period of s.
""" + _EXAMPLE + """    >>> curve.closed
    True
""",
    "length": """Arc length of the curve (float, the user's length unit); 0 for a contact point.
""" + _EXAMPLE + """    >>> round(curve.length, 6)        # 2 pi 0.8
    5.026548
""",
    "status": """How the curve ended (str): 'closed', or an open curve's ends' status ('boundary', 'singular', ...).

    'contact' or 'tangent' for a point or a line where the surfaces touch. See the Curve class.
""" + _EXAMPLE + """    >>> curve.status
    'closed'
""",
    "message": """A sentence (str) on how the curve ended (both ends for an open curve).""",
    "tolerance": """The accuracy asked for, an absolute length (float): tol times the scene scale, or 64 ulps of the
    coordinates' magnitude where that is larger.""",
    "nodes": """Singular points the curve passed straight through, ndarray (K, 3): nodes and apexes.""",
    "solver_gap": """|M1 - M2| of the solver's own states at its steps before the Newton correction, ndarray (M,): a
    diagnostic of drift.""",
    "nfev": """Right-hand-side evaluations spent by solve_ivp on this curve (int; 0 for a closed form).""",
    "wall_time": """Seconds spent tracing this curve (float).""",
    "topology": """The search of sk.intersect that found the component (spatialkin.tracing.search.topology), or
    None.""",
    "certificate": """What sk.intersect(..., certify=True) proved about this curve, or None without certify.

    A spatialkin.tracing.certify.certificate.Certificate: what the interval search proved (no box it discarded holds a
    component) and, for each stored point k, a radius ``radii[k]`` of a box round it holding a true intersection
    point; and what it did not prove (see Certificate).
""" + _EXAMPLE + """    >>> curve.certificate is None
    True
    >>> torus, sphere = sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    >>> loop = sk.intersect(torus, sphere, certify=True)[0]
    >>> loop.certificate.radii.shape == (len(loop.points),), loop.certificate.all_points_proven
    (True, True)
""",
}

def read_only(curve, name):
    """The record's array `name` of a Curve, made read-only (in place, once): the curve's stored points, arc lengths
    and parameters are what its dense output and measures read, so a user's write into them would change those."""
    value = getattr(curve._result, name)
    if value.flags.writeable:
        value.flags.writeable = False
    return value


class Curve:
    """One connected component of the intersection of two surfaces, parametrised by arc length.

    ``sk.trace`` and ``sk.intersect`` return curves; each is built once from a CurveResult (``Curve(result)``)
    and its attributes are read-only (its arrays too). Evaluations go through the dense output ``result.sol``: ``curve(s)`` gives
    points corrected onto both surfaces at any arc length; ``max_distance`` is measured on first access. Lengths
    are in the user's unit, parameters of angle kind in radians, arrays with the point index first.

    Parameters
    ----------
    result : CurveResult
        The record of one component (from the tracer or a closed form).
    topology, certificate : optional
        The search that found the component and what was proven about it, where sk.intersect gives them (else the
        record's own).

    Attributes
    ----------
    points : ndarray (N, 3)
        Points on the curve (solver steps, each corrected onto both surfaces by Newton).
    s : ndarray (N,)
        Arc length at each point, from 0 to ``length``, increasing.
    params : ndarray (N, 4)
        (u1, v1, u2, v2) of each point in the charts of surface a and b (u continuous, not wrapped).
    closed : bool
        True for a closed loop: the last point is the first (exactly), ``length`` is the period.
    length : float
        Arc length of the curve.
    status : str
        One of these (spatialkin.tracing.curve.status); an open curve's is that of its ends, the first of
        {precedence}:

{statuses}
    message : str
        A sentence on how it ended (both ends for an open curve).
    max_distance : float
        Largest measured distance (exact distance functions) of the returned points and of dense
        evaluations midway between them, to either surface (measured on first access).
    nfev : int
        Right-hand-side evaluations spent by solve_ivp.
    wall_time : float
        Seconds spent tracing this curve.
    nodes : ndarray (K, 3)
        Singular points the curve passed straight through: nodes where branches cross (each branch is then
        followed on through the node, so a figure-eight is one closed curve passing its node twice), and
        apexes of a spindle or horn torus or a cone.
    tolerance : float
        The accuracy asked for, as an absolute length: tol times the scene scale (the smaller surface
        size), or the round-off floor of the coordinates (64 ulps of their magnitude) where that is larger.
    solver_gap : ndarray (M,)
        |M1 - M2| of the solver's own states at its steps, before the Newton correction: how far plain
        integration (with the pull-back) strays; a diagnostic of drift.
    certificate : Certificate or None
        What sk.intersect(..., certify=True) verified (spatialkin.tracing.certify.certificate).
    topology : object or None
        The search of sk.intersect that found the component (spatialkin.tracing.search.topology).
    surfaces : (Surface, Surface)
        The two surfaces.
    result : CurveResult
        The record the curve was built from.

    Raises
    ------
    TypeError
        When `result` is not a CurveResult.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> curve, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
    >>> curve.closed, curve.status, round(curve.length, 6)
    (True, 'closed', 5.026548)
    >>> n = len(curve.points)
    >>> curve.points.shape == (n, 3) and curve.s.shape == (n,) and curve.params.shape == (n, 4)
    True
    >>> np.allclose(curve.points[:, 2], 0.6), np.allclose(np.linalg.norm(curve.points, axis=1), 1.0)
    (True, True)
    >>> curve(np.linspace(0.0, curve.length, 7)).shape
    (7, 3)
    >>> bool(curve.max_distance <= curve.tolerance)
    True
    """

    # --- the record's fields, read-only -----------------------------------------------------------------------
    points = property(functools.partial(read_only, name="points"), doc=FIELD_DOCS["points"])
    s = property(functools.partial(read_only, name="s"), doc=FIELD_DOCS["s"])
    params = property(functools.partial(read_only, name="params"), doc=FIELD_DOCS["params"])
    closed = property(operator.attrgetter("_result.closed"), doc=FIELD_DOCS["closed"])
    length = property(operator.attrgetter("_result.length"), doc=FIELD_DOCS["length"])
    status = property(operator.attrgetter("_result.status"), doc=FIELD_DOCS["status"])
    message = property(operator.attrgetter("_result.message"), doc=FIELD_DOCS["message"])
    tolerance = property(operator.attrgetter("_result.tolerance"), doc=FIELD_DOCS["tolerance"])
    nodes = property(functools.partial(read_only, name="nodes"), doc=FIELD_DOCS["nodes"])
    solver_gap = property(functools.partial(read_only, name="solver_gap"), doc=FIELD_DOCS["solver_gap"])
    nfev = property(operator.attrgetter("_result.nfev"), doc=FIELD_DOCS["nfev"])
    wall_time = property(operator.attrgetter("_result.wall_time"), doc=FIELD_DOCS["wall_time"])
    topology = property(operator.attrgetter("_topology"), doc=FIELD_DOCS["topology"])
    certificate = property(operator.attrgetter("_certificate"), doc=FIELD_DOCS["certificate"])

    def __init__(self, result, topology=None, certificate=None):
        if not isinstance(result, CurveResult):
            raise TypeError(f"a Curve is built from a CurveResult, got {type(result).__name__}")
        self._result = result
        self._topology = result.topology if topology is None else topology
        self._certificate = result.certificate if certificate is None else certificate

    @property
    def result(self):
        """The CurveResult this curve was built from."""
        return self._result

    @property
    def surfaces(self):
        """(a, b): the two surfaces, in the order they were given."""
        return self._result.sol.surfaces

    # --- dense evaluation (the record's dense output) -------------------------------------------------------
    def __call__(self, s):
        """Points on the curve at arc lengths s (dense evaluation), corrected onto both surfaces.

        Parameters
        ----------
        s : float or array_like, shape (...)
            Arc lengths, in the user's length unit: in [0, length] for an open curve, any finite value for a
            closed one (taken modulo its length).

        Returns
        -------
        ndarray, shape (..., 3)
            Global points, each within ``tolerance`` of both surfaces.

        Raises
        ------
        ValueError
            When s is not finite, or lies outside [0, length] on an open curve.
        TypeError
            When s is not real numbers (a str, None).

        Examples
        --------
        >>> import numpy as np
        >>> import spatialkin as sk
        >>> curve, = sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))))
        >>> curve(0.0).shape, curve(np.linspace(0.0, curve.length, 5)).shape
        ((3,), (5, 3))
        >>> np.allclose(curve(curve.length), curve(0.0))       # a closed curve is periodic in s
        True
        >>> arc, = sk.intersect(sk.Sphere(1.0), sk.Plane(u_range=(-2.0, 2.0), v_range=(0.0, 2.0)))
        >>> arc.closed, arc.status, round(arc.length, 6)      # half the equator, from edge to edge
        (False, 'boundary', 3.141593)
        >>> arc(4.0)
        Traceback (most recent call last):
        ...
        ValueError: s must lie in [0, 3.14159265359] for this open curve
        """
        return self._result.sol(arc_lengths(s))

    def tangent(self, s):
        """Unit tangents (..., 3) at s, pointing towards increasing s."""
        return self._result.sol.tangent(arc_lengths(s))

    def parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s (u wrapped to (-pi, pi] where a sphere had to be re-charted)."""
        return self._result.sol.parameters(arc_lengths(s))

    def predicted_parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s from the solver's dense output alone, without the Newton correction:
        within the solver's tolerance of the curve, a cheap start for Newton (a sphere's (u, v) are those of
        the point on surface a, as in parameters())."""
        return self._result.sol.predicted_parameters(arc_lengths(s))

    def derivatives(self, s):
        """(points, unit tangents C', curvature vectors C'') (..., 3) each at arc lengths s: from the corrected
        points and the two surfaces' implicit functions, or in closed form. Beside a singular point both lose
        accuracy, the tangent as the points' spread over the sine of the normals' angle, C'' as its square; C'' is
        NaN where its estimated relative error passes 1e-2 (spatialkin.tracing.curve.curvature)."""
        return self._result.sol.derivatives(arc_lengths(s))

    def closest(self, points):
        """Arc length (...,) of the curve point nearest to each point (..., 3), and the distance (...,).
        ValueError naming `points` when they are not finite or of shape (..., 3)."""
        pts = check_query_points("points", points)
        return self._result.sol.closest(pts)

    def sample(self, n):
        """n points evenly spaced in arc length (for a closed curve the last equals the first); n an integer
        >= 0 (ValueError naming it otherwise)."""
        return self(np.linspace(0.0, self.length, check_count("n", n, minimum=0)))

    # --- measured against the surfaces ----------------------------------------------------------------------
    def distances(self, points=None):
        """Exact distances (N, 2) of points (default: self.points) to surface a and surface b."""
        pts = self.points if points is None else check_query_points("points", points)
        return np.stack([surf.distance(pts) for surf in self.surfaces], axis=-1)

    @functools.cached_property
    def max_distance(self):
        """Largest measured distance (float, length unit) to either surface of the stored points and of dense
        evaluations midway between them (exact distance functions; measured on first access)."""
        pts = self.points
        if len(self.s) > 1 and self.length > 0:
            pts = np.vstack([pts, self(0.5 * (self.s[1:] + self.s[:-1]))])
        return float(np.max(self.distances(pts))) if len(pts) else 0.0

    def to_bspline(self, tol=1e-8):
        """A C2 quintic B-spline of the curve in its arc length, within tol times the scene scale (measured).

        Built from the exact points, unit tangents and curvature vectors at its knots (quintic Hermite data,
        turned into B-spline control points by blossoming [1]_); the knots are refined until the distance from
        the spline to the curve, measured at nine points inside every span (to the curve's point one Newton step
        in s from the spline's parameter: an upper bound of the distance to the curve), stays below 0.9 tol x
        scale. At the same s the spline and curve(s) may differ more, by the drift of the dense output's s from
        the true arc length (the integration's error, about rtol x length). A closed curve gives a periodic
        spline (extrapolate='periodic').

        Parameters
        ----------
        tol : float
            Allowed deviation, relative to the scene scale (the smaller surface size; see ``sk.intersect``).

        Returns
        -------
        scipy.interpolate.BSpline
            Degree 5 in the arc length s (the user's length unit), triple interior knots, values (3,) per s;
            ``spline.deviation`` is the largest measured distance (length unit), ``spline.checked`` how many curve
            points it was measured against.

        Raises
        ------
        ValueError
            For a non-positive tol, or a curve of length zero (a contact point).
        SplineToleranceError
            If tol lies below the round-off of the curve's points (spatialkin.tracing.curve.bspline).

        References
        ----------
        .. [1] L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer, 1997 (blossoms and control points, ch. 2
           and 5).

        Examples
        --------
        >>> import numpy as np
        >>> import spatialkin as sk
        >>> curve = sk.trace(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))), (0.5, 0.9, 0.0))
        >>> spline = curve.to_bspline(1e-8)                 # the scene scale is 1 here
        >>> spline.k, bool(spline.deviation <= 1e-8)
        (5, True)
        >>> _, gap = curve.closest(spline(np.linspace(0.0, curve.length, 101)))
        >>> bool(gap.max() <= 1e-8)
        True
        """
        tol = check_positive("tol", tol, strict=True)
        if self.length == 0:
            raise ValueError("a curve of length zero (a contact point) has no B-spline")
        from ..march.start import scene_scale       # start imports this module
        return fit_spline(self._hermite_data, 0.0, self.length, tol * scene_scale(*self.surfaces),
                          periodic=self.closed)

    def _hermite_data(self, s):
        """derivatives(s) for to_bspline, C'' where it is NaN beside a singular point (a node the curve passes)
        by central differences of the unit tangent HERMITE_STEP x length either side (clipped to an open curve's
        ends), where the normals are apart again: the spline is measured against the curve all the same."""
        points, tangents, bend = self.derivatives(s)
        bad = np.isnan(bend).any(axis=1) & np.isfinite(tangents).all(axis=1)
        if bad.any():
            h = HERMITE_STEP * self.length
            lo, hi = s[bad] - h, s[bad] + h
            if not self.closed:
                lo, hi = np.maximum(lo, 0.0), np.minimum(hi, self.length)
            bend[bad] = (self.tangent(hi) - self.tangent(lo)) / (hi - lo)[:, None]
        return points, tangents, bend

    def __len__(self):
        return len(self.points)

    def __repr__(self):
        kind = "closed" if self.closed else f"open ({self.status})"
        return (f"Curve({kind}, length={self.length:.6g}, points={len(self.points)}, "
                f"max_distance={self.max_distance:.2e})")


Curve.__doc__ = (Curve.__doc__.replace("{statuses}", describe(CURVE_STATUSES, 8))
                 .replace("{precedence}", ", ".join(f"'{s}'" for s in END_PRECEDENCE)))


def arc_lengths(s):
    """s as an array, or TypeError naming it when it is not real numbers (a str, None, a bool); ValueError naming it
    for an integer too large for a float."""
    arr = np.asarray(s)
    if arr.dtype.kind == "O" and all(type(x) in (int, float) for x in arr.flat):     # (ints past int64: objects)
        try:
            arr = arr.astype(float)
        except OverflowError:
            raise ValueError(f"s must be finite, got {TOO_LARGE}") from None
    if arr.dtype.kind not in "iuf":
        raise TypeError(f"s must be real numbers, got {type(s).__name__}")
    return arr


# --- states and parameters: helpers of the dense output (spatialkin.tracing.curve.dense) and of sk.trace ---------
def set_states(y, points, a, b):
    """Rows of the states y (M, 4) moved to the foot parameters of points (M, 3) on the charts a, b (angles kept
    within pi of the old ones); returns y."""
    uv = np.empty((len(points), 2))
    for k, data in enumerate((a, b)):
        ks.inverse(data, np.ascontiguousarray(points), uv)
        d = uv - y[:, 2 * k:2 * k + 2]
        for j, angle in enumerate(traits(data).angular):
            if angle:
                d[:, j] = np.mod(d[:, j] + np.pi, 2.0 * np.pi) - np.pi
        y[:, 2 * k:2 * k + 2] += d
    return y


def in_sk_order(curves):
    """The CurveResults sorted as sk.intersect returns them: longest first, then by first point (rounded to 9
    decimals; CurveResult.first_point: a closed form's without sampling the others). The first points are read only
    where two lengths are equal (a closed form's first point is an evaluation of its conic)."""
    if len(curves) > 1:
        curves.sort(key=lambda c: -c.length)
        if any(c.length == d.length for c, d in zip(curves, curves[1:])):
            curves.sort(key=lambda c: (-c.length, tuple(np.asarray(c.first_point()).round(9).tolist())))
    return curves


def in_own_chart(chart, surface):
    """True where chart (packed data) is a chart of its own (a re-charted sphere), not the surface's data."""
    return chart is not surface.data and not np.array_equal(chart, surface.data)


def user_params(surfaces, y, points, a_chart, b_chart):
    """(u1, v1, u2, v2) in the surfaces' own charts: a re-charted sphere's (u, v) come from the point."""
    out = np.array(y, dtype=float, copy=True)
    for k, (surf, chart) in enumerate(zip(surfaces, (a_chart, b_chart))):
        if in_own_chart(chart, surf):
            uv = np.empty((len(points), 2))
            ks.inverse(surf.data, np.ascontiguousarray(points), uv)
            out[:, 2 * k:2 * k + 2] = uv
    return out
