"""The certificate of ``sk.intersect(a, b, certify=True)``: what was verified about each returned curve."""
import math

import numpy as np

from ..curve.status import TANGENT

#: Python extra that provides the ball arithmetic of the certified path.
EXTRA = "spatialkin[certify]"


class Certificate:
    """What ``sk.intersect(..., certify=True)`` proved about one returned curve, and what it did not.

    Proven (with outward-rounded interval arithmetic, so round-off cannot break it):

    - **The search discarded no component.** The topology stage (spatialkin.tracing.search.topology) searched the whole
      parameter domain of one surface: every box it discarded provably holds no root of the conditions that
      every component must meet somewhere (a zero of g on an edge or a seam, on a ring round an apex, or a point
      of the level whose tangent is normal to a fixed direction); the roots it kept are isolated and unique in
      their boxes (interval Newton, Krawczyk) or are singular points classified by the Hessian. ``boxes``,
      ``verified_roots`` and ``singular_points`` count that search; ``mode`` says which configuration was
      recognised ('general', 'coaxial': parallels of a common axis, found on one meridian; 'ruled': lines along a
      cylinder's axis); ``components`` is the number of curves returned.
    - **Each stored point is near a true point.** For stored point k a box of half-width ``radii[k]`` round it
      holds exactly one point of both (untrimmed) surfaces in the plane through it normal to the curve (the
      Krawczyk operator on F_a = 0, F_b = 0, t . (x - p) = 0, in arb ball arithmetic), so a true intersection
      point lies within ``radii[k] * sqrt(3)`` of it.

    Not proven:

    - that every root the search kept lies on one of the returned curves: that is decided by distance (the
      de-duplication's radius), so two components closer than it may come back as one curve, certified;
    - the arcs between stored points (dense evaluations are Newton-corrected and measured, not proven);
    - that two returned curves are different components, or that a curve's pieces joined at a node belong
      together (the tracer passes nodes straight through);
    - points where the surfaces touch (contacts, circles or lines of tangency) or branches cross: there the
      system is singular and ``radii`` is inf (those points come from the singular-point classification, or
      in closed form for the coaxial and ruled configurations).

    Parameters
    ----------
    radii : array_like, shape (N,)
        Proven half-width of the box round each stored point of the curve (length unit; inf where not proven).
    topology : Topology
        The search of sk.intersect (spatialkin.tracing.search.topology).
    components : int
        How many curves sk.intersect returned.

    Attributes
    ----------
    radii : ndarray, shape (N,)
    components : int
    mode : str
    boxes, verified_roots, singular_points : int
    search_seconds : float
    all_points_proven : bool
    max_distance_bound : float
        The largest proven distance from a stored point to a true intersection point, radii.max() * sqrt(3).

    References
    ----------
    .. [1] R. E. Moore, R. B. Kearfott, M. J. Cloud, Introduction to Interval Analysis, SIAM, 2009 (the
       Krawczyk operator, interval Newton).
    .. [2] R. B. Kearfott, M. Novoa, "Algorithm 681: INTBIS, a portable interval Newton/bisection package", ACM
       Trans. Math. Softw. 16(2), 1990, 152-157.

    Examples
    --------
    >>> import numpy as np
    >>> import spatialkin as sk
    >>> torus, sphere = sk.Torus(1.0, 0.4), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.3)))
    >>> curve = sk.intersect(torus, sphere, certify=True)[0]
    >>> cert = curve.certificate
    >>> cert.mode, cert.components, cert.all_points_proven
    ('general', 2, True)
    >>> bool(np.all(np.isfinite(cert.radii))), bool(cert.max_distance_bound < 1e-12)
    (True, True)
    """

    def __init__(self, radii, topology, components):
        self.radii = np.asarray(radii, dtype=float)
        self.components = int(components)
        self.mode = topology.mode
        self.boxes = topology.boxes
        self.verified_roots = topology.verified
        self.singular_points = topology.unresolved
        self.search_seconds = topology.seconds

    @property
    def all_points_proven(self):
        """True when every stored point has a finite radius."""
        return bool(self.radii.size) and bool(np.all(np.isfinite(self.radii)))

    @property
    def max_distance_bound(self):
        """The largest proven distance (Euclidean) from a stored point to a true intersection point."""
        return float(np.max(self.radii) * math.sqrt(3.0)) if self.radii.size else math.inf

    def __repr__(self):
        proven = int(np.sum(np.isfinite(self.radii)))
        return (f"Certificate(components={self.components}, mode={self.mode!r}, boxes={self.boxes}, "
                f"points proven {proven}/{self.radii.size}, max distance <= {self.max_distance_bound:.2e})")


def certificates(a, b, curves, topology):
    """The Certificate of each curve (CurveResults of every component found: radii from arb Krawczyk tests on the
    stored points)."""
    try:
        from .certify_points import certify_points
    except ImportError as err:          # python-flint missing
        raise ImportError(f"certify=True needs python-flint: pip install '{EXTRA}' ({err})") from None
    out = []
    for curve in curves:
        if curve.length == 0 or curve.status == TANGENT:
            radii = np.full(len(curve.points), math.inf)
        else:
            radii = certify_points(a, b, curve.points, curve.sol.tangent(curve.s))
        out.append(Certificate(radii, topology, len(curves)))
    return out
