"""Benchmark cases and their closed forms: torus ∩ sphere per torus angle, the looper's ball centre per crank
angle (with its first and second derivatives), and the critical sphere radii that fix the topology.

The oracles here use numpy only (no spatialkin kernels), so that the errors the bench reports are measured
against formulas independent of the tracer.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the torus and sphere parametrisations, from which torus ∩ sphere is
alpha cos v + beta sin v = gamma per torus angle, and the looper drive A cos v1 + B sin v1 + C = 0 per crank angle.
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002:
the topology of an intersection, set by the critical radii.
"""
from dataclasses import dataclass

import numpy as np

from ..geometry.frame import Frame, rotation_about
from ..mechanisms.looper.reference import looper_pair
from ..geometry.surfaces import Sphere, Torus

#: Relative distance of the near-tangent case's sphere radius from a critical radius (two loops almost touch).
NEAR_TANGENT_GAP = 1e-4
#: Relative distance of the small-loop case's sphere radius above the smallest critical radius.
SMALL_LOOP_GAP = 1e-3


@dataclass
class Case:
    """A torus–sphere pair with its closed form.

    Attributes
    ----------
    name : str
        Short label used in the table and the plot.
    torus : Torus
    sphere : Sphere
    components : int
        Number of components (closed loops) by the band of the sphere radius among the critical radii.
    """
    name: str
    torus: Torus
    sphere: Sphere
    components: int

    @property
    def centre_local(self):
        """The sphere centre in the torus frame (3,)."""
        return self.torus.frame.to_local(self.sphere.frame.origin)

    def exact_points(self, n):
        """Exact points (M, 3) (global) of the curve at n torus angles where it exists, from the closed form."""
        phi = np.linspace(-np.pi, np.pi, n, endpoint=False)
        local, _ = torus_sphere_closed_form(self.torus.major_radius, self.torus.minor_radius, self.centre_local,
                                            self.sphere.radius, phi)
        return self.torus.frame.to_global(local.reshape(-1, 3))


def torus_sphere_closed_form(big, small, c, rho, phi):
    """Points (M, 2, 3) of torus ∩ sphere in the torus frame at the torus angles phi (n,) where they exist, and
    the mask (n,) of those angles.

    On the meridian at angle phi the torus point is ((R + r cos v) cos phi, (R + r cos v) sin phi, r sin v);
    |p - c|^2 = rho^2 reads alpha cos v + beta sin v = gamma with alpha = 2 r (R - a), beta = -2 r c_z,
    gamma = 2 R a - R^2 - r^2 - |c|^2 + rho^2 and a = c_x cos phi + c_y sin phi.
    """
    phi = np.asarray(phi, dtype=float)
    a = c[0] * np.cos(phi) + c[1] * np.sin(phi)
    alpha = 2 * small * (big - a)
    beta = np.full_like(phi, -2 * small * c[2])
    gamma = 2 * big * a - big ** 2 - small ** 2 - c @ c + rho ** 2
    amp = np.hypot(alpha, beta)
    ok = np.abs(gamma) <= amp
    base = np.arctan2(beta, alpha)
    spread = np.arccos(np.clip(gamma / np.where(amp > 0, amp, 1.0), -1.0, 1.0))
    pts = []
    for v in (base + spread, base - spread):
        w = big + small * np.cos(v)
        pts.append(np.stack([w * np.cos(phi), w * np.sin(phi), small * np.sin(v)], axis=-1))
    return np.stack(pts, axis=1)[ok], ok


def critical_radii(big, small, c):
    """Sorted critical sphere radii (4,) of a ring torus (R > r) and a sphere centred at c (torus frame)
    off its axis: the sphere touches the torus there."""
    rho_c = np.hypot(c[0], c[1])
    d_min = np.hypot(rho_c - big, c[2])
    d_max = np.hypot(rho_c + big, c[2])
    return np.sort([abs(d_min - small), d_min + small, abs(d_max - small), d_max + small])


def count_components(big, small, c, rho):
    """Components of ring torus ∩ sphere by the band of rho among the critical radii (generic position)."""
    r1, r2, r3, r4 = critical_radii(big, small, c)
    if rho < r1 or rho > r4:
        return 0
    return 2 if r2 < rho < r3 else 1


