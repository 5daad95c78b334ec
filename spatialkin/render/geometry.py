"""Numbers behind the pictures, with no pyvista: checked inputs, surface grids, chord lengths, the looper's
links as polylines. The pyvista side (meshes.py, scene.py) only turns these arrays into datasets."""
import math

import numpy as np

from ..geometry.surfaces import Plane
from ..geometry.traits import check_surface
from .._lib.validation import check_range

#: Default grid of a surface: samples along u and along v.
SURFACE_RESOLUTION = (96, 48)
#: Fewest samples along a parameter direction of a surface grid.
MIN_RESOLUTION = 3


def chord_length(points):
    """Cumulative chord length (N,) along points (N, 3), from 0: the arc length of the polyline."""
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(steps)])


def natural_domain(surface):
    """((u_lo, u_hi), (v_lo, v_hi)) of a surface's face: its trims where it has them (an angular range too),
    else its own chart's (the full turn of an angle), infinite where the surface is unbounded."""
    own = surface.traits.natural_domain(surface)
    return tuple(tuple(trim) if math.isfinite(trim[0]) and math.isfinite(trim[1]) else domain
                 for trim, domain in zip((surface.u_range, surface.v_range), own))


def _check_range(name, value, default):
    lo, hi = check_range(name, default if value is None else value)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"{name} must be finite to mesh the surface (it is unbounded there), got "
                         f"({lo}, {hi}); give {name}=(min, max)")
    return lo, hi


def parameter_domain(surface, u_range=None, v_range=None):
    """Finite ((u_lo, u_hi), (v_lo, v_hi)) to mesh: the given ranges, else the surface's own (its trimmed
    ranges; the full turn for angles). ValueError naming u_range / v_range where it would be unbounded, TypeError
    naming surface when it is not a spatialkin surface."""
    check_surface("surface", surface)
    u0, v0 = natural_domain(surface)
    return _check_range("u_range", u_range, u0), _check_range("v_range", v_range, v0)


def surface_grid(surface, u_range=None, v_range=None, resolution=SURFACE_RESOLUTION):
    """Points (nu, nv, 3) of surface.point(u, v) on a uniform grid of its parameter domain (periodic
    directions include both ends, so the grid closes; the mesh merges the seam)."""
    try:
        nu, nv = (int(n) for n in resolution)
    except (TypeError, ValueError):
        raise ValueError(f"resolution must be a pair (nu, nv) of integers, got {resolution!r}") from None
    if min(nu, nv) < MIN_RESOLUTION:
        raise ValueError(f"resolution must be at least ({MIN_RESOLUTION}, {MIN_RESOLUTION}), got {resolution!r}")
    (u_lo, u_hi), (v_lo, v_hi) = parameter_domain(surface, u_range, v_range)
    if isinstance(surface, Plane) and surface.radius is not None and u_range is v_range is None:
        return disc_grid(surface, nu, nv, (u_lo, u_hi), (v_lo, v_hi))
    u, v = np.meshgrid(np.linspace(u_lo, u_hi, nu), np.linspace(v_lo, v_hi, nv), indexing="ij")
    return surface.point(u, v)


def disc_grid(plane, n_turn, n_radius, u_range, v_range):
    """Points (n_turn, n_radius, 3) of a plane's disc or annulus on a polar grid (the turn closes), pressed into
    its rectangle where one cuts the disc."""
    inner = plane.inner_radius or 0.0
    turn, rho = np.meshgrid(np.linspace(0.0, 2.0 * math.pi, n_turn), np.linspace(inner, plane.radius, n_radius),
                            indexing="ij")
    u = np.clip(rho * np.cos(turn), *u_range)
    v = np.clip(rho * np.sin(turn), *v_range)
    return plane.point(u, v)


def looper_links(motion, index):
    """The looper drive drawn at one of the motion's crank angles.

    Parameters
    ----------
    motion : LooperMotion
    index : int
        Which of the motion's crank angles.

    Returns
    -------
    links : dict of name -> ndarray (K, 3)
        Polylines: 'crank' (shaft centre to crank pin), 'coupler' (pin to ball centre C), 'rocker_arm'
        (rocker centre P2 to C), 'looper' (the looper link's origin, along its x to the tip's abscissa, to
        the tip), 'crank_shaft' and 'rocker_shaft' (the two shaft axes through their centres).
    joints : ndarray (4, 3)
        Shaft centre, crank pin, ball centre C, rocker centre P2.
    """
    n = len(motion.crank_angle)
    if not (isinstance(index, (int, np.integer)) and -n <= index < n):
        raise ValueError(f"index must be an integer in [{-n}, {n}) (one of the motion's crank angles), "
                         f"got {index!r}")
    drive = motion.drive
    links = motion.links()
    shaft = links["crank"].origin[index]
    pin = links["coupler"].origin[index]
    ball = motion.ball_center[index]
    centre = links["rocker_arm"].origin[index]
    tip_link = links[drive.looper_link]
    tip = drive.looper_tip
    along = tip_link.origin[index] + tip_link.rotation[index] @ np.array([tip[0], 0.0, 0.0])
    tip_point = tip_link.origin[index] + tip_link.rotation[index] @ tip
    half = 0.25 * drive.coupler_length       # shaft axes drawn this far either side of their centres
    crank_axis = drive.crank_frame.rotation[:, 2]
    rocker_axis = drive.rocker_frame.rotation[:, 2]
    out = {
        "crank": np.array([shaft, pin]),
        "coupler": np.array([pin, ball]),
        "rocker_arm": np.array([centre, ball]),
        "looper": np.array([tip_link.origin[index], along, tip_point]),
        "crank_shaft": np.array([shaft - half * crank_axis, shaft + half * crank_axis]),
        "rocker_shaft": np.array([centre - half * rocker_axis, centre + half * rocker_axis]),
    }
    return out, np.array([shaft, pin, ball, centre])
