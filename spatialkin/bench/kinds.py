"""One general pair per pair kind of Plane, Sphere, Cylinder, Cone and Torus (15 kinds), for the per-kind
profile of sk.intersect and the side-by-side run against OpenCascade.

Each surface is placed by its own general frame (axes tilted, origins apart), the unbounded kinds trimmed to a
piece of a few units around the scene (a plane to a rectangle, a cylinder and a cone along the axis; the cone's
piece is one nappe away from its apex), so that every pair meets in curves of a few units, away from tangency.
"""
import itertools
import math

import numpy as np

from ..geometry.frame import Frame, rotation_about
from ..geometry.surfaces import Cone, Cylinder, Plane, Sphere, Torus

#: The kinds, in the order of their pair names.
KINDS = ("plane", "sphere", "cylinder", "cone", "torus")
#: Half-width of a trimmed plane's square, and the axial half-length of a trimmed cylinder (scene units).
PLANE_HALF = 2.0
CYLINDER_HALF = 2.0
#: Radii: sphere, cylinder, torus (major, minor); the cone's half angle and its trim along the axis (one
#: nappe, from near the apex to past the scene).
SPHERE_RADIUS = 1.0
CYLINDER_RADIUS = 0.8
TORUS_RADII = (1.2, 0.5)
CONE_HALF_ANGLE = 0.5
CONE_V_RANGE = (0.4, 3.0)
#: The cone's apex lies this far behind the scene centre along its axis (the piece passes through the centre).
CONE_APEX_BACK = 1.5
#: The angle between the axes of the Steinmetz pair (special_cases).
STEINMETZ_ANGLE = 1.2
#: The two placements of a pair (first surface, second surface): origin offset, rotation axis and angle.
PLACEMENTS = (((0.0, 0.0, 0.0), (1.0, 2.0, 0.5), 0.4),
              ((0.31, -0.22, 0.27), (-0.6, 0.3, 1.0), 1.1))


def surface(kind, slot):
    """The surface of `kind` in placement `slot` (0 or 1)."""
    offset, axis, angle = PLACEMENTS[slot]
    rot = rotation_about(axis, angle)
    origin = np.array(offset, dtype=float)
    if kind == "plane":
        return Plane(Frame(origin, rot), (-PLANE_HALF, PLANE_HALF), (-PLANE_HALF, PLANE_HALF))
    if kind == "sphere":
        return Sphere(SPHERE_RADIUS, Frame(origin, rot))
    if kind == "cylinder":
        return Cylinder(CYLINDER_RADIUS, Frame(origin, rot), (-CYLINDER_HALF, CYLINDER_HALF))
    if kind == "cone":
        return Cone(CONE_HALF_ANGLE, Frame(origin - CONE_APEX_BACK * rot[:, 2], rot), CONE_V_RANGE)
    if kind == "torus":
        return Torus(*TORUS_RADII, Frame(origin, rot))
    raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")


def pair_kind_cases():
    """[(name 'kind-kind', a, b)] for the 15 pair kinds, each surface in its own placement."""
    return [(f"{p}-{q}", surface(p, 0), surface(q, 1))
            for p, q in itertools.combinations_with_replacement(KINDS, 2)]


def special_cases():
    """[(name, a, b)] of special placements beside the general ones: two equal cylinders whose axes cross at
    STEINMETZ_ANGLE (the Steinmetz curves: two ellipses through two nodes, a pipe tee), in the first placement."""
    a = surface("cylinder", 0)
    axis = a.frame.rotation[:, 0]                       # normal to a's axis, through its origin
    rot = rotation_about(axis, STEINMETZ_ANGLE) @ a.frame.rotation
    b = Cylinder(CYLINDER_RADIUS, Frame(a.frame.origin, rot), (-CYLINDER_HALF, CYLINDER_HALF))
    return [("steinmetz cyl-cyl", a, b)]


def face_cases():
    """[(name, a, b)] of CAD faces, in the pair kinds' placements: trims that are not ranges of a length (half and
    quarter turns, a turn and a half, a sphere's band of latitudes, an annulus) cutting the components into arcs."""
    cylinder, cone, torus = surface("cylinder", 0), surface("cone", 0), surface("torus", 0)
    return [("half cylinder-sphere", Cylinder(CYLINDER_RADIUS, cylinder.frame, cylinder.v_range,
                                              u_range=(0.0, math.pi)), surface("sphere", 1)),
            ("quarter torus-cylinder", Torus(*TORUS_RADII, torus.frame, u_range=(0.0, 0.5 * math.pi)),
             surface("cylinder", 1)),
            ("3/4 cone-sphere", Cone(CONE_HALF_ANGLE, cone.frame, CONE_V_RANGE, u_range=(0.0, 1.5 * math.pi)),
             surface("sphere", 1)),
            ("sphere band-cylinder", Sphere(SPHERE_RADIUS, surface("sphere", 0).frame, v_range=(-0.4, 0.6)),
             surface("cylinder", 1)),
            ("annulus-torus", Plane(surface("plane", 0).frame, radius=1.6, inner_radius=0.6), surface("torus", 1))]


# --- the same surfaces as OpenCascade geometry (cadquery-ocp) ----------------------------------------------
def occ_surface(s):
    """The Geom_Surface of a spatialkin surface: the same placement (gp_Ax3 from its frame) and parametrisation
    (OCC's plane, sphere, cylinder and torus share spatialkin's (u, v); OCC's cone runs v along the slant, so
    the axial trim is divided by cos(half angle)), trimmed as it is (Geom_RectangularTrimmedSurface)."""
    from OCP.Geom import (Geom_ConicalSurface, Geom_CylindricalSurface, Geom_Plane, Geom_RectangularTrimmedSurface,
                          Geom_SphericalSurface, Geom_ToroidalSurface)
    from .baselines import ax3
    axes = ax3(s.frame)
    if isinstance(s, Plane):
        (u0, u1), (v0, v1) = s.u_range, s.v_range
        return Geom_RectangularTrimmedSurface(Geom_Plane(axes), u0, u1, v0, v1)
    if isinstance(s, Sphere):
        return Geom_SphericalSurface(axes, s.radius)
    if isinstance(s, Cylinder):
        v0, v1 = s.v_range
        return Geom_RectangularTrimmedSurface(Geom_CylindricalSurface(axes, s.radius), v0, v1, False)
    if isinstance(s, Cone):
        v0, v1 = s.v_range
        c = math.cos(s.half_angle)
        return Geom_RectangularTrimmedSurface(Geom_ConicalSurface(axes, s.half_angle, 0.0), v0 / c, v1 / c, False)
    if isinstance(s, Torus):
        return Geom_ToroidalSurface(axes, s.major_radius, s.minor_radius)
    raise TypeError(f"no OpenCascade surface for {type(s).__name__}")
