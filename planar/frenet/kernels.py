"""Jitted laws phi(s) of the crank mechanisms of Pylypaka et al. (2017) and the driven link's s-derivatives.

Each law kernel fills phi, phi', phi'' at the arc lengths s (flat arrays); link_derivatives fills the
positions of the link's points and their first and second s-derivatives from the law (computed once per s
by the caller and shared by every point rho). Formulas: planar.frenet.laws and planar.frenet.link.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven member
using Frenet trihedron", 2017.
T. J. Dekker, "A floating-point technique for extending the available precision", Numer. Math. 18 (1971) (the
exact product of two doubles).
"""
import math

from spatialkin.kernels import jit

#: Smallest W^2 kept under the square root of the crank-slider (its boundary case has W = 0 at a cusp).
TINY = 2.2250738585072014e-308


@jit
def crank_slider_law(k, h, length, branch, s, phi, dphi, ddphi, cg, sg, ck, sk):
    """Offset crank-slider (guide y = h, rod length `length`, branch 0 or 1); cg, sg: the link's direction
    (cos, sin of gamma = ks + phi), here sin gamma = q and cos gamma = +-W/(kL) with no further trig; ck, sk:
    cos ks, sin ks (the trihedron's tangent)."""
    sgn = 1.0 if branch == 0 else -1.0
    for i in range(s.size):
        ks = k * s[i]
        c, sn = math.cos(ks), math.sin(ks)
        ck[i], sk[i] = c, sn
        u = k * h + c
        q = min(max(u / (k * length), -1.0), 1.0)
        w2 = max(k * k * length * length - u * u, 0.0)
        w = math.sqrt(max(w2, TINY))
        asq = math.asin(q)
        phi[i] = (asq if branch == 0 else math.pi - asq) - ks
        sg[i] = q
        cg[i] = sgn * math.sqrt(w2) / (k * length)
        if w2 > 0.0:
            dphi[i] = -k - sgn * k * sn / w
            ddphi[i] = -sgn * k * k * (c * w2 - sn * sn * u) / (w * w * w)
        else:          # the cusp of the boundary case: the limits along sin(ks) -> 0
            dphi[i] = -k
            ddphi[i] = 0.0


#: pi / 4 as the double nearest it and the rest.
QUARTER_TURN, QUARTER_TURN_LOW = 0.25 * math.pi, 3.061616997868383e-17
#: Veltkamp's splitting factor for doubles, 2^27 + 1.
SPLITTER = 134217729.0


@jit(inline="always")
def two_product(a, b):
    """(p, e): p = fl(a b) and its rounding error e, a b = p + e exactly (Dekker's product by Veltkamp's
    splitting; |a|, |b| below about 1e300)."""
    p = a * b
    t = SPLITTER * a
    a_hi = t - (t - a)
    a_lo = a - a_hi
    t = SPLITTER * b
    b_hi = t - (t - b)
    b_lo = b - b_hi
    return p, ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo


@jit
def crank_rocker_law(k, d, s, phi, dphi, ddphi, cg, sg, ck, sk):
    """Crank-rocker through the stone at (d, 0); d = 1/k turns uniformly. cg, sg: the link's direction,
    gamma = atan2(cos ks, kd - sin ks); ck, sk: cos ks, sin ks."""
    kd, error = two_product(k, d)
    beyond = (kd - 1.0) + error                  # kd - 1 from the exact product
    for i in range(s.size):
        ks, ks_error = two_product(k, s[i])
        sn, c = math.sin(ks), math.cos(ks)
        sn, c = sn + c * ks_error, c - sn * ks_error      # at the exact k s (to first order in its rounding)
        ck[i], sk[i] = c, sn
        if beyond == 0.0:
            phi[i] = math.pi / 4 - ks / 2
            dphi[i] = -k / 2
            ddphi[i] = 0.0
            cg[i] = math.cos(math.pi / 4 + ks / 2)
            sg[i] = math.sin(math.pi / 4 + ks / 2)
            continue
        half = math.sin((QUARTER_TURN - 0.5 * ks) + (QUARTER_TURN_LOW - 0.5 * ks_error))
        gap = beyond + 2.0 * half * half          # kd - sin ks, without its cancellation where sin ks is near kd
        big_d = gap * gap + c * c                 # 1 + kd^2 - 2 kd sin ks, likewise
        if big_d == 0.0:
            raise ValueError("the crank pin passes through the stone here (d = 1/k to within round-off, "
                             "not exactly): the link's direction is undefined")
        phi[i] = math.atan2(c, gap) - ks
        norm = math.sqrt(big_d)
        cg[i] = gap / norm
        sg[i] = c / norm
        dphi[i] = -k * k * d * gap / big_d
        ddphi[i] = -d * k ** 3 * (beyond * (beyond + 2.0)) * c / (big_d * big_d)


@jit
def link_derivatives(k, dphi, ddphi, cgs, sgs, cks, sks, rho, pos, d1, d2):
    """Points P = A + rho e of the link and P', P'' (M, R, 2) at M crank positions from their law's
    derivatives, the link's direction e = (cgs, sgs) (M,) and the trihedron's tangent (cks, sks) = (cos ks,
    sin ks), for the distances rho (M, R): the trihedron and the law are computed once per position."""
    for i in range(dphi.size):
        sk, ck = sks[i], cks[i]
        cg, sg = cgs[i], sgs[i]
        g1 = k + dphi[i]
        g1s = g1 * g1
        g2 = ddphi[i]
        for j in range(rho.shape[1]):
            r = rho[i, j]
            pos[i, j, 0] = sk / k + r * cg
            pos[i, j, 1] = -ck / k + r * sg
            d1[i, j, 0] = ck - r * g1 * sg
            d1[i, j, 1] = sk + r * g1 * cg
            d2[i, j, 0] = -k * sk - r * (g2 * sg + g1s * cg)
            d2[i, j, 1] = k * ck + r * (g2 * cg - g1s * sg)
