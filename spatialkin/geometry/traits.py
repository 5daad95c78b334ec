"""Surface traits: what tracing asks of a kind of surface, declared once per kind, and their registry.

Every kind of surface declares, next to its class (spatialkin.geometry.surfaces.<kind>), one SurfaceTraits object: its
extent and size, the units and periodicity of (u, v), where its parametrisation collapses (chart poles and
apexes), its natural domain, its re-chart (the sphere's chart turned away from its poles), and the placement
knowledge of the topology stage (symmetry axes, rulings, coincidence, its polynomial implicit function).
``register(cls, traits)`` files the traits under the class and under the kind code that every surface writes to
``data[KIND]`` of its packed kernel data, and sets them as the class attribute ``traits`` (so ``surface.traits``);
tracing asks ``surface.traits`` or ``traits(data)`` and never switches on a kind code or on a surface class. A kind
that is not registered raises UnknownSurfaceKindError.

This module belongs to the tracing layer and imports only the kernels: tracing reads the traits without importing
the domain layer, whose kind modules register themselves here.

Limits: the kernels (spatialkin.kernels.geometry.surfaces and spatialkin.kernels.geometry.interval) are compiled and evaluate a
closed set of geometries, chosen by ``data[GEOMETRY]`` (plane, sphere, cylinder, cone, torus). A new kind over
one of these geometries (another trim, chart or set of traits) is its own module plus a registration; a kind
whose geometry is new also needs its branches in those two kernel modules.
"""
import math

import numpy as np

from ..kernels.geometry import surfaces as ks

__all__ = ["SurfaceTraits", "UnknownSurfaceKindError", "register", "unregister", "traits", "check_surface",
           "power_of_two", "ANGLE", "LENGTH", "POINT", "AXIS", "NORMAL", "TRANSLATION", "SCALING", "GEOMETRIES",
           "FULL_TURN"]

# --- vocabulary of the traits ----------------------------------------------------------------------------------
#: Units of a surface parameter: an angle (radians, unit step 1) or a length (the user's unit, unit step = scale).
ANGLE, LENGTH = "angle", "length"
#: Symmetries (SurfaceTraits.symmetry): a surface of revolution about any line through a centre (a sphere), about
#: one axis (a torus, cylinder, cone), or about any line along a direction (a plane and its normal).
POINT, AXIS, NORMAL = "point", "axis", "normal"
#: Rulings (SurfaceTraits.ruling): straight lines along a direction (invariant under translation along it, a
#: cylinder) or through an apex (invariant under scaling about it, a cone).
TRANSLATION, SCALING = "translation", "scaling"
#: Geometry codes the compiled kernels evaluate (spatialkin.kernels.geometry.surfaces).
GEOMETRIES = (ks.PLANE, ks.SPHERE, ks.CYLINDER, ks.CONE, ks.TORUS)
#: The full turn of an angle parameter.
FULL_TURN = (-math.pi, math.pi)


class UnknownSurfaceKindError(TypeError):
    """A surface class or kind code with no registered traits (the tracer knows nothing of its geometry)."""


