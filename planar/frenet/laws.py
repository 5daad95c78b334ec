"""Laws phi(s) of a crank mechanism's driven link, relative to the Frenet trihedron on the crank pin.

The crank pin A runs on a circle of curvature k (radius 1/k) at arc length s; the link passes through A at
the angle phi(s) to the tangent tau (anticlockwise). Each law gives phi, phi' and phi'' (' = d/ds) at once.
Convention (../shared/reference/frenet-planar.md): A(s) = (sin ks, -cos ks)/k, tau = (cos ks, sin ks),
n = (-sin ks, cos ks), the crank angle is ks.

References
----------
Seed 000 and ../shared/reference/frenet-planar.md (formulas reconstructed; the printed (15), (16) have the
wrong sign of the gamma term: the corrected derivatives are used).
"""
import numpy as np

from spatialkin.validation import check_choice, check_finite, check_nonnegative, check_positive

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
    """Offset crank-slider: the slider (rho = L) on the guide y = side * e.

    Parameters
    ----------
    k : float          curvature of the crank circle (1 / crank radius)
    e : float          guide offset (>= 0)
    L : float          rod length A to slider
    side : +1 or -1    which side of the crank centre the guide lies on
    branch : 0 or 1    assembly: 0 takes phi = asin(q) - ks, 1 takes pi - asin(q) - ks

    Raises ValueError unless e + 1/k <= L (the rod must reach the guide at every crank angle).
    """

    def __init__(self, k, e, L, side=1, branch=0):
        self.k = check_positive("k", k)
        self.e = check_nonnegative("e", e)
        self.L = check_positive("L", L)
        check_choice("side", side, (1, -1))
        check_choice("branch", branch, (0, 1))
        if self.e + 1.0 / self.k > self.L * (1 + TURN_SLACK):
            raise ValueError(f"the crank-slider needs e + 1/k <= L to turn fully: e + 1/k = "
                             f"{self.e + 1 / self.k:.6g} > L = {self.L:.6g}")
        self.side, self.branch = side, branch
        self.h = side * self.e

    def evaluate_with_direction(self, s):
        return kernel_law(lk.crank_slider_law, s, self.k, self.h, self.L, self.branch)


class CrankRocker(Law):
    """Crank-rocker through a fixed stone at distance d from the crank centre O; in this convention the
    stone sits at (d, 0). d > r (r = 1/k): a rocking stone; d = r: the link turns uniformly at -k/2 per unit
    s; d < r: a rotating stone (no arccos break: phi = atan2(cos ks, kd - sin ks) - ks, continuous)."""

    def __init__(self, k, d):
        self.k = check_positive("k", k)
        self.d = check_positive("d", d)

    def evaluate_with_direction(self, s):
        return kernel_law(lk.crank_rocker_law, s, self.k, self.d)

    @property
    def stone(self):
        return np.array([self.d, 0.0])


class LawFromFunctions(Law):
    """A law from user functions phi(s), phi'(s), phi''(s) (vectorised callables) on a circle of curvature k."""

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
    """A law from the link's angle to Ox, gamma(s), with gamma' and gamma'': phi = gamma - ks (eq. (1))."""

    def __init__(self, k, gamma, dgamma, ddgamma):
        k = check_positive("k", k)
        super().__init__(k, lambda s: gamma(s) - k * s, lambda s: np.asarray(dgamma(s)) - k, ddgamma)
