"""Consistency survey of near-degenerate pairs: each family of placements (a near-tangency, a trim edge grazed, an
apex beside the other surface, ...) at offsets 1e-9 to 1e-3 of either sign, in 3 random placements and both argument
orders; a family and offset whose answers (statuses, lengths to 4 digits) differ across placements or orders is
flagged "!!!". An empty list beside non-empty ones, or one component fewer, is a silent miss; TopologyError is an
honest refusal. The oracle is the intersection's invariance under rigid motion and argument order (and, for the
families whose truth is known, the README's and the tests' closed forms).

Run from the repository: ``python -m tests.spatialkin.tracing.survey_degenerate [family ...]`` (about 4 minutes on 2 cores
for all; the README's "Every component" section gives what it finds and names the tests that keep each family
consistent).
"""
import math
import sys
import time

import numpy as np

import spatialkin as sk

OFFSETS = (1e-9, 1e-7, 1e-5, 1e-3)
PLACEMENTS = 3


def rot(rng):
    """A random rotation."""
    return sk.rotation_about(rng.normal(size=3), rng.uniform(0, 6))


def fam_torus_sphere_off(rng, eps):
    """Sphere centred near the torus axis, tangent to the tube's outer equator, axis offset."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Sphere(1.3, sk.Frame(o + eps * R[:, 0], R))


def fam_torus_sphere_inner(rng, eps):
    """Sphere touching the inner equator (radius 0.7) from inside, offset."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Sphere(0.7, sk.Frame(o + eps * R[:, 0], R))


def fam_plane_torus_top(rng, eps):
    """Plane tangent to the torus top circle, tilted by eps."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    Rp = sk.rotation_about(R[:, 0], eps) @ R
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Plane(sk.Frame(o + 0.3 * R[:, 2], Rp), (-2, 2), (-2, 2))


def fam_cyl_torus_inner(rng, eps):
    """Cylinder touching the torus inner equator, axis offset."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Cylinder(0.7, sk.Frame(o + eps * R[:, 0], R), v_range=(-1, 1))


def fam_steinmetz_off(rng, eps):
    """Equal cylinders, crossing axes offset by eps."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    R2 = sk.rotation_about(R[:, 0], 1.1) @ R
    return (sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-2, 2)),
            sk.Cylinder(0.5, sk.Frame(o + eps * R[:, 0], R2), v_range=(-2, 2)))


def fam_steinmetz_radius(rng, eps):
    """Crossing axes, radii differ by eps."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    R2 = sk.rotation_about(R[:, 0], 1.1) @ R
    return sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-2, 2)), sk.Cylinder(0.5 + eps, sk.Frame(o, R2), v_range=(-2, 2))


def fam_sphere_sphere_torus(rng, eps):
    """Torus and sphere touching at one point of the outer equator (sphere off-axis)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Sphere(0.5, sk.Frame(o + (1.8 - eps) * R[:, 0], R))


def fam_cone_cyl_coaxial_off(rng, eps):
    """Cone inside a cylinder touching along a circle? (cone and cylinder coaxial: a circle), offset."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return (sk.Cone(0.5, sk.Frame(o, R), v_range=(0.1, 2.0)),
            sk.Cylinder(0.5, sk.Frame(o + eps * R[:, 0], R), v_range=(-1, 3)))


def fam_torus_torus_off(rng, eps):
    """Two equal tori, coaxial, one shifted along the axis by 0.6 - eps (touching tubes), then offset."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Torus(1.0, 0.3, sk.Frame(o + 0.6 * R[:, 2] + eps * R[:, 0], R))


def fam_plane_cyl_rim(rng, eps):
    """Tilted plane whose ellipse's top touches the cylinder rim v = 1 (within eps)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tilt = 0.4
    Rp = sk.rotation_about(R[:, 0], tilt) @ R
    top = 0.5 * math.tan(tilt)          # ellipse's highest point above its centre (radius 0.5)
    cyl = sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-1.0, 1.0))
    return cyl, sk.Plane(sk.Frame(o + (1.0 - top + eps) * R[:, 2], Rp), (-3, 3), (-3, 3))


