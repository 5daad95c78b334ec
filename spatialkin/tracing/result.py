"""What tracing found: ``CurveResult``, the plain record of one component (scipy's OdeResult is the model), and
``sk.Curve``, the public curve built once from it, which evaluates through the record's dense output ``sol``
(spatialkin.tracing.dense and .exact; scipy's OdeSolution) and measures its distances to the surfaces lazily."""
import dataclasses
import functools
import operator

import numpy as np

from ..kernels import surfaces as ks
from ..validation import check_positive
from .bspline import fit as fit_spline
from .status import CURVE_STATUSES, END_PRECEDENCE, FAILED, check_status, describe, outcome
from .traits import traits

#: Interior sample points closer than this (relative to the curve scale) to the closing point are dropped,
#: so that a closed curve has no near-duplicate of its first point before the exact copy at its end.
DUPLICATE_SPACING = 1e-9


class TracingError(RuntimeError):
    """Tracing could not start or go on; ``where`` is the point (3,) or None, ``status`` a short code
    (spatialkin.tracing.status)."""

    def __init__(self, message, where=None, status=FAILED):
        super().__init__(message)
        self.where = where
        self.status = check_status(status)

    @classmethod
    def of(cls, event, where=None, status=None, **fields):
        """The error of an event of spatialkin.tracing.status.MESSAGES at where: its message, the template filled
        with fields, and its status (or the one given, for an event whose status depends on the case)."""
        own, message = outcome(event, **fields)
        return cls(message, where=where, status=status or own)


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class CurveResult:
    """What tracing found about one component: a plain record; ``sol`` evaluates it. (A closed form's,
    spatialkin.tracing.exact.SampledResult, makes its points, s and params on first read, the same arrays
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

    def __post_init__(self):
        state = self.__dict__                   # (frozen: written as object.__setattr__ writes, at a third of its cost)
        for name, kind in (("closed", bool), ("length", float), ("tolerance", float), ("nfev", int),
                           ("wall_time", float)):
            state[name] = kind(state[name])
        if self.status not in CURVE_STATUSES:
            raise ValueError(f"a curve's status is one of {CURVE_STATUSES}, got {self.status!r}")


class Curve:
    """One connected component of the intersection of two surfaces, parametrised by arc length.

    Built once from a CurveResult (``Curve(result)``); its attributes are read-only. Evaluations go through the
    dense output ``result.sol``; ``max_distance`` is measured on first access.

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
        One of these (spatialkin.tracing.status); an open curve's is that of its ends, the first of
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
        What sk.intersect(..., certify=True) verified (spatialkin.tracing.certificate).
    topology : object or None
        The search of sk.intersect that found the component (spatialkin.tracing.topology).
    surfaces : (Surface, Surface)
        The two surfaces.
    result : CurveResult
        The record the curve was built from.
    """

    def __init__(self, result):
        if not isinstance(result, CurveResult):
            raise TypeError(f"a Curve is built from a CurveResult, got {type(result).__name__}")
        self._result = result

    @property
    def result(self):
        return self._result

    @property
    def surfaces(self):
        return self._result.sol.surfaces

    # --- dense evaluation (the record's dense output) -------------------------------------------------------
    def __call__(self, s):
        """Points (..., 3) on the curve at arc lengths s (...,), corrected onto both surfaces."""
        return self._result.sol(s)

    def tangent(self, s):
        """Unit tangents (..., 3) at s, pointing towards increasing s."""
        return self._result.sol.tangent(s)

    def parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s (u wrapped to (-pi, pi] where a sphere had to be re-charted)."""
        return self._result.sol.parameters(s)

    def predicted_parameters(self, s):
        """(u1, v1, u2, v2) (..., 4) at s from the solver's dense output alone, without the Newton correction:
        within the solver's tolerance of the curve, a cheap start for Newton (a sphere's (u, v) are those of
        the point on surface a, as in parameters())."""
        return self._result.sol.predicted_parameters(s)

    def derivatives(self, s):
        """(points, unit tangents C', curvature vectors C'') (..., 3) each at arc lengths s: exact, from the
        corrected points and the two surfaces' implicit functions, or in closed form (NaN at a singular
        point)."""
        return self._result.sol.derivatives(s)

    def closest(self, points):
        """Arc length (...,) of the curve point nearest to each point (..., 3), and the distance (...,)."""
        return self._result.sol.closest(points)

    def sample(self, n):
        """n points evenly spaced in arc length (for a closed curve the last equals the first)."""
        return self(np.linspace(0.0, self.length, int(n)))

    # --- measured against the surfaces ----------------------------------------------------------------------
    def distances(self, points=None):
        """Exact distances (N, 2) of points (default: self.points) to surface a and surface b."""
        pts = self.points if points is None else np.asarray(points, dtype=float)
        return np.stack([surf.distance(pts) for surf in self.surfaces], axis=-1)

    @functools.cached_property
    def max_distance(self):
        pts = self.points
        if len(self.s) > 1 and self.length > 0:
            pts = np.vstack([pts, self(0.5 * (self.s[1:] + self.s[:-1]))])
        return float(np.max(self.distances(pts))) if len(pts) else 0.0

    def to_bspline(self, tol=1e-8):
        """A C2 quintic B-spline (scipy.interpolate.BSpline, parameter: the arc length s) within tol times the
        scene scale of this curve, measured.

        Built from the exact points, unit tangents and curvature vectors at its knots (quintic Hermite data);
        the knots are refined until the distance between the spline and Newton-corrected points of the curve at
        the same s, measured at nine points inside every span, stays below 0.9 tol x scale. A closed curve gives
        a periodic spline (extrapolate='periodic').

        Parameters
        ----------
        tol : float
            Allowed deviation, relative to the scene scale (the smaller surface size).

        Returns
        -------
        scipy.interpolate.BSpline
            Degree 5, triple interior knots; ``spline.deviation`` is the largest measured distance (length
            unit), ``spline.checked`` how many curve points it was measured against.

        Raises
        ------
        ValueError
            For a non-positive tol, or a curve of length zero (a contact point).
        SplineToleranceError
            If tol lies below the round-off of the curve's points.
        """
        tol = check_positive("tol", tol)
        if self.length == 0:
            raise ValueError("a curve of length zero (a contact point) has no B-spline")
        from .start import scene_scale       # start imports this module
        return fit_spline(self.derivatives, 0.0, self.length, tol * scene_scale(*self.surfaces),
                          periodic=self.closed)

    def __len__(self):
        return len(self.points)

    def __repr__(self):
        kind = "closed" if self.closed else f"open ({self.status})"
        return (f"Curve({kind}, length={self.length:.6g}, points={len(self.points)}, "
                f"max_distance={self.max_distance:.2e})")


Curve.__doc__ = (Curve.__doc__.replace("{statuses}", describe(CURVE_STATUSES, 8))
                 .replace("{precedence}", ", ".join(f"'{s}'" for s in END_PRECEDENCE)))
#: The record's fields a Curve shows as read-only attributes of the same names (all but the dense output).
RECORD_FIELDS = tuple(f.name for f in dataclasses.fields(CurveResult) if f.name != "sol")
for _name in RECORD_FIELDS:
    setattr(Curve, _name, property(operator.attrgetter(f"_result.{_name}"), doc=f"CurveResult.{_name}"))


# --- states and parameters: helpers of the dense output (spatialkin.tracing.dense) and of sk.trace ----------------
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


def in_sk_order(curves, first_point=lambda c: c.points[0]):
    """The CurveResults sorted as sk.intersect returns them: longest first, then by first point (rounded to 9
    decimals); first_point reads a curve's first point (a closed form's without sampling the others)."""
    if len(curves) > 1:
        curves.sort(key=lambda c: (-c.length, tuple(np.round(first_point(c), 9))))
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
