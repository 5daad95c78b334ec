"""Independent oracles (numpy, and mpmath for one quadrature; no spatialkin code): exact distances, closed forms,
topology.

Exact distances to the torus (both circles of the meridian plane, which matter for horn and spindle tori) and the
sphere; the closed form alpha cos v + beta sin v = gamma of torus ∩ sphere per torus angle; the critical sphere radii
|d_min - r|, d_min + r, |d_max - r|, d_max + r that fix the torus-sphere topology.

References
----------
N. M. Patrikalakis, T. Maekawa, Shape Interrogation for Computer Aided Design and Manufacturing, Springer, 2002.
"""
import numpy as np


def random_rotation(rng):
    """A uniformly random proper rotation (from a random unit quaternion)."""
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def torus_distance(local_points, big, small):
    """Exact distance to the torus about local z (both circles of the meridian plane)."""
    p = np.asarray(local_points)
    rho = np.hypot(p[..., 0], p[..., 1])
    z = p[..., 2]
    return np.minimum(np.abs(np.hypot(rho - big, z) - small), np.abs(np.hypot(rho + big, z) - small))


def sphere_distance(points, centre, radius):
    return np.abs(np.linalg.norm(np.asarray(points) - centre, axis=-1) - radius)


def torus_sphere_closed_form(big, small, c, rho, phi):
    """Exact points (n, 2, 3) (local torus coordinates) of torus ∩ sphere at torus angles phi where they exist,
    and the mask of those angles: alpha cos v + beta sin v = gamma (ssi-notes)."""
    phi = np.asarray(phi, dtype=float)
    a = c[0] * np.cos(phi) + c[1] * np.sin(phi)
    alpha = 2 * small * (big - a)
    beta = np.full_like(phi, -2 * small * c[2])
    gamma = 2 * big * a - big ** 2 - small ** 2 - c @ c + rho ** 2
    amp = np.hypot(alpha, beta)
    ok = np.abs(gamma) <= amp
    base = np.arctan2(beta, alpha)
    spread = np.arccos(np.clip(gamma / np.where(amp > 0, amp, 1), -1, 1))
    pts = []
    for v in (base + spread, base - spread):
        w = big + small * np.cos(v)
        pts.append(np.stack([w * np.cos(phi), w * np.sin(phi), small * np.sin(v)], axis=-1))
    return np.stack(pts, axis=1)[ok], ok


def torus_sphere_critical_radii(big, small, c):
    """Sorted critical sphere radii for a ring torus and a sphere centre c off the axis (local coords)."""
    rho_c = np.hypot(c[0], c[1])
    d_min = np.hypot(rho_c - big, c[2])
    d_max = np.hypot(rho_c + big, c[2])
    return np.sort([abs(d_min - small), d_min + small, abs(d_max - small), d_max + small])


def torus_sphere_components(big, small, c, rho):
    """Number of components by the band of rho among the critical radii (generic position)."""
    r1, r2, r3, r4 = torus_sphere_critical_radii(big, small, c)
    if rho < r1 or rho > r4:
        return 0
    if r2 < rho < r3:
        return 2
    return 1


def looper_closed_form(drive, u1, branch):
    """Looper drive: (v1, C) at crank angles u1 (N,) from the coupler circle cut by the rocker sphere,
    A cos v1 + B sin v1 + C0 = 0; branch 0 is the root
    where |C - P2| grows with v1 (v1 = atan2(B, A) - arccos(-C0 / sqrt(A^2 + B^2)))."""
    rot, o1 = drive.crank_frame.rotation, drive.crank_frame.origin
    q = rot.T @ (drive.rocker_frame.origin - o1)
    big, small, rho = drive.crank_radius, drive.coupler_length, drive.rocker_length
    qr = q[0] * np.cos(u1) + q[1] * np.sin(u1)
    a = 2 * small * (big - qr)
    b = -2 * small * q[2] * np.ones_like(u1)
    c0 = big ** 2 + small ** 2 + q @ q - 2 * big * qr - rho ** 2
    spread = np.arccos(-c0 / np.hypot(a, b))
    v1 = np.arctan2(b, a) + (-spread if branch == 0 else spread)
    w = big + small * np.cos(v1)
    local = np.stack([w * np.cos(u1), w * np.sin(u1), small * np.sin(v1)], axis=-1)
    return v1, o1 + local @ rot.T