def ring_case(name, rho_of_radii):
    """A ring torus (R 10, r 3, tilted) and a sphere about a point near its tube, radius picked from the
    critical radii by rho_of_radii(r1, r2, r3, r4)."""
    frame = Frame((1.0, -2.0, 0.5), rotation_about((1.0, 2.0, 0.5), 0.4))
    torus = Torus(10.0, 3.0, frame)
    c_local = np.array([9.0, 1.5, 0.8])
    rho = float(rho_of_radii(*critical_radii(10.0, 3.0, c_local)))
    sphere = Sphere(rho, Frame(frame.to_global(c_local), rotation_about((0.3, -1.0, 0.2), 1.1)))
    return Case(name, torus, sphere, count_components(10.0, 3.0, c_local, rho))


def torus_sphere_cases():
    """The bench's torus–sphere cases: the looper's pair (2 loops), a ring torus with a sphere giving 2 loops,
    the same with two loops nearly touching (near-tangent) and a small loop just past first contact."""
    torus, sphere = looper_pair()
    return [
        Case("looper", torus, sphere, 2),
        ring_case("ring-2", lambda r1, r2, r3, r4: 0.5 * (r2 + r3)),
        ring_case("near-tangent", lambda r1, r2, r3, r4: r3 * (1 - NEAR_TANGENT_GAP)),
        ring_case("small-loop", lambda r1, r2, r3, r4: r1 * (1 + SMALL_LOOP_GAP)),
    ]


def looper_closed_form(drive, u1, omega, branch=0):
    """Ball centre C (N, 3) of the looper drive at crank angles u1 (N,), with its velocity and acceleration
    (crank at the constant rate omega), from A cos v1 + B sin v1 + C0 = 0 and its implicit derivatives.

    With a = q_x cos u1 + q_y sin u1 (q the rocker centre in the crank frame): A = 2 r1 (R1 - a),
    B = -2 r1 q_z, C0 = R1^2 + r1^2 + |q|^2 - 2 R1 a - R2^2. Branch 0 is v1 = atan2(B, A) - arccos(-C0 / |A, B|).
    F(u1, v1) = A cos v1 + B sin v1 + C0; v1' = -F_u / F_v, v1'' = -(F_uu + 2 F_uv v1' + F_vv v1'^2) / F_v.
    """
    rot, o1 = drive.crank_frame.rotation, drive.crank_frame.origin
    q = rot.T @ (drive.rocker_frame.origin - o1)
    big, small, rho = drive.crank_radius, drive.coupler_length, drive.rocker_length
    u1 = np.asarray(u1, dtype=float)
    cu, su = np.cos(u1), np.sin(u1)
    a, a_u, a_uu = q[0] * cu + q[1] * su, -q[0] * su + q[1] * cu, -(q[0] * cu + q[1] * su)
    big_a, big_b = 2 * small * (big - a), -2 * small * q[2]
    c0 = big ** 2 + small ** 2 + q @ q - 2 * big * a - rho ** 2
    spread = np.arccos(-c0 / np.hypot(big_a, big_b))
    v1 = np.arctan2(big_b, big_a) + (-spread if branch == 0 else spread)
    cv, sv = np.cos(v1), np.sin(v1)
    # F = A cos v + B sin v + C0 with A_u = -2 r1 a_u, C0_u = -2 R1 a_u
    f_v = -big_a * sv + big_b * cv
    f_u = -2 * small * a_u * cv - 2 * big * a_u
    f_uu = -2 * small * a_uu * cv - 2 * big * a_uu
    f_uv = 2 * small * a_u * sv
    f_vv = -big_a * cv - big_b * sv
    dv = -f_u / f_v
    ddv = -(f_uu + 2 * f_uv * dv + f_vv * dv ** 2) / f_v
    w, w_v, w_vv = big + small * cv, -small * sv, -small * cv
    # torus point p(u1, v1(u1)) = (w cos u1, w sin u1, r1 sin v1); total derivatives in u1
    w1 = w_v * dv
    w2 = w_vv * dv ** 2 + w_v * ddv
    p = np.stack([w * cu, w * su, small * sv], axis=-1)
    p1 = np.stack([w1 * cu - w * su, w1 * su + w * cu, small * cv * dv], axis=-1)
    p2 = np.stack([w2 * cu - 2 * w1 * su - w * cu, w2 * su + 2 * w1 * cu - w * su,
                   small * (-sv * dv ** 2 + cv * ddv)], axis=-1)
    return o1 + p @ rot.T, omega * p1 @ rot.T, omega ** 2 * p2 @ rot.T