def fam_sphere_cyl_rim(rng, eps):
    """Sphere on the axis: circle at height h touching the rim (v_max = h + eps)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    h = 0.3
    cyl = sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-1.0, h + eps))
    return cyl, sk.Sphere(math.hypot(0.5, h), sk.Frame(o + 0.02 * R[:, 0], R))


def fam_torus_plane_edge(rng, eps):
    """Plane through the torus, its trim edge tangent to a loop."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tor = sk.Torus(1.0, 0.3, sk.Frame(o, R))
    # plane z = 0.1 (local), the loop of the torus there: circles radius 1 +- sqrt(0.09-0.01); trim the plane's u at
    # the outer circle
    rout = 1 + math.sqrt(0.08)
    return tor, sk.Plane(sk.Frame(o + 0.1 * R[:, 2], R), (-3, rout + eps), (-3, 3))


def fam_cone_sphere_apex(rng, eps):
    """Small sphere centred on the cone axis near the apex."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    cone = sk.Cone(0.5, sk.Frame(o, R), v_range=(0.0, 2.0))
    return cone, sk.Sphere(abs(eps) * 3, sk.Frame(o + abs(eps) * 4 * R[:, 2] + 0.3 * abs(eps) * R[:, 0], R))


def fam_torus_cyl_rim(rng, eps):
    """Cylinder through the torus hole region cutting the tube, rim at a loop's top."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tor = sk.Torus(1.0, 0.3, sk.Frame(o, R))
    # cylinder radius 1 coaxial-ish offset 0.05: meets the tube in loops near z = +-0.3; trim v at 0.25
    return tor, sk.Cylinder(1.0, sk.Frame(o + 0.05 * R[:, 0], R), v_range=(-2.0, 0.25 + eps))


def fam_tiny_sphere_torus(rng, eps):
    """Tiny sphere straddling the torus surface."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tor = sk.Torus(1.0, 0.3, sk.Frame(o, R))
    return tor, sk.Sphere(abs(eps), sk.Frame(o + R @ np.array([1.3 + 0.5 * eps, 0.0, 0.0]), R))


def fam_corner(rng, eps):
    """Sphere whose circle on a trimmed plane passes through the rectangle's corner."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    pl = sk.Plane(sk.Frame(o, R), (-0.5, 0.5), (-0.5, 0.5))
    c = o + R @ np.array([0.0, 0.0, 0.3])
    return pl, sk.Sphere(math.sqrt(0.5 + 0.09) + eps, sk.Frame(c, R))


def fam_two_spheres_near_same(rng, eps):
    """Nearly coincident spheres (radii differ by eps, centres 0.1 apart)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Sphere(1.0, sk.Frame(o, R)), sk.Sphere(1.0 + eps, sk.Frame(o + 1e-3 * R[:, 0], R))


def fam_plane_cyl_ruling(rng, eps):
    """Plane through a cylinder nearly along a ruling (tilted by eps about the normal)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    cyl = sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-1, 1))
    Rp = sk.rotation_about(R[:, 1], eps) @ np.column_stack([R[:, 1], R[:, 2], R[:, 0]])
    return cyl, sk.Plane(sk.Frame(o + 0.3 * R[:, 0], Rp), (-2, 2), (-2, 2))


def fam_viviani_trim(rng, eps):
    """Viviani: sphere r=1, cylinder r=0.5 through the centre; cylinder trimmed near the node height 0."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Sphere(1.0, sk.Frame(o, R)), sk.Cylinder(0.5, sk.Frame(o + 0.5 * R[:, 0], R), v_range=(eps, 2.0))


def fam_cone_apex_on_sphere(rng, eps):
    """Cone apex near a sphere's surface."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Sphere(1.0, sk.Frame(o, R)), sk.Cone(0.4, sk.Frame(o + (1.0 + eps) * R[:, 0], R), v_range=(-1.0, 1.0))


def fam_torus_spindle(rng, eps):
    """Spindle-ish torus (R slightly below r) cut by a plane through the axis."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(0.5 - eps, 0.5, sk.Frame(o, R)), sk.Plane(sk.Frame(o + 0.1 * R[:, 2], R), (-2, 2), (-2, 2))


def fam_cone_apex_on_cyl(rng, eps):
    """Double cone apex near a cylinder's surface, axis tangent."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    cyl = sk.Cylinder(1.0, sk.Frame(o, R), v_range=(-2, 2))
    axis = R @ sk.rotation_about((1, 0, 0), 0.3)
    return cyl, sk.Cone(0.4, sk.Frame(o + (1.0 + eps) * R[:, 0], axis), v_range=(-1.0, 1.0))


