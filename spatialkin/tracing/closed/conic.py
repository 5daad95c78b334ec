"""A conic arc in closed form (a line, an ellipse, a branch of a hyperbola, a parabola), parametrised by arc length:
the dense output of the plane-quadric and plane-plane intersections of spatialkin.tracing.closed.forms.

The conic is C(t) = centre + P f(t) + Q g(t), P and Q orthogonal, with (f, g) = (0, t) for a line, (cos t, sin t)
for an ellipse, (cosh t, sinh t) for a hyperbola's branch and (t^2, t) for a parabola (Q a unit vector for the line
and the parabola, |P| <= |Q| for the ellipse). Its arc length from t = 0, S(t), is exact: t for a line, the
incomplete elliptic integral of the second kind for an ellipse, a closed form for a parabola, composite
Gauss-Legendre quadrature to round-off for a hyperbola; s -> t by Newton.

References
----------
Abramowitz and Stegun, Handbook of Mathematical Functions, 17.2 (E(phi | m)) and 25.4.29 (Gauss-Legendre).
"""
import functools
import math

import numpy as np
from scipy.special import cython_special, ellipeinc

from ..curve.exact import EXACT_SAMPLES, ExactSolution, counting
from ...geometry.quadrature import gauss_legendre

LINE, ELLIPSE, HYPERBOLA, PARABOLA = "line", "ellipse", "hyperbola", "parabola"
#: Gauss-Legendre nodes per panel of a hyperbola's arc-length quadrature ...
GL_NODES = 16
#: ... and the widest panel in t; a panel is also no wider than the distance from the real axis to the nearest
#: zero of |C'(t)|^2 (atan(|Q| / |P|), at t = 0), so that 16 nodes reach round-off (Bernstein ellipse rho > 4).
GL_PANEL = 0.5
#: Newton steps of s -> t from the interpolated guess between the stored samples (quadratic convergence: the
#: guess is within about (sample spacing)^2 x curvature, so three steps reach round-off; one more for margin).
NEWTON_STEPS = 4

#: The shapes whose arc length S(t) is computed value by value (the same at a t whatever else is evaluated with
#: it): their length comes from the two ends, their knots are made on first use.
ENDWISE = (LINE, ELLIPSE)
#: A quarter turn, the last of quarter_turn's angles (np.linspace ends on its stop).
QUARTER = 0.5 * math.pi


def basis(shape, t, order=0, lib=np):
    """(f, g) of a conic of the given shape at t, or their derivatives of the given order (0, 1, 2): t an array
    with lib numpy, or one float with lib math (the closed forms' scalar arithmetic)."""
    if shape == ELLIPSE:
        c, s = lib.cos(t), lib.sin(t)
        return (c, s) if order == 0 else (-s, c) if order == 1 else (-c, -s)
    if shape == HYPERBOLA:
        c, s = lib.cosh(t), lib.sinh(t)
        return (s, c) if order == 1 else (c, s)
    zero, one = (np.zeros_like(t), np.ones_like(t)) if lib is np else (0.0, 1.0)
    if shape == PARABOLA:
        return (t * t, t) if order == 0 else (2.0 * t, one) if order == 1 else (2.0 * one, zero)
    return (zero, t) if order == 0 else (zero, one) if order == 1 else (zero, zero)


