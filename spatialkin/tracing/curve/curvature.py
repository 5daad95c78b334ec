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


def curvature_vectors(a, b, points, tangents):
    """C'' (N, 3) of the intersection curve of a and b at points (N, 3) with unit tangents (N, 3); NaN rows where
    the normals are parallel (a singular point)."""
    t = np.asarray(tangents, dtype=float)
    rows, rhs = [], []
    for surf in (a, b):
        _, grad, hess = implicit_jets(surf, points)
        rows.append(grad)
        rhs.append(-np.einsum("ni,nij,nj->n", t, hess, t))
    mat = np.stack([rows[0], rows[1], t], axis=1)
    vec = np.stack([rhs[0], rhs[1], np.zeros(len(t))], axis=1)
    out = np.full((len(t), 3), np.nan)
    ok = np.abs(np.linalg.det(mat)) > 1e-300
    if ok.any():
        out[ok] = np.linalg.solve(mat[ok], vec[ok][:, :, None])[:, :, 0]
    return out
