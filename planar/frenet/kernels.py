"""Jitted laws phi(s) of the crank mechanisms of Pylypaka et al. (2017) and the driven link's s-derivatives.

Each law kernel fills phi, phi', phi'' at the arc lengths s (flat arrays); link_derivatives fills the
positions of the link's points and their first and second s-derivatives from the law (computed once per s
by the caller and shared by every point rho). Formulas: planar.frenet.laws and planar.frenet.link.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven member
using Frenet trihedron", 2017.
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


@jit
def crank_rocker_law(k, d, s, phi, dphi, ddphi, cg, sg, ck, sk):
    """Crank-rocker through the stone at (d, 0); d = 1/k turns uniformly. cg, sg: the link's direction,
    gamma = atan2(cos ks, kd - sin ks); ck, sk: cos ks, sin ks."""
    kd = k * d
    for i in range(s.size):
        ks = k * s[i]
        sn, c = math.sin(ks), math.cos(ks)
        ck[i], sk[i] = c, sn
        if kd == 1.0:
            phi[i] = math.pi / 4 - ks / 2
            dphi[i] = -k / 2
            ddphi[i] = 0.0
            cg[i] = math.cos(math.pi / 4 + ks / 2)
            sg[i] = math.sin(math.pi / 4 + ks / 2)
            continue
        big_d = 1.0 + kd * kd - 2.0 * kd * sn
        phi[i] = math.atan2(c, kd - sn) - ks
        norm = math.sqrt(big_d)
        cg[i] = (kd - sn) / norm
        sg[i] = c / norm
        dphi[i] = -k * k * d * (kd - sn) / big_d
        ddphi[i] = -d * k ** 3 * (kd * kd - 1.0) * c / (big_d * big_d)


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