class Conic:
    """The conic C(t) = centre + P f(t) + Q g(t) of the given shape (see the module docstring), with the arc
    length S(t) from t = 0 (a hyperbola's quadrature covers [t_lo, t_hi]). centre, P and Q are given as 3 floats
    each and read as arrays (3,), made on first use (the arc length needs only |P|^2 and |Q|^2)."""

    def __init__(self, shape, centre, P, Q, t_lo=0.0, t_hi=0.0):
        self.shape, self.rows = shape, (centre, P, Q)
        (p0, p1, p2), (q0, q1, q2) = P, Q
        self.p2, self.q2 = p0 * p0 + p1 * p1 + p2 * p2, q0 * q0 + q1 * q1 + q2 * q2     # (P @ P, Q @ Q)
        if shape == ELLIPSE:
            self.m = 1.0 - self.p2 / self.q2              # |P| <= |Q|: 0 <= m < 1
            self.b = math.sqrt(self.q2)
        elif shape == PARABOLA:
            self.k = 2.0 * math.sqrt(self.p2)
        elif shape == HYPERBOLA:
            width = min(GL_PANEL, math.atan2(math.sqrt(self.q2), math.sqrt(self.p2)))
            count = max(1, math.ceil((t_hi - t_lo) / width))
            self.edges = np.linspace(t_lo, t_hi, count + 1)
            self.cum = np.concatenate([[0.0], np.cumsum(self._panel(self.edges[:-1], self.edges[1:]))])

    @functools.cached_property
    def centre(self):
        """The centre (3,) (a line's point at t = 0)."""
        return np.array(self.rows[0])

    @functools.cached_property
    def P(self):
        """P (3,)."""
        return np.array(self.rows[1])

    @functools.cached_property
    def Q(self):
        """Q (3,)."""
        return np.array(self.rows[2])

    def basis(self, t, order=0):
        """(f, g) (M,) each, or their derivatives of the given order (0, 1, 2) at t (M,)."""
        return basis(self.shape, t, order)

    def at(self, t, order=0):
        """C(t) (M, 3), or its derivative of the given order, at t (M,)."""
        f, g = self.basis(t, order)
        out = f[:, None] * self.P + g[:, None] * self.Q
        return out + self.centre if order == 0 else out

    def speed(self, t):
        """|C'(t)| (M,)."""
        f, g = self.basis(t, 1)
        return np.sqrt(f * f * self.p2 + g * g * self.q2)

    def arc(self, t):
        """Arc length S(t) (M,) from t = 0 (a hyperbola: from t_lo), increasing with t, at t (M,) (a line's or an
        ellipse's: or at one float t)."""
        shape = self.shape
        if shape == ELLIPSE:
            return self.b * elliptic_e(t, self.m) if self.m > 0 else self.b * t
        if shape == PARABOLA:
            kt = self.k * t
            return 0.5 * t * np.sqrt(1.0 + kt * kt) + np.arcsinh(kt) / (2.0 * self.k) if self.k > 0 else t
        if shape == HYPERBOLA:
            j = np.clip(np.searchsorted(self.edges, t, side="right") - 1, 0, len(self.edges) - 2)
            return self.cum[j] + self._panel(self.edges[j], t)
        return t

    def _panel(self, lo, hi):
        """Gauss-Legendre integral of |C'| over [lo, hi] (each (M,)), GL_NODES nodes."""
        return gauss_legendre(self.speed, lo, hi, GL_NODES)


