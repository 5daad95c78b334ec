"""Curvature vectors of an intersection curve from the two surfaces' polynomial implicit functions (numpy).

Differentiating grad F(C(s)) . C'(s) = 0 along the curve gives grad F . C'' = -C'^T (hess F) C' for each
surface, and C'' is normal to C': three linear equations for the curvature vector C'' at each point.
"""
import numpy as np


def implicit_jets(surface, points):
    """(F (N,), grad F (N, 3), hess F (N, 3, 3)) of the surface's polynomial implicit function at global points
    (N, 3): its traits' local jets (plane z, sphere |q|^2 - R^2, cylinder x^2 + y^2 - r^2, cone
    x^2 + y^2 - tan(a)^2 z^2, torus (|q|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2), q the local point) turned to global
    coordinates."""
    rot = surface.frame.rotation
    q = (np.asarray(points, dtype=float) - surface.frame.origin) @ rot
    value, grad, hess = surface.traits.implicit_jets(surface, q)
    return value, grad @ rot.T, np.einsum("ij,njk,lk->nil", rot, hess, rot)


def sine_squares(grad_a, grad_b):
    """sin^2 of the angle between the gradients (N, 3) row by row (NaN where one vanishes)."""
    cross = np.cross(grad_a, grad_b)
    sizes = np.einsum("ij,ij->i", grad_a, grad_a) * np.einsum("ij,ij->i", grad_b, grad_b)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.einsum("ij,ij->i", cross, cross) / sizes


def normal_sines(a, b, points):
    """sin of the angle between the normals of surfaces a and b at global points (N, 3), from their implicit
    functions' gradients (no chart involved; NaN where a gradient vanishes)."""
    return np.sqrt(sine_squares(implicit_jets(a, points)[1], implicit_jets(b, points)[1]))


#: The relative error of C'' beside a singular point, measured on Viviani's curve beside its node, is up to
#: (ERROR_FACTOR x eps + SPREAD_FACTOR x kappa d) / sin^2 of the normals' angle: the solve's round-off, and the
#: error of the unit tangent, d / sin (kappa: the surfaces' |hess F| / |grad F|; d: the spread of the point's two
#: surface points, the dense output's Newton tolerance, and its coordinates' round-off). C'' is NaN where that
#: exceeds SINGULAR_ERROR.
ERROR_FACTOR, SPREAD_FACTOR, SINGULAR_ERROR = 64.0, 8.0, 1e-2


def curvature_vectors(a, b, points, tangents, spread=0.0):
    """C'' (N, 3) of the intersection curve of a and b at points (N, 3) with unit tangents (N, 3); NaN rows at and
    beside a singular point, where the normals are so nearly parallel that its estimated relative error exceeds
    SINGULAR_ERROR (see ERROR_FACTOR; spread: the points' Newton tolerance, a length)."""
    t = np.asarray(tangents, dtype=float)
    rows, rhs, kappa = [], [], np.zeros(len(t))
    for surf in (a, b):
        _, grad, hess = implicit_jets(surf, points)
        rows.append(grad)
        rhs.append(-np.einsum("ni,nij,nj->n", t, hess, t))
        with np.errstate(invalid="ignore", divide="ignore"):
            kappa = np.maximum(kappa, np.linalg.norm(hess, axis=(1, 2)) / np.linalg.norm(grad, axis=1))
    mat = np.stack([rows[0], rows[1], t], axis=1)
    vec = np.stack([rhs[0], rhs[1], np.zeros(len(t))], axis=1)
    out = np.full((len(t), 3), np.nan)
    sine2 = sine_squares(rows[0], rows[1])
    eps = np.finfo(float).eps
    spread = spread + 4.0 * eps * np.max(np.abs(np.asarray(points, dtype=float)), axis=1)
    ok = ((sine2 * SINGULAR_ERROR > ERROR_FACTOR * eps + SPREAD_FACTOR * kappa * spread)
          & (np.abs(np.linalg.det(mat)) > 1e-300))
    if ok.any():
        out[ok] = np.linalg.solve(mat[ok], vec[ok][:, :, None])[:, :, 0]
    return out
