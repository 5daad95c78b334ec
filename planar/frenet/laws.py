"""Laws phi(s) of a crank mechanism's driven link, relative to the Frenet trihedron on the crank pin.

The crank pin A runs on a circle of curvature k (radius 1/k) at arc length s; the link passes through A at
the angle phi(s) to the tangent tau (anticlockwise). Each law gives phi, phi' and phi'' (' = d/ds) at once.
Convention (that of the paper's eq. (11)): A(s) = (sin ks, -cos ks)/k, tau = (cos ks, sin ks),
n = (-sin ks, cos ks), the crank angle is ks.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven
member using Frenet trihedron", 2017. The laws' derivatives are derived from its schemes and checked against
finite differences; its printed crank-rocker derivatives (15), (16) have the wrong sign of the gamma term, and
the corrected ones are used (at d = 1/k they give phi' = -k/2, the uniform turn of a chord through the pin).
"""
import numpy as np

from spatialkin._lib.validation import check_choice, check_finite, check_length, check_positive

from . import kernels as lk

#: Relative slack of the crank-slider's full-turn condition e + 1/k <= L (round-off in the given lengths).
TURN_SLACK = 1e-12


def kernel_law(kernel, s, *params):
    """(phi, dphi, ddphi, cos gamma, sin gamma, cos ks, sin ks) shaped like s from a jitted law kernel
    (planar.frenet.kernels)."""
    s = check_finite("s", s)
    out = np.empty((7, s.size))
    kernel(*params, np.ascontiguousarray(s).ravel(), *out)
    return tuple(o.reshape(s.shape) for o in out)


class Law:
    """Base: a law evaluates (phi, phi', phi'') at arc lengths s of the crank pin's circle."""

    k = 1.0

    def __repr__(self):
        names = [n for n in ("k", "e", "L", "d", "side", "branch") if n in vars(self)]
        return f"{type(self).__name__}(" + ", ".join(f"{n}={getattr(self, n)!r}" for n in names) + ")"

    def evaluate(self, s):
        """(phi, dphi, ddphi), arrays shaped like s."""
        return self.evaluate_with_direction(s)[:3]

    def evaluate_with_direction(self, s):
        """(phi, dphi, ddphi, cos gamma, sin gamma, cos ks, sin ks): the law with the link's direction
        gamma = ks + phi and the trihedron's tangent tau = (cos ks, sin ks)."""
        phi, dphi, ddphi = self.evaluate(s)
        ks = self.k * np.asarray(s, dtype=float)
        gamma = ks + phi
        return phi, dphi, ddphi, np.cos(gamma), np.sin(gamma), np.cos(ks), np.sin(ks)

    def gamma(self, s):
        """Angle of the link to the fixed x-axis, gamma = ks + phi (eq. (1))."""
        s = check_finite("s", s)
        return self.k * s + self.evaluate(s)[0]


class CrankSlider(Law):
    """Offset crank-slider: the slider (rho = L) on the straight guide y = side * e.

    The crank pin A runs on the circle of radius 1/k about the origin O (A = (sin ks, -cos ks)/k); the rod AB
    of length L keeps its slider B on the guide, so sin(ks + phi) = (k h + cos ks) / (k L), h = side * e [1]_.
    phi' and phi'' come in closed form.

    Parameters
    ----------
    k : float
        Curvature of the crank circle, 1 / crank radius (per length unit), > 0.
    e : float
        Guide offset from the crank centre (length), >= 0.
    L : float
        Rod length from the pin A to the slider B (length), > 0.
    side : {1, -1}
        Which side of the crank centre the guide lies on.
    branch : {0, 1}
        Assembly: 0 takes phi = asin(q) - ks, 1 takes pi - asin(q) - ks, q = (k h + cos ks) / (k L).

    Attributes
    ----------
    k, e, L : float
    side, branch : int
    h : float
        side * e, the guide's y.

    Raises
    ------
    ValueError
        Naming `k`, `e`, `L`, `side` or `branch` when out of range; unless e + 1/k <= L (the rod must reach
        the guide at every crank angle).

    References
    ----------
    .. [1] S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms'
       driven member using Frenet trihedron", 2017.

    Examples
    --------
    Crank radius 2 (k = 0.5), guide offset 1, rod 4: the slider stays on the guide y = 1 over a turn
    (s from 0 to 2 pi / k):

    >>> import numpy as np
    >>> import planar
    >>> law = planar.CrankSlider(0.5, 1.0, 4.0)
    >>> s = np.linspace(0.0, 4 * np.pi, 9)
    >>> phi, dphi, ddphi = law.evaluate(s)
    >>> phi.shape, dphi.shape, ddphi.shape
    ((9,), (9,), (9,))
    >>> np.allclose(planar.DrivenLink(law).position(s, 4.0)[:, 1], 1.0)
    True
    >>> planar.CrankSlider(0.5, 2.0, 3.0)
    Traceback (most recent call last):
    ...
    ValueError: the crank-slider needs e + 1/k <= L to turn fully: e + 1/k = 4 > L = 3
    """

    def __init__(self, k, e, L, side=1, branch=0):
        self.k = check_length("k", k)              # (1 / length: within the lengths' range too)
        self.e = check_length("e", e, allow_zero=True)
        self.L = check_length("L", L)
        side = check_choice("side", side, (1, -1))
        branch = check_choice("branch", branch, (0, 1))
        if self.e + 1.0 / self.k > self.L * (1 + TURN_SLACK):
            raise ValueError(f"the crank-slider needs e + 1/k <= L to turn fully: e + 1/k = "
                             f"{self.e + 1 / self.k:.6g} > L = {self.L:.6g}")
        self.side, self.branch = side, branch
        self.h = side * self.e

    def evaluate_with_direction(self, s):
        return kernel_law(lk.crank_slider_law, s, self.k, self.h, self.L, self.branch)