class ConicSolution(ExactSolution):
    """Dense output of the arc t in [t_lo, t_hi] of a Conic (the whole period of a closed ellipse), s = S(t) -
    S(t_lo). The stored points are at `samples` values of t evenly spaced; s -> t by Newton from them. Periodic
    parameters of surfaces that are not re-charted (a cylinder's or cone's u) continue those of the nearest stored
    point (as a traced curve's do); a sphere's u is wrapped to (-pi, pi] (as there)."""

    def __init__(self, surfaces, conic, t_lo, t_hi, closed, samples=EXACT_SAMPLES):
        self.conic, self.t_lo = conic, float(t_lo)
        self._t_range, self._t_knots = (t_lo, t_hi, (t_hi - t_lo) / (samples - 1), samples), None
        self.turn = closed and conic.shape == ELLIPSE and conic.m > 0 and (samples - 1) % 4 == 0
        knots = None                            # (made on first use: make_knots)
        if self.turn:                           # t_lo is 0 or -2 pi: S(t_lo) = 0 or -length
            length = conic.b * (4 * elliptic_e(QUARTER, conic.m))     # (ellipse_turn's last: quarter_turn's last)
            self.s0 = 0.0 if t_lo == 0 else -length
        elif conic.shape in ENDWISE:
            step = self._t_range[2]
            self.s0 = float(conic.arc(t_lo + step * 0.0))            # (t_knots' first and last, one by one)
            length = conic.arc(t_hi) - self.s0
        else:
            knots = self.make_knots()
            length = knots[-1]
        self.shape = conic.shape
        super().__init__(surfaces, length, closed, knots)

    @property
    def t_knots(self):
        """The conic parameters (N,) of the stored points, evenly spaced from t_lo to t_hi (made on first use)."""
        if self._t_knots is None:
            t_lo, t_hi, step, samples = self._t_range
            t_knots = t_lo + step * counting(samples)
            t_knots[-1] = t_hi
            self._t_knots = t_knots                  # (whole: a concurrent first read never sees it unfinished)
        return self._t_knots

    def make_knots(self):
        """The knots: a closed ellipse's by ellipse_turn, else S(t_knots) - S(t_lo) (setting s0 = S(t_lo))."""
        if self.turn:
            return self.conic.b * ellipse_turn(self.conic.m, self._t_range[3])
        arcs = self.conic.arc(self.t_knots)
        self.s0 = float(arcs[0])
        knots = arcs - self.s0
        knots[0] = 0.0
        return knots

    def first_sample(self):
        """The first stored point (3,), made alone as sample_points makes it (at t_knots[0])."""
        return self.conic.at(self.t_knots[:1])[0]

    def sample_points(self):
        """The exact points (N, 3) at t_knots (ExactSolution.samples makes the rest)."""
        return self.conic.at(self.t_knots)

    @property
    def params(self):
        """The stored parameters (N, 4) (samples; the continuity reference of evaluate)."""
        return self.samples()[1]

    def t_of(self, s):
        """Conic parameter t (M,) at wrapped arc lengths s (M,)."""
        conic = self.conic
        if conic.shape == LINE:
            return self.t_lo + s
        t = np.interp(s, self.knots, self.t_knots)
        target = s + self.s0
        for _ in range(NEWTON_STEPS):
            t = t + (target - conic.arc(t)) / conic.speed(t)
        return t

    def at(self, s):
        t = self.t_of(s)
        d1 = self.conic.at(t, 1)
        return self.conic.at(t), d1 / np.linalg.norm(d1, axis=1)[:, None]

    def evaluate(self, s, with_params=True):
        s, points, tangents, params = super().evaluate(s, with_params)
        if with_params:
            near = self.params[np.clip(np.searchsorted(self.knots, s), 0, len(self.knots) - 1)]
            for k, surf in enumerate(self.surfaces):
                kind = surf.traits
                if kind.periodic[0] and not kind.recharts:
                    u = params[:, 2 * k]
                    u -= 2.0 * np.pi * np.round((u - near[:, 2 * k]) / (2.0 * np.pi))
        return s, points, tangents, params

    def derivatives(self, s):
        """(points, unit tangents, curvature vectors) (..., 3) at s: C'' less its tangential part over |C'|^2."""
        shape = np.shape(s)
        t = self.t_of(self.wrap(np.ravel(s)))
        d1, d2 = self.conic.at(t, 1), self.conic.at(t, 2)
        speed2 = np.einsum("ij,ij->i", d1, d1)
        tangents = d1 / np.sqrt(speed2)[:, None]
        bend = (d2 - np.einsum("ij,ij->i", d2, tangents)[:, None] * tangents) / speed2[:, None]
        return tuple(x.reshape(shape + (3,)) for x in (self.conic.at(t), tangents, bend))


def elliptic_e(t, m):
    """E(t | m) (scipy.special.ellipeinc) at t (M,), or at one float t by its compiled scalar twin
    (scipy.special.cython_special.ellipeinc: the same function, a float, without the ufunc's call)."""
    return cython_special.ellipeinc(t, m) if type(t) is float else ellipeinc(t, m)


def ellipse_turn(m, samples):
    """E(t | m) at `samples` values of t evenly spaced over [0, 2 pi] (samples - 1 a multiple of 4): evaluated on
    the first quarter only, by E(pi / 2 + x) = 2 E(m) - E(pi / 2 - x) and E(t + pi) = E(t) + 2 E(m)."""
    e = ellipeinc(quarter_turn(samples), m)
    full = e[-1]
    rising, falling = e[:-1], full - e[:0:-1]           # E(x) and E(pi/2 + x) - E(pi/2) for x in [0, pi/2)
    return np.concatenate([rising, full + falling, 2 * full + rising, 3 * full + falling, [4 * full]])


@functools.lru_cache(maxsize=None)
def quarter_turn(samples):
    """The angles of ellipse_turn's first quarter, np.linspace(0, pi / 2, (samples - 1) / 4 + 1), made once per
    samples (read-only)."""
    out = np.linspace(0.0, 0.5 * math.pi, (samples - 1) // 4 + 1)
    out.flags.writeable = False
    return out