def fam_cone_cone_apexes(rng, eps):
    """Two double cones, apexes eps apart, axes crossing."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return (sk.Cone(0.4, sk.Frame(o, R), v_range=(-1, 1)),
            sk.Cone(0.5, sk.Frame(o + eps * R[:, 0], sk.rotation_about(R[:, 0], 0.9) @ R), v_range=(-1, 1)))


def fam_villarceau_off(rng, eps):
    """Bitangent plane of a torus (Villarceau), offset by eps along its normal."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    Rmaj, r = 1.0, 0.4
    ang = math.asin(r / Rmaj)
    Rp = R @ sk.rotation_about((1, 0, 0), ang)
    return sk.Torus(Rmaj, r, sk.Frame(o, R)), sk.Plane(sk.Frame(o + eps * Rp[:, 2], Rp), (-2, 2), (-2, 2))


def fam_sphere_on_tube_circle(rng, eps):
    """Sphere centred (eps off) on the torus's tube-centre circle, radius = r: nodes."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Sphere(0.3, sk.Frame(o + R @ np.array([1.0, eps, 0.0]), R))


def fam_saddle_tiny(rng, eps):
    """Plane tangent to the torus inner equator region (saddle), offset by eps."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    Rp = R @ np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]]).T    # normal along local x
    return (sk.Torus(1.0, 0.3, sk.Frame(o, R)),
            sk.Plane(sk.Frame(o + (0.7 + eps) * R[:, 0], Rp), (-0.5, 0.5), (-0.5, 0.5)))


def fam_torus_torus_linked(rng, eps):
    """Two tori linked like chain links, tubes nearly touching."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    R2 = R @ sk.rotation_about((1, 0, 0), math.pi / 2)
    return (sk.Torus(1.0, 0.2, sk.Frame(o, R)),
            sk.Torus(1.0, 0.2, sk.Frame(o + (1.0 + 0.4 + eps) * R[:, 0] - 0.0 * R[:, 1], R2)))


def fam_cyl_cyl_trim_node(rng, eps):
    """Steinmetz pair (closed form) with a trim through a node region."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    R2 = sk.rotation_about(R[:, 0], 1.1) @ R
    return sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-2, 2)), sk.Cylinder(0.5 + 1e-4, sk.Frame(o, R2), v_range=(eps, 2))


def fam_sphere_cone_trim_apex(rng, eps):
    """Cone trimmed at v in [eps, 2] with a sphere around the apex."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Sphere(0.5, sk.Frame(o + 0.1 * R[:, 0], R)), sk.Cone(0.5, sk.Frame(o, R), v_range=(eps, 2))


def fam_torus_cyl_edge_graze(rng, eps):
    """Torus and a cylinder whose rim grazes the intersection loop's top."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tor = sk.Torus(1.0, 0.3, sk.Frame(o, R))
    # cylinder radius 1.1 coaxial: circles at z = +-sqrt(0.09 - 0.01); offset 0.02 tilts them slightly
    cyl = sk.Cylinder(1.1, sk.Frame(o + 0.02 * R[:, 0], R), v_range=(-1, math.sqrt(0.08) + eps))
    return tor, cyl


def fam_plane_torus_two_edges(rng, eps):
    """Plane through the torus, rectangle corner grazing the outer circle."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    tor = sk.Torus(1.0, 0.3, sk.Frame(o, R))
    rout = 1 + math.sqrt(0.08)
    c = (rout + eps) / math.sqrt(2)
    return tor, sk.Plane(sk.Frame(o + 0.1 * R[:, 2], R), (-3, c), (-3, c))


def fam_plane_torus_side(rng, eps):
    """Plane parallel to the torus axis touching the outer equator (tangent at a point, saddle-free)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    Rp = R @ np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]]).T
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Plane(sk.Frame(o + (1.3 - eps) * R[:, 0], Rp), (-2, 2), (-2, 2))


def fam_cyl_cyl_parallel(rng, eps):
    """Parallel axes, radii sum = distance - eps (touching along a ruling), trimmed."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return (sk.Cylinder(0.5, sk.Frame(o, R), v_range=(-1, 1)),
            sk.Cylinder(0.4, sk.Frame(o + (0.9 - eps) * R[:, 0], R), v_range=(-0.5, 1.5)))


def fam_cone_torus_apex(rng, eps):
    """Cone apex on the torus surface (outer equator), axis along the torus axis."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Cone(0.3, sk.Frame(o + (1.3 - eps) * R[:, 0], R), v_range=(-1, 1))