class CrankRocker(Law):
    """Crank-rocker through a fixed stone at distance d from the crank centre O (the stone at (d, 0)).

    The link slides through the stone, so it lies along the line from the crank pin A to the stone:
    phi = atan2(cos ks, kd - sin ks) - ks, continuous in s, with phi' = -k^2 d (kd - sin ks) / D and
    phi'' = -d k^3 (k^2 d^2 - 1) cos ks / D^2, D = 1 + k^2 d^2 - 2 kd sin ks [1]_ (the paper's printed (15), (16)
    have the wrong sign of the gamma term; these are the corrected derivatives), computed as
    D = (kd - sin ks)^2 + cos^2 ks with kd - sin ks = (kd - 1) + 2 sin^2(pi/4 - ks/2), which keep their relative
    accuracy where the pin passes near the stone (d near 1/k). d > r (r = 1/k): a rocking stone; d = r: the link
    turns uniformly at -k/2 per unit s; d < r: a rotating stone.

    Parameters
    ----------
    k : float
        Curvature of the crank circle, 1 / crank radius (per length unit), > 0.
    d : float
        Distance of the stone from the crank centre (length), > 0.

    Attributes
    ----------
    k, d : float
    stone : ndarray, shape (2,)
        The stone's position (d, 0).

    Raises
    ------
    ValueError
        Naming `k` or `d` when it is not a positive finite number within the supported lengths (1e-32 to 1e32;
        TypeError when its type is no real number's).

    References
    ----------
    .. [1] S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms'
       driven member using Frenet trihedron", 2017.

    Examples
    --------
    >>> import numpy as np
    >>> import planar
    >>> law = planar.CrankRocker(0.5, 4.0)                 # a rocking stone, d > 1/k = 2
    >>> s = np.linspace(0.0, 4 * np.pi, 7)
    >>> link = planar.DrivenLink(law)
    >>> pin = link.position(s, 0.0)
    >>> reach = np.linalg.norm(law.stone - pin, axis=1)    # the link's point at the stone
    >>> np.allclose(link.position(s, reach), law.stone)
    True
    >>> np.allclose(planar.CrankRocker(0.5, 2.0).evaluate(s[:3])[1], -0.25)    # d = 1/k: phi' = -k/2
    True
    """

    def __init__(self, k, d):
        self.k = check_length("k", k)
        self.d = check_length("d", d)

    def evaluate_with_direction(self, s):
        return kernel_law(lk.crank_rocker_law, s, self.k, self.d)

    @property
    def stone(self):
        """The stone's position (d, 0) (2,)."""
        return np.array([self.d, 0.0])


class LawFromFunctions(Law):
    """A law from user functions phi(s), phi'(s), phi''(s) (vectorised callables) on a circle of curvature k.

    Parameters
    ----------
    k : float
        Curvature of the crank circle (per length unit), > 0.
    phi, dphi, ddphi : callable
        s (array) -> phi (radians), phi' and phi'' (derivatives in s), broadcast to the shape of s.

    Raises
    ------
    ValueError
        Naming `k` or a function that is not callable; at evaluation, when the functions return non-finite values.
    """

    def __init__(self, k, phi, dphi, ddphi):
        self.k = check_positive("k", k)
        for name, f in (("phi", phi), ("dphi", dphi), ("ddphi", ddphi)):
            if not callable(f):
                raise ValueError(f"{name} must be callable, got {type(f).__name__}")
        self._f = (phi, dphi, ddphi)

    def evaluate(self, s):
        s = check_finite("s", s)
        out = tuple(np.broadcast_to(np.asarray(f(s), dtype=float), s.shape).copy() for f in self._f)
        if not all(np.all(np.isfinite(x)) for x in out):
            raise ValueError("the law's functions returned non-finite values (outside their domain?)")
        return out


class LawFromGamma(LawFromFunctions):
    """A law from the link's angle to Ox, gamma(s), with gamma' and gamma'': phi = gamma - ks (eq. (1)).

    Parameters
    ----------
    k : float
        Curvature of the crank circle (per length unit), > 0.
    gamma, dgamma, ddgamma : callable
        s (array) -> the link's angle to the x-axis (radians) and its first and second derivatives in s.
    """

    def __init__(self, k, gamma, dgamma, ddgamma):
        k = check_positive("k", k)
        super().__init__(k, lambda s: gamma(s) - k * s, lambda s: np.asarray(dgamma(s)) - k, ddgamma)
