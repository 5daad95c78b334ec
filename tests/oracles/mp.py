"""High-precision truth for tiny loops: the intersection of the surfaces exactly as the doubles define them.

A loop of 1e-6 x scale where the surfaces nearly touch is fixed by double arithmetic only to about
u |x| / sin(angle of the normals): its length cannot agree between argument orders to better than that. The
stress test therefore compares such loops with their true length, computed here in 40-digit arithmetic
(mpmath) from the surfaces' own data (frames and radii read as exact binary numbers), written from the local
equations (nothing of spatialkin is used):

- the loop is read in polar form about its centre c, in the plane of its samples (normal n):
  x(phi) = c + rho(phi) e(phi) + h(phi) n, (rho, h) solved by Newton on f_a(x) = f_b(x) = 0;
- its length is the trapezoid rule on the speed |x'(phi)| (x' by implicit differentiation), exponentially
  convergent for a smooth periodic integrand: N and 2N points agree to the returned error estimate.

It also returns the smallest sine of the normals' angle on the loop, for the conditioning bound.
"""
import mpmath as mp
import numpy as np
from tests.oracles.ssi import frame_of, kind, shape_params

DIGITS = 40


def _implicit(k, q, p):
    """(f, grad f) at local point p (3 mpf) of the surface of kind k: signed distance-like, as in tests.oracles.ssi."""
    x, y, z = p
    if k == "plane":
        return z, (mp.mpf(0), mp.mpf(0), mp.mpf(1))
    if k == "sphere":
        n = mp.sqrt(x * x + y * y + z * z)
        return n - q["R"], (x / n, y / n, z / n)
    rho = mp.sqrt(x * x + y * y)
    ex, ey = x / rho, y / rho
    if k == "cylinder":
        return rho - q["r"], (ex, ey, mp.mpf(0))
    if k == "cone":
        c, s = mp.cos(q["a"]), mp.sin(q["a"])
        sg = 1 if z >= 0 else -1
        return rho * c - abs(z) * s, (c * ex, c * ey, -sg * s)
    d = rho - q["R"]
    qd = mp.sqrt(d * d + z * z)
    return qd - q["r"], (d / qd * ex, d / qd * ey, z / qd)


class _Surface:
    def __init__(self, surface):
        self.k = kind(surface)
        o, rot = frame_of(surface)
        self.o = [mp.mpf(float(v)) for v in o]
        self.rot = [[mp.mpf(float(rot[i, j])) for j in range(3)] for i in range(3)]
        self.q = {key: mp.mpf(float(v)) for key, v in shape_params(surface).items()}

    def __call__(self, x):
        """(f, global gradient) at global point x (3 mpf)."""
        d = [x[i] - self.o[i] for i in range(3)]
        loc = [sum(d[i] * self.rot[i][j] for i in range(3)) for j in range(3)]      # R^T (x - o)
        f, g = _implicit(self.k, self.q, loc)
        return f, [sum(self.rot[i][j] * g[j] for j in range(3)) for i in range(3)]


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def loop_length(a, b, samples, n=64):
    """(length, error estimate, smallest sine of the normals' angle) of the loop of a and b through which the
    samples (M, 3, M >= 3, within a small fraction of its size) pass."""
    samples = np.asarray(samples, dtype=float).reshape(-1, 3)
    centre = samples.mean(axis=0)
    _, _, vt = np.linalg.svd(samples - centre)
    e1, e2, nrm = vt[0], vt[1], vt[2]
    radius = float(np.mean(np.linalg.norm(samples - centre, axis=1)))
    with mp.workdps(DIGITS):
        fa, fb = _Surface(a), _Surface(b)
        c = [mp.mpf(float(v)) for v in centre]
        settle = mp.mpf(10) ** (-DIGITS + 12) * (1 + float(np.abs(centre).max()))    # ~1e-28 |x|
        e1m, e2m, nm = ([mp.mpf(float(v)) for v in w] for w in (e1, e2, nrm))

        def solve(phi, guess):
            cs, sn = mp.cos(phi), mp.sin(phi)
            e = [cs * e1m[i] + sn * e2m[i] for i in range(3)]
            de = [-sn * e1m[i] + cs * e2m[i] for i in range(3)]
            rho, h = guess
            for _ in range(60):
                x = [c[i] + rho * e[i] + h * nm[i] for i in range(3)]
                (f1, g1), (f2, g2) = fa(x), fb(x)
                j11, j12, j21, j22 = _dot(g1, e), _dot(g1, nm), _dot(g2, e), _dot(g2, nm)
                det = j11 * j22 - j12 * j21
                d_rho = (f1 * j22 - f2 * j12) / det
                d_h = (j11 * f2 - j21 * f1) / det
                rho, h = rho - d_rho, h - d_h
                if abs(d_rho) + abs(d_h) < settle:
                    break
            else:
                raise RuntimeError("loop_length: Newton did not converge")
            x = [c[i] + rho * e[i] + h * nm[i] for i in range(3)]
            (_, g1), (_, g2) = fa(x), fb(x)
            j11, j12, j21, j22 = _dot(g1, e), _dot(g1, nm), _dot(g2, e), _dot(g2, nm)
            det = j11 * j22 - j12 * j21
            r1, r2 = -rho * _dot(g1, de), -rho * _dot(g2, de)          # J (rho', h') = -(grad f . rho e')
            d_rho, d_h = (r1 * j22 - r2 * j12) / det, (j11 * r2 - j21 * r1) / det
            speed = mp.sqrt(sum((d_rho * e[i] + rho * de[i] + d_h * nm[i]) ** 2 for i in range(3)))
            cross = [g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]]
            sine = mp.sqrt(_dot(cross, cross)) / (mp.sqrt(_dot(g1, g1)) * mp.sqrt(_dot(g2, g2)))
            return (rho, h), speed, sine

        def trapezoid(m):
            guess = (mp.mpf(radius), mp.mpf(0))
            total, sines = mp.mpf(0), []
            for k in range(m):
                guess, speed, sine = solve(2 * mp.pi * k / m, guess)
                total += speed
                sines.append(sine)
            return total * 2 * mp.pi / m, min(sines)

        coarse, _ = trapezoid(n)
        fine, sine = trapezoid(2 * n)
        return float(fine), float(abs(fine - coarse)), float(sine)


def foot(a, b, x, digits=30):
    """(distance, foot point (3,)) from the point x (3,) to the nearest point of the intersection of a and b near
    it: Newton on f_a(y) = f_b(y) = 0, (y - x) . (grad f_a x grad f_b) = 0 (the last row's Jacobian taken as the
    tangent, exact at the foot), in `digits`-digit arithmetic."""
    with mp.workdps(digits):
        fa, fb = _Surface(a), _Surface(b)
        xm = [mp.mpf(float(v)) for v in x]
        y = list(xm)
        settle = mp.mpf(10) ** (-digits + 6) * (1 + max(abs(v) for v in xm))
        for _ in range(60):
            (f1, g1), (f2, g2) = fa(y), fb(y)
            t = [g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]]
            f3 = _dot([y[i] - xm[i] for i in range(3)], t)
            step = mp.lu_solve(mp.matrix([g1, g2, t]), mp.matrix([f1, f2, f3]))
            y = [y[i] - step[i] for i in range(3)]
            if mp.norm(step) < settle:
                break
        else:
            raise RuntimeError("foot: Newton did not converge")
        return float(mp.sqrt(sum((y[i] - xm[i]) ** 2 for i in range(3)))), np.array([float(v) for v in y])
