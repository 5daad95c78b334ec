"""What the bench sets the tracer against: OpenCascade's GeomAPI_IntSS (optional ``cadquery-ocp`` wheel) and,
for the looper drive, a per-crank-angle root solve with scipy as a user would write it without spatialkin.

Neither is used by the library itself; OCP is an optional benchmark dependency (``pip install ".[bench]"``).
"""
import importlib.util
import math
import time

import numpy as np
from scipy.optimize import root

#: OpenCascade's default tolerance (Precision::Confusion(), 1e-7 model units) and a tighter one.
OCC_DEFAULT_TOL = 1e-7
OCC_TIGHT_TOL = 1e-10
#: Points sampled evenly in each OCC result curve's parameter to measure its distance to both surfaces.
OCC_SAMPLES = 4000
#: Tolerance of the per-angle root solve (scipy's hybr xtol): its positions then agree with the closed form
#: to about 1e-14 of the mechanism's size, as the tracer's do.
ROOT_XTOL = 1e-12


def occ_available():
    """True when the optional ``cadquery-ocp`` wheel (module OCP) can be imported."""
    try:
        return importlib.util.find_spec("OCP") is not None and importlib.util.find_spec("OCP.GeomAPI") is not None
    except ImportError:
        return False


def ax3(frame):
    """gp_Ax3 of a spatialkin Frame: origin, main direction local z, x direction local x."""
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt
    rot = frame.rotation
    return gp_Ax3(gp_Pnt(*frame.origin), gp_Dir(*rot[:, 2]), gp_Dir(*rot[:, 0]))


def occ_surfaces(torus, sphere):
    """Geom_ToroidalSurface and Geom_SphericalSurface with the same placement as the spatialkin surfaces."""
    from OCP.Geom import Geom_SphericalSurface, Geom_ToroidalSurface
    return (Geom_ToroidalSurface(ax3(torus.frame), torus.major_radius, torus.minor_radius),
            Geom_SphericalSurface(ax3(sphere.frame), sphere.radius))


def occ_intersect(torus, sphere, tol, repeats):
    """Intersect with GeomAPI_IntSS at tolerance tol; best wall time of `repeats` calls (surfaces built once).

    Returns
    -------
    seconds : float
        Wall time of one GeomAPI_IntSS call (all components).
    curves : list of ndarray (OCC_SAMPLES, 3)
        Each result curve sampled evenly in its parameter.
    """
    from OCP.GeomAPI import GeomAPI_IntSS
    geom_t, geom_s = occ_surfaces(torus, sphere)
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        inter = GeomAPI_IntSS(geom_t, geom_s, tol)
        best = min(best, time.perf_counter() - t0)
    if not inter.IsDone():
        raise RuntimeError(f"GeomAPI_IntSS did not finish at tolerance {tol:g}")
    curves = []
    for i in range(1, inter.NbLines() + 1):
        line = inter.Line(i)
        ts = np.linspace(line.FirstParameter(), line.LastParameter(), OCC_SAMPLES)
        pts = [line.Value(float(t)) for t in ts]
        curves.append(np.array([[p.X(), p.Y(), p.Z()] for p in pts]))
    return best, curves


def occ_splines(torus, sphere, tol):
    """GeomAPI_IntSS's result curves at tolerance tol as (poles, degree, sampled points (OCC_SAMPLES, 3)) each."""
    from OCP.GeomAPI import GeomAPI_IntSS
    geom_t, geom_s = occ_surfaces(torus, sphere)
    inter = GeomAPI_IntSS(geom_t, geom_s, tol)
    out = []
    for i in range(1, inter.NbLines() + 1):
        line = inter.Line(i)
        ts = np.linspace(line.FirstParameter(), line.LastParameter(), OCC_SAMPLES)
        pts = np.array([[p.X(), p.Y(), p.Z()] for p in (line.Value(float(t)) for t in ts)])
        poles = line.NbPoles() if hasattr(line, "NbPoles") else 0
        out.append((poles, line.Degree() if hasattr(line, "Degree") else 0, pts))
    return out


# --- the looper drive solved per crank angle, as a user would without spatialkin ------------------------
def _torus_terms(drive, u1, v1):
    """Torus point and its partial derivatives in (u1, v1) up to second order, crank frame (numpy)."""
    big, small = drive.crank_radius, drive.coupler_length
    cu, su, cv, sv = np.cos(u1), np.sin(u1), np.cos(v1), np.sin(v1)
    w = big + small * cv
    zero = np.zeros_like(u1)
    p = np.stack([w * cu, w * su, small * sv], axis=-1)
    p_u = np.stack([-w * su, w * cu, zero], axis=-1)
    p_v = np.stack([-small * sv * cu, -small * sv * su, small * cv], axis=-1)
    p_uu = np.stack([-w * cu, -w * su, zero], axis=-1)
    p_uv = np.stack([small * sv * su, -small * sv * cu, zero], axis=-1)
    p_vv = np.stack([-small * cv * cu, -small * cv * su, -small * sv], axis=-1)
    return p, p_u, p_v, p_uu, p_uv, p_vv