def fam_sphere_plane_trim_circle(rng, eps):
    """Sphere circle on a trimmed plane inscribed in the square (touching 4 edges)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    pl = sk.Plane(sk.Frame(o, R), (-0.5, 0.5), (-0.5, 0.5))
    return pl, sk.Sphere(math.sqrt(0.25 + 0.09) + eps, sk.Frame(o + 0.3 * R[:, 2], R))


def fam_torus_torus_cross(rng, eps):
    """Two tori with perpendicular axes, tubes tangent at a point."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    R2 = R @ sk.rotation_about((1, 0, 0), math.pi / 2)
    return sk.Torus(1.0, 0.3, sk.Frame(o, R)), sk.Torus(1.0, 0.3, sk.Frame(o + (2.6 - eps) * R[:, 0], R2))


def fam_cone_plane_apex_near(rng, eps):
    """Plane through near the cone apex, generic tilt (small ellipse/hyperbola)."""
    R, o = rot(rng), rng.uniform(-1, 1, 3)
    Rp = sk.rotation_about(R[:, 0], 0.3) @ R
    return sk.Cone(0.5, sk.Frame(o, R), v_range=(-1, 1)), sk.Plane(sk.Frame(o + eps * R[:, 2], Rp), (-2, 2), (-2, 2))

FAMILIES = [fam_torus_sphere_off, fam_torus_sphere_inner, fam_plane_torus_top, fam_cyl_torus_inner,
            fam_steinmetz_off, fam_steinmetz_radius, fam_sphere_sphere_torus, fam_cone_cyl_coaxial_off,
            fam_torus_torus_off, fam_plane_cyl_rim, fam_sphere_cyl_rim, fam_torus_plane_edge,
            fam_cone_sphere_apex, fam_torus_cyl_rim, fam_tiny_sphere_torus, fam_corner,
            fam_two_spheres_near_same, fam_plane_cyl_ruling, fam_viviani_trim, fam_cone_apex_on_sphere,
            fam_torus_spindle, fam_cone_apex_on_cyl, fam_cone_cone_apexes, fam_villarceau_off,
            fam_sphere_on_tube_circle, fam_saddle_tiny, fam_torus_torus_linked, fam_cyl_cyl_trim_node,
            fam_sphere_cone_trim_apex, fam_torus_cyl_edge_graze, fam_plane_torus_two_edges, fam_plane_torus_side,
            fam_cyl_cyl_parallel, fam_cone_torus_apex, fam_sphere_plane_trim_circle, fam_torus_torus_cross,
            fam_cone_plane_apex_near]


def answer(p, q):
    """(sorted (status, length to 4 digits) of sk.intersect(p, q), or (exception name,)), seconds."""
    t = time.process_time()
    try:
        out = tuple(sorted((c.status, float(f"{c.length:.4g}")) for c in sk.intersect(p, q)))
    except Exception as exc:                       # (the refusal is an answer too)
        out = (type(exc).__name__,)
    return out, time.process_time() - t


def survey(families=FAMILIES, echo=print):
    """Run the families; returns the keys ('family +offset') flagged as inconsistent."""
    flagged = []
    for family in families:
        for eps in OFFSETS:
            for sign in (1, -1):
                answers = []
                for seed in range(PLACEMENTS):
                    a, b = family(np.random.default_rng(seed), sign * eps)
                    answers += [answer(a, b), answer(b, a)]
                kinds = sorted(set(a for a, _ in answers), key=repr)    # (an exception's answer beside curves')
                key = f"{family.__name__} {sign * eps:+.0e}"
                if len(kinds) > 1:
                    flagged.append(key)
                worst = max(t for _, t in answers) * 1e3
                echo(("!!! " if len(kinds) > 1 else "    ") + f"{key:34s} max {worst:7.1f} ms "
                     + str(kinds if len(kinds) > 1 else kinds[0]))
    return flagged


if __name__ == "__main__":
    chosen = [f for f in FAMILIES if not sys.argv[1:] or f.__name__ in sys.argv[1:]]
    print(f"{len(survey(chosen))} inconsistent")
