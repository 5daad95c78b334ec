"""Compile spatialkin's kernels ahead: the workload of the background warm-up (spatialkin._lib.warm) and of
``spatialkin warmup``.

The workload calls what a user's first calls reach: ``sk.intersect`` on a general pair of every kind of surface (15
kinds) and on trimmed faces (arcs ending on trim edges, open pieces of one loop told apart), each with and without
``certify=True`` (the closed forms' proofs, the tubes, the arcs against the trims), ``sk.trace`` (from a point, and
from ``sk.auxiliary_starts``), the looper drive over a turn with its analysis (and a drive whose crank does not turn
fully), ``certify=True`` on the looper pair, on circles in closed form, on a trimmed cylinder and on Viviani's
figure-eight (a node), its design sensitivities, ``sk.intersect_many``, a torus and its bitangent plane (Villarceau's
circles), and pairs whose loops pass close where the surfaces nearly touch (steps capped beside them: a torus and a
sphere, a torus and a plane just below its bitangent one); numba compiles every kernel and
specialisation they reach into its cache.
"""

#: Crank angles of the looper drive's turn in the workload.
ANGLES = 361


def run():
    """Call the workload (each kernel it reaches compiled, or loaded from the cache)."""
    import math

    import numpy as np

    import spatialkin as sk
    from ..bench.cases import torus_sphere_cases
    from ..bench.kinds import face_cases, pair_kind_cases
    from ..design import LooperDesign
    from ..mechanisms import LooperDrive
    for _, a, b in pair_kind_cases() + face_cases():
        for curve in sk.intersect(a, b):
            if curve.length > 0:
                curve(np.linspace(0.0, curve.length, 5))
                curve.closest(curve.points[:3])
                # (foot points, as the de-duplication of starts asks them: of writable arrays)
                curve.result.sol.foot_points(np.array(curve.points[:3]), np.array(curve.s[:3]), 2)
        sk.intersect(a, b, certify=True)
    face = sk.Cylinder(1.0, u_range=(0.0, 2.0), v_range=(-1.0, 1.0))
    sk.intersect(face, sk.Sphere(1.2, sk.Frame((0.5, 0.0, 0.3)), u_range=(-1.0, 2.5)))
    across = sk.Frame((0.1, 0.0, 0.0), [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])   # (a plane normal to x)
    sk.intersect(sk.Torus(1.0, 0.4), sk.Plane(across, u_range=(-2.0, 2.0), v_range=(-0.2, 0.2)))   # (4 arcs)
    sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))))
    sk.trace(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))), (0.5, 0.9, 0.0))
    sk.intersect_many([(sk.Torus(2.0, 1.0), sk.Sphere(1.2, sk.Frame((2.5, 0.0, 0.3))))])
    drive = LooperDrive.reference()
    sk.intersect(drive.torus, drive.sphere, certify=True)
    sk.trace(drive.torus, drive.sphere, sk.auxiliary_starts(drive.torus, drive.sphere)[0])
    sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))), certify=True)
    sk.intersect(sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.6))), certify=True)
    sk.intersect(sk.Cylinder(1.0, v_range=(-1.0, 1.0)), sk.Sphere(1.5, sk.Frame((0.05, 0.0, 0.0))), certify=True)
    sk.intersect(sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.5, 0.0, 0.0)), v_range=(-2.0, 2.0)), certify=True)
    for case in torus_sphere_cases()[2:]:       # (loops nearly touching, a small loop: steps capped beside them)
        sk.intersect(case.torus, case.sphere)
    turn = sk.rotation_about((0.3, -1.0, 0.2), 1.1)     # (a torus and planes at and just below its bitangent one)
    for tilt in (math.asin(0.5), math.asin(0.5 - 1e-9)):
        sk.intersect(sk.Torus(1.0, 0.5, sk.Frame((0.4, -0.2, 0.3), turn)),
                     sk.Plane(sk.Frame((0.4, -0.2, 0.3), turn @ sk.rotation_about((1.0, 0.0, 0.0), tilt)),
                              u_range=(-3.0, 3.0), v_range=(-3.0, 3.0)))
    angles = np.linspace(0.0, 2 * np.pi, ANGLES)
    motion = drive.solve(angles, omega=2.0, branch=0)
    drive.analyse(branch=0, samples=ANGLES)
    drive.torus.distance(motion.ball_center), drive.sphere.distance(motion.ball_center)
    motion.looper_tip
    partial = LooperDrive(drive.crank_radius, drive.coupler_length, drive.rocker_length,
                          rocker_frame=sk.Frame((40.0, 0.0, 60.0)))
    partial.analyse(branch=0, samples=ANGLES)
    LooperDesign.from_drive(drive).sensitivities(angles[::10])


def main(echo=print, names=None):
    """``spatialkin warmup``: compile every workload (names: these only) in the foreground (spatialkin's and each
    installed package's: spatialkin._lib.warm.compile_ahead), stamp the cache, report the time. Returns 0."""
    from .._lib import jit, warm
    warm.say_with(lambda line: None)    # (it says what it did when done)
    before = sum(len(d.signatures) for d in jit.dispatchers())
    seconds = warm.compile_ahead(names)
    after = sum(len(d.signatures) for d in jit.dispatchers())
    echo(f"spatialkin warmup: {after} kernel specialisations ready ({after - before} compiled or loaded here) in "
         f"{sum(seconds.values()):.1f} s ({', '.join(f'{name} {t:.1f} s' for name, t in seconds.items())}); "
         f"numba's cache: {warm.cache_folder()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
