"""Truncated Taylor arithmetic in the crank angle and first order in the design parameters.

A :class:`Jet` holds, for every entry of an array, the coefficients of a polynomial in a time-like variable
t (the crank angle increment) up to t**(T-1) and in P parameter increments eps_i up to first order
(eps_i * eps_j = 0): ``coef[..., a, 0]`` is the coefficient of t**a, ``coef[..., a, i]`` (i >= 1) that of
t**a * eps_i. So for x(u1, p): ``coef[..., 0, 0] = x``, ``coef[..., a, 0] = (d/du1)**a x / a!`` and
``coef[..., a, i] = d/dp_i (d/du1)**a x / a!``. Arithmetic on jets is exact (no truncation error beyond
the dropped orders), so every output computed from jets carries its exact derivatives.

This is forward-mode automatic differentiation in the algebra R[t, eps]/(t**T, eps_i eps_j); the implicit
function theorem is applied to it in :mod:`spatialkin.design.sensitivity`.

References
----------
A. Griewank, A. Walther, Evaluating Derivatives, 2nd ed., SIAM 2008, ch. 13 (Taylor arithmetic).
"""
import math

import numpy as np

from ..kernels.design.jet import jet_product


class Jet:
    """An array of truncated Taylor polynomials.

    Parameters
    ----------
    coef : ndarray (..., T, P + 1)
        Coefficients (see the module docstring).
    """

    __slots__ = ("coef",)
    __array_priority__ = 100      # numpy scalars and arrays defer to Jet's operators

    def __init__(self, coef):
        self.coef = coef

    # --- construction ------------------------------------------------------------------------------
    @classmethod
    def constant(cls, value, orders, nparams):
        """A jet with no t or eps part: value (...,) -> coef (..., orders, nparams + 1)."""
        value = np.asarray(value, dtype=float)
        coef = np.zeros(value.shape + (orders, nparams + 1))
        coef[..., 0, 0] = value
        return cls(coef)

    @classmethod
    def variable(cls, value, orders, nparams, param=None, t=False):
        """value + eps_param (param in 1..P) and/or + t."""
        jet = cls.constant(value, orders, nparams)
        if param is not None:
            jet.coef[..., 0, param] = 1.0
        if t and orders > 1:
            jet.coef[..., 1, 0] = 1.0
        return jet

    def _like(self, value):
        if isinstance(value, Jet):
            return value
        return Jet.constant(value, self.orders, self.nparams)

    # --- shape -------------------------------------------------------------------------------------
    @property
    def orders(self):
        return self.coef.shape[-2]

    @property
    def nparams(self):
        return self.coef.shape[-1] - 1

    @property
    def shape(self):
        return self.coef.shape[:-2]

    @property
    def value(self):
        """The plain value (...,)."""
        return self.coef[..., 0, 0]

    def __getitem__(self, index):
        """Index the leading dimensions (no Ellipsis)."""
        index = index if isinstance(index, tuple) else (index,)
        return Jet(self.coef[index + (Ellipsis, slice(None), slice(None))])

    def component(self, k):
        """Entry k of the last leading axis (a vector's component)."""
        return Jet(self.coef[..., k, :, :])

    def __len__(self):
        return self.shape[0]

    def sum(self, axis):
        """Sum over a leading axis (axis counted among the leading dimensions, may be negative)."""
        axis = axis if axis >= 0 else len(self.shape) + axis
        return Jet(self.coef.sum(axis=axis))

    @staticmethod
    def stack(jets, axis=-1):
        """Stack jets of equal shape along a new leading axis (axis among the leading dimensions)."""
        ndim = len(jets[0].shape) + 1
        axis = axis if axis >= 0 else ndim + axis
        return Jet(np.stack([j.coef for j in jets], axis=axis))

    # --- derivatives -------------------------------------------------------------------------------
    def d_du(self, order=1):
        """The plain Taylor coefficient's derivative (d/du1)**order (...,)."""
        return math.factorial(order) * self.coef[..., order, 0]

    def d_dp(self, order=0):
        """d/dp (d/du1)**order (..., P)."""
        return math.factorial(order) * self.coef[..., order, 1:]

    def derivative(self):
        """The jet of d/du1 (one t order fewer; the top order is zero and must not be used)."""
        coef = np.zeros_like(self.coef)
        for a in range(1, self.orders):
            coef[..., a - 1, :] = a * self.coef[..., a, :]
        return Jet(coef)

    # --- arithmetic --------------------------------------------------------------------------------
    def __add__(self, other):
        other = self._like(other)
        return Jet(self.coef + other.coef)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.coef)

    def __sub__(self, other):
        other = self._like(other)
        return Jet(self.coef - other.coef)

    def __rsub__(self, other):
        return self._like(other) - self

    def __mul__(self, other):
        if not isinstance(other, Jet):
            value = np.asarray(other, dtype=float)
            return Jet(self.coef * value[..., None, None])
        return Jet(_mul(self.coef, other.coef))

    __rmul__ = __mul__

    def __truediv__(self, other):
        if not isinstance(other, Jet):
            value = np.asarray(other, dtype=float)
            return Jet(self.coef / value[..., None, None])
        return self * other.power(-1.0)

    def __rtruediv__(self, other):
        return self._like(other) * self.power(-1.0)

    # --- functions ---------------------------------------------------------------------------------
    def compose(self, taylor):
        """f(self) from f's Taylor coefficients about self.value: taylor (orders + 1, ...) with
        taylor[k] = f^(k)(x0) / k!."""
        h = Jet(self.coef.copy())
        h.coef[..., 0, 0] = 0.0
        out = Jet.constant(taylor[-1], self.orders, self.nparams)
        for k in range(len(taylor) - 2, -1, -1):
            out = out * h
            out.coef[..., 0, 0] += taylor[k]
        return out

    def _terms(self):
        return self.orders + 1     # h**k with k <= orders can still carry t**(orders-1) eps

    def sin(self):
        x0 = self.value
        return self.compose([np.sin(x0 + k * np.pi / 2) / math.factorial(k) for k in range(self._terms())])

    def cos(self):
        x0 = self.value
        return self.compose([np.cos(x0 + k * np.pi / 2) / math.factorial(k) for k in range(self._terms())])

    def power(self, exponent):
        """self ** exponent (self.value > 0 unless exponent is a whole number)."""
        x0 = self.value
        taylor, binom = [], 1.0
        for k in range(self._terms()):
            taylor.append(binom * x0 ** (exponent - k))
            binom *= (exponent - k) / (k + 1)
        return self.compose(taylor)

    def sqrt(self):
        return self.power(0.5)

    def atan_small(self):
        """atan of a jet whose value is zero (the series w - w**3/3 + ...)."""
        taylor = [0.0 if k % 2 == 0 else (-1.0) ** (k // 2) / k for k in range(self._terms())]
        return self.compose([np.full(self.shape, c) for c in taylor])


def atan2(y, x):
    """atan2 of jets: the plain angle plus atan of the (nilpotent) angle to it,
    atan2(y, x) = atan2(y0, x0) + atan((x0 y - y0 x) / (x0 x + y0 y))."""
    x0, y0 = x.value, y.value
    w = (y * x0 - x * y0) / (x * x0 + y * y0)
    w.coef[..., 0, 0] = 0.0
    out = w.atan_small()
    out.coef[..., 0, 0] = np.arctan2(y0, x0)
    return out


def dot(a, b, axis=-1):
    """Dot product of jet vectors along a leading axis."""
    return (a * b).sum(axis)


def cross(a, b):
    """Cross product of jet 3-vectors (last leading axis of length 3)."""
    ax, ay, az = (a.component(k) for k in range(3))
    bx, by, bz = (b.component(k) for k in range(3))
    return Jet.stack([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx], axis=-1)


def matvec(m, v):
    """m @ v for jet (or plain) matrices (..., 3, 3) and jet vectors (..., 3)."""
    if not isinstance(m, Jet):
        m = np.asarray(m, dtype=float)
        return Jet(np.einsum("...ij,...jab->...iab", m, v.coef))
    return (m * Jet(v.coef[..., None, :, :, :])).sum(-1)


def _writable(x):
    """x, or a copy of it where it is read-only (a broadcast view, a frame's arrays): numba compiles a kernel anew
    for each read-only flag of its arguments, and spatialkin warmup compiles the writable one."""
    return x if x.flags.writeable else x.copy()


def _mul(c, d):
    """Product of coefficient arrays (..., T, Q) in R[t, eps]/(t**T, eps_i eps_j), broadcasting the leading
    dimensions (a jitted kernel on the flattened arrays)."""
    shape = c.shape if c.shape == d.shape else np.broadcast_shapes(c.shape, d.shape)
    flat = (-1,) + shape[-2:]
    if c.shape != shape:
        c = np.broadcast_to(c, shape)
    if d.shape != shape:
        d = np.broadcast_to(d, shape)
    c = _writable(np.ascontiguousarray(c).reshape(flat))
    d = _writable(np.ascontiguousarray(d).reshape(flat))
    out = np.empty_like(c)
    jet_product(c, d, out)
    return out.reshape(shape)