def torus_cylinder_lobe_length(shift, digits=30):
    """Length of one lobe of the torus (major radius 1, minor 0.4, axis z) cut by the cylinder of radius 0.8 whose
    axis is parallel to y through (1.4 + shift, 0, 0), for shift < 0 (the cylinder touches the tube's inner equator at
    (0.6, 0, 0) when shift = 0; moved inwards, the figure eight's node splits and the lobes y > 0 and y < 0 come
    apart, by 2 sqrt(-1.2 shift) at tau = 0). On the cylinder, x = 1.4 + shift - 0.8 cos(tau), z = -0.8 sin(tau),
    |tau| <= pi / 6; the torus gives rho = sqrt(x^2 + y^2) = 1 -+ w, w = sqrt(0.16 - z^2) (the inner and the outer
    half of the lobe, joined where w = 0), y = sqrt(rho^2 - x^2). The length is the integral of the speed
    (derivatives in closed form) by tanh-sinh quadrature (mpmath), split at tau = 0 where y turns on the scale
    sqrt(-shift), in `digits`-digit arithmetic."""
    import mpmath as mp
    if not shift < 0:
        raise ValueError("shift must be negative (the lobes apart)")
    with mp.workdps(digits):
        kap = mp.mpf(shift)

        def speed(tau, sign):
            s, c = mp.sin(tau), mp.cos(tau)
            x, dx, dz = mp.mpf("1.4") + kap - mp.mpf("0.8") * c, mp.mpf("0.8") * s, -mp.mpf("0.8") * c
            w = mp.sqrt(mp.mpf("0.16") - mp.mpf("0.64") * s * s)
            rho, drho = 1 + sign * w, -sign * mp.mpf("0.64") * s * c / w
            y = mp.sqrt(rho * rho - x * x)
            dy = (rho * drho - x * dx) / y
            return mp.sqrt(dx * dx + dy * dy + dz * dz)

        end = mp.pi / 6
        return float(sum(mp.quad(lambda t: speed(t, sign), [-end, 0, end]) for sign in (-1, 1)))


def bitangent_loops(torus, plane, digits=30):
    """(r^2 - R^2 sin^2 a, lengths of the inner and the outer loop) where a plane through the centre of a ring torus
    (R, r) makes an angle a with its equatorial plane just below the bitangent one (sin a < r / R): the plane cuts two
    nested loops, which pass closest (2 sqrt(r^2 - R^2 sin^2 a) apart) where the plane nearly touches the torus. From the
    doubles of the frames and radii as exact binary numbers, in `digits`-digit arithmetic (mpmath): in the plane, at the
    angle phi from its line in the equatorial plane, a loop lies at rho = R k -+ sqrt(R^2 k^2 - R^2 + r^2),
    k = sqrt(cos^2 phi + sin^2 phi cos^2 a); each length is the integral of sqrt(rho^2 + rho'^2) over a turn, by
    tanh-sinh quadrature split round phi = pi / 2, where rho turns on the scale of the loops' gap."""
    import mpmath as mp
    with mp.workdps(digits):
        centre = [mp.mpf(float(v)) for v in torus.frame.origin]
        axis = [mp.mpf(float(v)) for v in np.asarray(torus.frame.rotation)[:, 2]]
        normal = [mp.mpf(float(v)) for v in np.asarray(plane.frame.rotation)[:, 2]]
        if any(mp.mpf(float(v)) != c for v, c in zip(plane.frame.origin, centre)):
            raise ValueError("the plane must pass through the torus's centre: give both frames one origin")
        cos_a = abs(sum(x * y for x, y in zip(axis, normal))) / mp.sqrt(sum(x * x for x in axis) * sum(
            x * x for x in normal))
        big, small = mp.mpf(float(torus.major_radius)), mp.mpf(float(torus.minor_radius))
        gap = small ** 2 - big ** 2 * (1 - cos_a ** 2)
        if not gap > 0:
            raise ValueError("the plane must be tilted less than the bitangent plane: R sin(a) < r")
        c2 = cos_a ** 2

        def speed(phi, sign):
            k2 = mp.cos(phi) ** 2 + mp.sin(phi) ** 2 * c2
            k = mp.sqrt(k2)
            dk = mp.sin(phi) * mp.cos(phi) * (c2 - 1) / k
            root = mp.sqrt(big ** 2 * k2 - big ** 2 + small ** 2)
            rho = big * k + sign * root
            drho = big * dk + sign * big ** 2 * k * dk / root
            return mp.sqrt(rho ** 2 + drho ** 2)

        width = mp.sqrt(gap) / big
        cuts = [0] + [mp.pi / 2 - k * width for k in (1e3, 30, 1)] + [mp.pi / 2]
        return float(gap), tuple(float(4 * mp.quad(lambda phi: speed(phi, sign), cuts)) for sign in (-1, 1))


