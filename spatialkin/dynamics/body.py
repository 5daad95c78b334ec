"""Mass properties of a link: its mass, centre of mass and inertia tensor in the link's own frame.

Units: mass in kg, lengths in the mechanism's length unit (the looper drive's: mm), so an inertia tensor is in
kg x (length unit)^2.

References
----------
J. L. Meriam, L. G. Kraige, Engineering Mechanics: Dynamics, Wiley (moments of inertia of slender rods and discs).
"""
import numpy as np

from .._lib.validation import TOO_LARGE, check_nonnegative, check_vector

#: An inertia tensor's asymmetry and negative eigenvalues allowed, relative to its largest entry (round-off of
#: values typed or computed elsewhere).
INERTIA_RTOL = 1e-9


class Body:
    """The mass properties of one link, in the link's own frame (its origin and axes).

    Parameters
    ----------
    mass : float
        kg, >= 0 (0: a massless link).
    com : array_like (3,)
        The centre of mass in the link's frame (length unit).
    inertia : array_like (3, 3)
        The inertia tensor about the centre of mass, in the link's axes (kg x length unit^2): symmetric, positive
        semi-definite.

    Raises
    ------
    ValueError
        Naming the key: a negative or non-finite mass, a centre of mass that is not 3 finite numbers, an inertia
        tensor that is not 3 x 3, finite, symmetric and positive semi-definite.

    Examples
    --------
    >>> from spatialkin.dynamics import Body
    >>> rod = Body.rod(0.2, 30.0)                     # 200 g, 30 mm along the link's x axis from its origin
    >>> rod.com.tolist(), round(float(rod.inertia[1, 1]), 6)     # m L^2 / 12 about the centre
    ([15.0, 0.0, 0.0], 15.0)
    >>> Body(-1.0)
    Traceback (most recent call last):
    ...
    ValueError: mass must be a finite number >= 0 (kg), got -1.0
    """

    __slots__ = ("mass", "com", "inertia")

    def __init__(self, mass, com=(0.0, 0.0, 0.0), inertia=None):
        try:
            mass = float(mass)
        except OverflowError:
            raise ValueError(f"mass must be a finite number >= 0 (kg), got {TOO_LARGE}") from None
        except (TypeError, ValueError):
            raise ValueError(f"mass must be a finite number >= 0 (kg), got {mass!r}") from None
        if not (np.isfinite(mass) and mass >= 0):
            raise ValueError(f"mass must be a finite number >= 0 (kg), got {mass!r}")
        self.mass = mass
        self.com = check_vector("com", com)
        inertia = np.zeros((3, 3)) if inertia is None else np.array(inertia, dtype=float)
        if inertia.shape != (3, 3) or not np.all(np.isfinite(inertia)):
            raise ValueError(f"inertia must be a finite 3 x 3 tensor (kg x length^2), got shape {inertia.shape}")
        scale = max(float(np.max(np.abs(inertia))), np.finfo(float).tiny)
        if np.max(np.abs(inertia - inertia.T)) > INERTIA_RTOL * scale:
            raise ValueError("inertia must be symmetric: max |I - I^T| = "
                             f"{float(np.max(np.abs(inertia - inertia.T))):.3g}")
        smallest = float(np.min(np.linalg.eigvalsh(0.5 * (inertia + inertia.T))))
        if smallest < -INERTIA_RTOL * scale:
            raise ValueError(f"inertia must be positive semi-definite: its smallest eigenvalue is {smallest:.6g}")
        self.inertia = 0.5 * (inertia + inertia.T)

    @classmethod
    def point(cls, mass, at=(0.0, 0.0, 0.0)):
        """A point mass (kg) at `at` in the link's frame."""
        return cls(mass, at)

    @classmethod
    def rod(cls, mass, length, axis=(1.0, 0.0, 0.0), start=(0.0, 0.0, 0.0)):
        """A slender rod of the given mass (kg) and length from `start` along the unit `axis` (link frame):
        centre at its middle, m L^2 / 12 about any axis through it normal to the rod, nothing about the rod."""
        a = _unit_axis(axis)
        length = check_nonnegative("length", length)
        inertia = float(mass) * length ** 2 / 12.0 * (np.eye(3) - np.outer(a, a)) if np.isfinite(mass) else None
        return cls(mass, check_vector("start", start) + 0.5 * length * a, inertia)

    @classmethod
    def disc(cls, mass, radius, axis=(0.0, 0.0, 1.0), centre=(0.0, 0.0, 0.0)):
        """A thin disc of the given mass (kg) and radius about the unit `axis` through `centre` (link frame):
        m r^2 / 2 about its axis, m r^2 / 4 about a diameter."""
        a = _unit_axis(axis)
        radius = check_nonnegative("radius", radius)
        quarter = float(mass) * radius ** 2 / 4.0 if np.isfinite(mass) else np.nan
        return cls(mass, centre, quarter * (np.eye(3) - np.outer(a, a)) + 2.0 * quarter * np.outer(a, a))

    def __repr__(self):
        return (f"Body(mass={self.mass:g}, com=({', '.join(f'{x:g}' for x in self.com)}), "
                f"inertia diag=({', '.join(f'{x:g}' for x in np.diag(self.inertia))}))")


def _unit_axis(axis):
    """The unit vector along `axis` (3 finite numbers, not zero; ValueError naming it otherwise)."""
    a = check_vector("axis", axis)
    norm = float(np.linalg.norm(a))
    if norm == 0:
        raise ValueError("axis must not be zero")
    return a / norm


def check_bodies(bodies, links):
    """The bodies as {link: Body} (None: none; links not named are massless); ValueError naming a link not among
    `links`, or a value that is not a Body."""
    if bodies is None:
        return {}
    if not isinstance(bodies, dict):
        raise ValueError(f"bodies must be a dict of link name -> Body (links {list(links)}), got "
                         f"{type(bodies).__name__}")
    for name, body in bodies.items():
        if name not in links:
            raise ValueError(f"bodies: unknown link {name!r}; the links are {list(links)}")
        if not isinstance(body, Body):
            raise ValueError(f"bodies[{name!r}] must be a spatialkin.dynamics.Body, got {type(body).__name__}")
    return dict(bodies)


def combined(*bodies):
    """One Body for several rigidly joined ones (the same link frame): their total mass, the centre of their masses
    and the inertia about it (each one's own plus m |d|^2 I - m d d^T, d its centre from the common one)."""
    mass = sum(b.mass for b in bodies)
    if mass == 0:
        return Body(0.0)
    com = sum(b.mass * b.com for b in bodies) / mass
    inertia = np.zeros((3, 3))
    for b in bodies:
        d = b.com - com
        inertia += b.inertia + b.mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return Body(mass, com, inertia)