class SurfaceTraits:
    """What tracing and the topology stage ask of one kind of surface.

    A kind subclasses this, sets the class attributes below (``register`` refuses a kind that leaves one unset)
    and overrides the methods whose default does not describe it. Methods take the placed surface (its
    ``frame``, ``u_range``, ``v_range``, ``data`` and shape attributes) and never a kind code.
    """

    #: Kind code written to data[KIND] (unique among the registered kinds).
    code = None
    #: Geometry code written to data[GEOMETRY]: which compiled parametrisation and implicit function evaluate it.
    geometry = None
    #: Name in messages.
    name = None
    #: Order of preference as the parametrised surface P of the topology stage (lower first).
    rank = None
    #: Unit of u and of v: ANGLE or LENGTH.
    units = None
    #: Whether u and whether v is periodic (period 2 pi).
    periodic = None
    #: Local axis (0 x, 1 y, 2 z) along which each parameter measures length (None for an angle): where a bounding
    #: ball limits an unbounded parameter, and where a line is clipped to the trims.
    parameter_axes = None
    #: True when the surface is closed and bounded (it has no edge).
    compact = None
    #: True when the tracer turns its chart at every segment start (``rechart``) so that the chart's poles
    #: (the lines v = +-pi/2, ``poles``) are never reached: its user parameters then come from the points, and a
    #: segment ends where |cos v| falls to the pole guard.
    recharts = None
    #: True when its parametrisation may degenerate on the curve (an apex, a horn or spindle torus's axis points):
    #: the tracer watches the relative area element and jumps the apex.
    area_watch = None
    #: True when it may be the parametrised surface P of a coaxial placement: its lines v = const are parallels
    #: about its local z axis (once ``aligned``).
    has_parallels = None

    REQUIRED = ("code", "geometry", "name", "rank", "units", "periodic", "parameter_axes", "compact", "recharts",
                "area_watch", "has_parallels")

    # --- size and extent ---------------------------------------------------------------------------------------
    def size(self, surface):
        """Characteristic length (Surface.size): a radius, a torus's outer radius; 1 where the shape has none."""
        raise NotImplementedError(f"{self.name}: size is not declared")

    def scale_length(self, surface):
        """The length that sets the scene scale of an intersection, or None where the shape has none (a plane,
        an untrimmed cone)."""
        return float(self.size(surface))

    def extent(self, surface):
        """A length that bounds the (trimmed) surface, inf where it is unbounded (the default max_length)."""
        return self.size(surface)

    def bounding_ball(self, surface):
        """(centre (3,), radius) of a ball holding the (trimmed) surface, or None when it is unbounded."""
        raise NotImplementedError(f"{self.name}: bounding_ball is not declared")

    def asymptote(self, surface):
        """(w, angle, offset, origin) of an unbounded surface's directions to infinity, or None where the surface is
        bounded: every point x of the untrimmed surface lies within the angle asin(offset / |x - origin|), seen
        from origin, of the double cone of unit vectors at ``angle`` (in [0, pi/2]) from +-w (unit, (3,)): a
        cylinder's axis (angle 0, offset its radius), a cone's (its half angle, from its apex), a plane's normal
        (pi/2). spatialkin.geometry.asymptotic reads it."""
        return None

    # --- parameters ----------------------------------------------------------------------------------------------
    def natural_domain(self, surface):
        """((u_lo, u_hi), (v_lo, v_hi)) of the surface's own chart: the full turn for a periodic angle, else the
        trims (infinite where unbounded)."""
        (u_range, v_range), (u_periodic, v_periodic) = surface.bounds, self.periodic
        return FULL_TURN if u_periodic else tuple(u_range), FULL_TURN if v_periodic else tuple(v_range)

    def parameter_units(self, scale):
        """Length of a unit step of (u, v) (2,): 1 for an angle, scale for a length."""
        u_unit, v_unit = self.units
        return np.array((scale if u_unit == LENGTH else 1.0, scale if v_unit == LENGTH else 1.0))

    @property
    def angular(self):
        """(bool, bool): which of u and v are angles."""
        return tuple(unit == ANGLE for unit in self.units)

    def trim_slack(self, surface, slack):
        """(du, dv): a distance slack on the surface as parameter slacks at its trims."""
        return slack, slack

    # --- charts --------------------------------------------------------------------------------------------------
    def rechart(self, data, point, tangent, bend=None):
        """Packed data of the surface with its chart turned at point (kinds with ``recharts``)."""
        raise NotImplementedError(f"{self.name}: no re-chart (recharts is False)")

    def poles(self, surface):
        """Values of v along which the chart collapses to one point of a smooth surface (a sphere's poles)."""
        return []

    def apexes(self, surface):
        """Values of v along which the chart collapses to a singular point of the surface (a cone's apex)."""
        return []

    def collapse_lines(self, surface):
        """Poles and apexes: every v where the parametrisation collapses to one point."""
        return self.poles(surface) + self.apexes(surface)

    def general_chart(self, p, q):
        """The surface as the parametrised surface P of a general placement, its chart placed for the search
        of Q (a sphere turns its poles away from Q)."""
        return p

    # --- placement knowledge of the topology stage --------------------------------------------------------------
    def symmetry(self, surface):
        """(POINT, centre), (AXIS, point, unit direction), (NORMAL, unit direction), or None: the lines about which
        the surface is a surface of revolution."""
        return None

    def aligned(self, surface, axis):
        """The surface re-placed so that its local z is the line axis = (point, direction) (a common axis of
        revolution; kinds with an axis of their own already turn about it)."""
        return surface

    def trim_breaks_revolution(self, surface):
        """True when the trims are not invariant under its turns about a common axis (a plane's rectangle)."""
        return False

    def ruling(self, surface):
        """(TRANSLATION, unit direction), (SCALING, apex), or None: the straight lines the surface is made of, when
        the topology stage can use them."""
        return None

    def cross_section(self, v_lo, v_hi):
        """The v of the cross-section that cuts every ruling once (ruled kinds), within [v_lo, v_hi]."""
        return 0.5 * (v_lo + v_hi)

    def keeps_translation(self, surface, direction, same):
        """True when the surface is invariant under translation along direction (to the direction tolerance
        ``same``); the placements recognised, not every one that holds."""
        return False

    def keeps_scaling(self, surface, centre, tol):
        """True when the surface is invariant under scaling about centre (within the length tolerance ``tol``)."""
        return False

    def same_surface(self, a, b, tol, same):
        """True when a and b (both of this kind) are the same untrimmed surface: positions within tol, directions
        and angles within same."""
        raise NotImplementedError(f"{self.name}: same_surface is not declared")

    def trims_overlap(self, a, b):
        """For the same surface given twice: True when the trimmed patches share a piece of positive area."""
        return True

    # --- the polynomial implicit function -----------------------------------------------------------------------
    def implicit_jets(self, surface, q):
        """(F (N,), grad F (N, 3), hess F (N, 3, 3)) of the polynomial implicit function at local points q (N, 3)."""
        raise NotImplementedError(f"{self.name}: implicit_jets is not declared")

    def __repr__(self):
        return f"<{type(self).__name__} {self.name!r} code={self.code} geometry={self.geometry}>"