def cylinder_sphere_loops(cylinder, sphere, digits=30):
    """(R - r - d, length of each loop) of a cylinder of radius r and a sphere of radius R whose centre lies d from the
    cylinder's axis, d + r < R: the surfaces meet in two loops, mirror images in the plane through the centre normal
    to the axis (a gap of R - r - d > 0 keeps them apart where the cylinder comes nearest the sphere). From the
    doubles of the frames and radii as exact binary numbers, in `digits`-digit arithmetic (mpmath): with theta the
    angle round the axis from the direction to the centre, a loop's height over the centre is
    z = sqrt(R^2 - r^2 - d^2 + 2 r d cos(theta)), and its length the integral of sqrt(r^2 + z'^2), z' = -r d sin / z,
    by tanh-sinh quadrature split round theta = pi, where z turns on the scale sqrt((R - r - d) / d)."""
    import mpmath as mp
    with mp.workdps(digits):
        origin = [mp.mpf(float(v)) for v in cylinder.frame.origin]
        axis = [mp.mpf(float(v)) for v in np.asarray(cylinder.frame.rotation)[:, 2]]
        centre = [mp.mpf(float(v)) for v in sphere.frame.origin]
        v = [centre[i] - origin[i] for i in range(3)]
        along = sum(v[i] * axis[i] for i in range(3)) / sum(x * x for x in axis)
        d = mp.sqrt(sum((v[i] - along * axis[i]) ** 2 for i in range(3)))
        r, big = mp.mpf(float(cylinder.radius)), mp.mpf(float(sphere.radius))
        gap = big - r - d
        if not gap > 0:
            raise ValueError("the cylinder must lie inside the sphere's tangent cylinder: d + r < R")

        def speed(theta):
            z = mp.sqrt(big * big - r * r - d * d + 2 * r * d * mp.cos(theta))
            return mp.sqrt(r * r + (r * d * mp.sin(theta) / z) ** 2)

        width = mp.sqrt(gap / d)
        cuts = [0] + [mp.pi - k * width for k in (1e3, 30, 1)] + [mp.pi]
        half = mp.quad(speed, cuts)
        return float(gap), float(2 * half)


#: Cylinders a hair inside a sphere's tangent cylinder, far from the origin: (radius, origin, axes), (radius, centre).
HAIR_INSIDE = {
    "2e-9 at 1.8e6": ((1.2650800463272425, (1226618.1500858318, -1350363.433052412, 517417.21657624067),
                       [[0.6782916004821165, -0.6879940417301931, 0.25804011947594985],
                        [0.22551611874318647, 0.5291423012223048, 0.8180164455829557],
                        [-0.6993303832255668, -0.4966614778709108, 0.5140665243882983]]),
                      (4.319199704927846, (1226617.0368326479, -1350362.2083425173, 517420.8619835968))),
    "1e-9 at 2.5e6": ((0.5355669439173747, (-1921377.5595063106, 726942.1865019236, -1432301.9587617328),
                       [[0.30762069641573087, 0.6870173122445304, 0.6583135421765243],
                        [0.9324328237182387, -0.355501906702802, -0.06471030507967795],
                        [0.18957461958166574, 0.6337393841374972, -0.7499572365165186]]),
                      (2.5581271012597866, (-1921377.55989616, 726944.133600338, -1432300.8660964363))),
    "7e-10 at 8.6e4": ((1.4803247636830736, (-57184.62381583693, -8583.37946854299, -63622.86208895696),
                        [[-0.1505049726501111, 0.45002895497759987, 0.8802398496372218],
                         [0.9877611974209392, 0.03158113575660626, 0.1527430808052374],
                         [0.040939834845072354, 0.8924553610943755, -0.4492742574160755]]),
                       (2.843736506417479, (-57184.50691030673, -8581.976850121653, -63622.9706738348))),
}