def _sphere_terms(drive, u2, v2):
    """Sphere point (about the rocker centre, in the crank frame) and its partial derivatives in (u2, v2)."""
    rho = drive.rocker_length
    rot = drive.crank_frame.rotation.T @ drive.rocker_frame.rotation
    q = drive.crank_frame.rotation.T @ (drive.rocker_frame.origin - drive.crank_frame.origin)
    cu, su, cv, sv = np.cos(u2), np.sin(u2), np.cos(v2), np.sin(v2)
    zero = np.zeros_like(u2)
    terms = [np.stack(x, axis=-1) for x in (
        (cv * cu, cv * su, sv), (-cv * su, cv * cu, zero), (-sv * cu, -sv * su, cv),
        (-cv * cu, -cv * su, zero), (sv * su, -sv * cu, zero), (-cv * cu, -cv * su, -sv))]
    return [q + rho * terms[0] @ rot.T] + [rho * t @ rot.T for t in terms[1:]]


def looper_by_root(drive, crank_angles, omega, start):
    """The looper's ball centre at each crank angle by scipy.optimize.root on the loop closure
    torus(u1, v1) = sphere(u2, v2) for (v1, u2, v2), warm-started from the previous angle; velocities and
    accelerations by the implicit-function formulas.

    Parameters
    ----------
    drive : LooperDrive
    crank_angles : ndarray (N,)
        In order along the turn (each solve starts from the previous one's root).
    omega : float
        Crank rate (rad per time unit).
    start : ndarray (3,)
        (v1, u2, v2) near the first angle's root on the wanted branch.

    Returns
    -------
    centre, velocity, acceleration : ndarray (N, 3)
        In fixed axes.
    """
    u1 = np.asarray(crank_angles, dtype=float)
    q = np.empty((len(u1), 3))
    x = np.asarray(start, dtype=float)

    big, small, rho = drive.crank_radius, drive.coupler_length, drive.rocker_length
    rot = drive.crank_frame.rotation.T @ drive.rocker_frame.rotation      # rocker axes in the crank frame
    centre = drive.crank_frame.rotation.T @ (drive.rocker_frame.origin - drive.crank_frame.origin)

    def closure(x, u):           # scalar math per call: the per-angle work a careful user writes
        v1, u2, v2 = x
        w = big + small * math.cos(v1)
        cv2 = math.cos(v2)
        local = rot @ np.array([cv2 * math.cos(u2), cv2 * math.sin(u2), math.sin(v2)])
        return np.array([w * math.cos(u), w * math.sin(u), small * math.sin(v1)]) - centre - rho * local

    def jacobian(x, u):
        v1, u2, v2 = x
        cu2, su2, cv2, sv2 = math.cos(u2), math.sin(u2), math.cos(v2), math.sin(v2)
        p_v = [-small * math.sin(v1) * math.cos(u), -small * math.sin(v1) * math.sin(u), small * math.cos(v1)]
        s_u = rho * rot @ np.array([-cv2 * su2, cv2 * cu2, 0.0])
        s_v = rho * rot @ np.array([-sv2 * cu2, -sv2 * su2, cv2])
        return np.column_stack([p_v, -s_u, -s_v])

    for k, u in enumerate(u1):
        sol = root(closure, x, args=(u,), jac=jacobian, method="hybr", options={"xtol": ROOT_XTOL})
        if not sol.success:
            raise RuntimeError(f"root solve failed at crank angle {np.degrees(u):.6g} deg: {sol.message}")
        x = q[k] = sol.x
    v1, u2, v2 = q.T
    p, p_u, p_v, p_uu, p_uv, p_vv = _torus_terms(drive, u1, v1)
    _, s_u, s_v, s_uu, s_uv, s_vv = _sphere_terms(drive, u2, v2)
    jac = np.stack([p_v, -s_u, -s_v], axis=-1)                    # (N, 3, 3), d closure / d(v1, u2, v2)
    dq = np.linalg.solve(jac, -p_u[..., None])[..., 0]          # q' = -J^-1 d closure / du1
    dv1, du2, dv2 = dq.T
    curv = (p_uu + 2 * p_uv * dv1[:, None] + p_vv * (dv1 ** 2)[:, None]
            - s_uu * (du2 ** 2)[:, None] - 2 * s_uv * (du2 * dv2)[:, None] - s_vv * (dv2 ** 2)[:, None])
    ddv1 = np.linalg.solve(jac, -curv[..., None])[..., 0][:, 0]
    vel = p_u + p_v * dv1[:, None]
    acc = p_uu + 2 * p_uv * dv1[:, None] + p_vv * (dv1 ** 2)[:, None] + p_v * ddv1[:, None]
    rot, o1 = drive.crank_frame.rotation, drive.crank_frame.origin
    return o1 + p @ rot.T, omega * vel @ rot.T, omega ** 2 * acc @ rot.T
