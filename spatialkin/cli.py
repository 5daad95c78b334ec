"""Command line: ``spatialkin looper --out DIR [--config FILE.toml]`` (the main job) and ``spatialkin demo``
(torus ∩ sphere of the looper, every component) and ``spatialkin bench [--out DIR] [--quick]`` (speed against
error: work–precision table, goal ratios, CSV and PNG).
"""
import argparse
import sys
import time

import numpy as np


def reference_pair():
    """The looper drive's surfaces (reference geometry of ../shared/reference/looper-drive.md, mm)."""
    import spatialkin as sk
    torus = sk.Torus(8.0, 50.0)                                   # crank radius, coupler length
    sphere = sk.Sphere(30.0, sk.Frame((6.0, 0.0, 75.0), sk.rotation_about((1, 0, 0), -np.pi / 2)))
    return torus, sphere


def demo(args):
    t0 = time.perf_counter()
    import spatialkin as sk
    torus, sphere = reference_pair()
    curves = sk.intersect(torus, sphere, tol=args.tol)
    total = time.perf_counter() - t0
    print(f"torus(R=8, r=50) ∩ sphere(R=30, centre (6, 0, 75)): {len(curves)} component(s)")
    print(f"{'#':>2} {'kind':>8} {'length':>14} {'points':>7} {'max dist':>10} {'rhs evals':>9} {'time [ms]':>9}")
    for k, c in enumerate(curves):
        kind = "closed" if c.closed else c.status
        print(f"{k:>2} {kind:>8} {c.length:>14.9f} {len(c):>7} {c.max_distance:>10.2e} {c.nfev:>9} "
              f"{1e3 * c.wall_time:>9.2f}")
    print(f"import + compile/load + intersect: {total:.2f} s")
    return 0


def looper(args):
    from .looper_job import run
    try:
        run(args.out, args.config)
    except (ValueError, OSError) as err:
        print(f"spatialkin looper: {err}", file=sys.stderr)
        return 2
    return 0


def bench(args):
    from .bench import run
    try:
        run(args.out, quick=args.quick)
    except (ValueError, OSError, RuntimeError) as err:
        print(f"spatialkin bench: {err}", file=sys.stderr)
        return 2
    return 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["design"]:      # spatialkin design --targets FILE.toml (spatialkin/design/cli.py)
        from .design.cli import main_design
        return main_design(argv[1:])
    parser = argparse.ArgumentParser(prog="spatialkin", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p_looper = sub.add_parser("looper", help="the looper drive over a full crank turn: CSV, plot, summary")
    p_looper.add_argument("--out", required=True, help="output folder (created if missing)")
    p_looper.add_argument("--config", default=None, help="TOML file overriding the reference geometry")
    p_looper.set_defaults(func=looper)
    p_demo = sub.add_parser("demo", help="trace torus ∩ sphere of the looper drive and print the components")
    p_demo.add_argument("--tol", type=float, default=1e-10, help="accuracy relative to the scene scale")
    p_demo.set_defaults(func=demo)
    p_bench = sub.add_parser("bench", help="speed against error: every solve_ivp method and tolerance, "
                             "OpenCascade (if installed), the looper against a per-angle root solve")
    p_bench.add_argument("--out", default=None, help="folder for bench.csv and bench.png (created if missing)")
    p_bench.add_argument("--quick", action="store_true", help="a short run: two cases, two tolerances, one repeat")
    p_bench.set_defaults(func=bench)
    args = parser.parse_args(argv)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