def power_of_two(x):
    """The power of two nearest to x > 0 (1 for x not positive and finite). Tolerances that feed iterations (Newton
    and root-finder stops, solve_ivp's time unit) are taken relative to the scene's scale rounded so: a scene scaled
    by 2^k then runs on the same numbers to the bit, and one whose scale is within a factor sqrt(2) of 1 on the
    same numbers as with the absolute tolerance."""
    return math.ldexp(1.0, round(math.log2(x))) if x > 0.0 and math.isfinite(x) else 1.0


# --- the registry ------------------------------------------------------------------------------------------------
_BY_CODE = {}
_BY_CLASS = {}


def register(cls, kind):
    """File the traits ``kind`` (a SurfaceTraits) under the surface class cls and under kind.code.

    Raises
    ------
    TypeError
        kind is not a SurfaceTraits.
    ValueError
        A declaration is missing or out of range, or the class or the code is registered already.
    """
    if not isinstance(kind, SurfaceTraits):
        raise TypeError(f"traits of {cls.__name__} must be a SurfaceTraits, got {type(kind).__name__}")
    missing = [name for name in SurfaceTraits.REQUIRED if getattr(kind, name) is None]
    if missing:
        raise ValueError(f"traits of {cls.__name__} leave {', '.join(missing)} undeclared")
    if kind.geometry not in GEOMETRIES:
        raise ValueError(f"traits of {cls.__name__}: geometry {kind.geometry!r} is not one the kernels evaluate "
                         f"{GEOMETRIES} (a new geometry needs its kernel branches)")
    if len(kind.units) != 2 or any(unit not in (ANGLE, LENGTH) for unit in kind.units):
        raise ValueError(f"traits of {cls.__name__}: units must be two of {ANGLE!r}, {LENGTH!r}, got {kind.units!r}")
    if not isinstance(kind.code, int) or kind.code in _BY_CODE or cls in _BY_CLASS:
        raise ValueError(f"{cls.__name__}: kind code {kind.code!r} or the class is registered already (or the code "
                         "is not an int)")
    _BY_CODE[kind.code] = kind
    _BY_CLASS[cls] = kind
    cls.traits = kind               # (read as surface.traits on the hot paths: an attribute, not a call)
    return kind


def unregister(cls):
    """Remove the kind registered under the class cls (a test kind's cleanup)."""
    kind = _BY_CLASS.pop(cls)
    del _BY_CODE[kind.code]
    del cls.traits


def traits(x):
    """The SurfaceTraits of a surface, a surface class, packed kernel data (data[KIND]) or a kind code.

    Raises
    ------
    UnknownSurfaceKindError
        Nothing is registered for x.
    """
    kind = _BY_CLASS.get(type(x))          # a surface of a registered class (the common call)
    if kind is not None:
        return kind
    if isinstance(x, np.ndarray):
        return _by_code(int(x[ks.KIND]))
    if isinstance(x, (int, np.integer)):
        return _by_code(int(x))
    cls = x if isinstance(x, type) else type(x)
    for base in cls.__mro__:
        kind = _BY_CLASS.get(base)
        if kind is not None:
            return kind
    raise UnknownSurfaceKindError(f"no surface traits registered for {cls.__name__} (registered: "
                                  f"{', '.join(c.__name__ for c in _BY_CLASS)})")


def _by_code(code):
    kind = _BY_CODE.get(code)
    if kind is None:
        raise UnknownSurfaceKindError(f"no surface traits registered for kind code {code} (registered: "
                                      f"{sorted(_BY_CODE)})")
    return kind


def check_surface(name, value):
    """value when it is a surface of a registered kind, else TypeError naming the argument."""
    if type(value) in _BY_CLASS:            # (a surface of a registered class: the common call)
        return value
    try:
        traits(type(value))
    except UnknownSurfaceKindError:
        raise TypeError(f"{name} must be a spatialkin surface ({', '.join(c.__name__ for c in _BY_CLASS)}), "
                        f"got {type(value).__name__}") from None
    return value
