"""Command line: ``spatialkin looper --out DIR [--config FILE.toml]`` (the main job), ``spatialkin demo``
(torus ∩ sphere of the looper, every component), ``spatialkin bench [--out DIR] [--quick]`` (speed against
error: work–precision table, ratios against the peers, CSV and PNG), ``spatialkin design --targets FILE.toml``
(fit a looper drive to targets), ``spatialkin warmup`` (compile the kernels ahead) and ``spatialkin --version``.

Every bad input ends in one line on stderr and exit status 2.
"""
import argparse
import sys
import time


#: Exceptions that mean bad input or a situation the user must change (one line, exit 2), never a traceback.
USER_ERRORS = (ValueError, TypeError, OSError, KeyError, RuntimeError)


class OneLineParser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block) and exit status 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: {message} (see {self.prog.split()[0]} --help)\n")


def positive_float(text):
    """argparse type of a positive finite number (a tolerance)."""
    from .._lib.validation import check_positive
    try:
        return check_positive("the value", text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def demo(args):
    import spatialkin as sk                     # (imported already: this module is inside it)
    from ..mechanisms.looper import reference as ref
    t0 = time.perf_counter()
    sk.intersect(*ref.looper_pair(), tol=args.tol)
    total = time.perf_counter() - t0
    t1 = time.perf_counter()                    # (the table's times: a second call's, loading done)
    curves = sk.intersect(*ref.looper_pair(), tol=args.tol)
    again = time.perf_counter() - t1
    centre = ", ".join(f"{x:g}" for x in ref.ROCKER_CENTRE)
    print(f"torus(R={ref.CRANK_RADIUS:g}, r={ref.COUPLER_LENGTH:g}) ∩ sphere(R={ref.ROCKER_LENGTH:g}, centre "
          f"({centre})): {len(curves)} component(s)")
    print(f"{'#':>2} {'kind':>8} {'length':>14} {'points':>7} {'max dist':>10} {'rhs evals':>9} {'time [ms]':>9}")
    for k, c in enumerate(curves):
        kind = "closed" if c.closed else c.status
        print(f"{k:>2} {kind:>8} {c.length:>14.9f} {len(c):>7} {c.max_distance:>10.2e} {c.nfev:>9} "
              f"{1e3 * c.wall_time:>9.2f}")
    print(f"first call, compiling or loading its kernels included (spatialkin's import not): {total:.2f} s; a "
          f"second call: {1e3 * again:.2f} ms (its curves' times above)")
    return 0


def looper(args):
    from .looper_job import run
    run(args.out, args.config)
    return 0


def warm_up(args):
    from .warmup import main as compile_ahead
    return compile_ahead()


def bench(args):
    from .._lib.files import check_out_dir
    from ..bench import run
    if args.out is not None:
        check_out_dir(args.out)                 # (before the runs, not after them)
    run(args.out, quick=args.quick)
    return 0


def parser():
    from .. import __version__
    from .looper_job import keys_help, outputs_help
    top = OneLineParser(prog="spatialkin", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    top.add_argument("--version", action="version", version=f"spatialkin {__version__}")
    sub = top.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    p_looper = sub.add_parser("looper", help="the looper drive over a crank turn at machine speed: CSV, JSON record, "
                              "pictures, summary", formatter_class=argparse.RawDescriptionHelpFormatter,
                              description="The looper drive over a crank turn at machine speed: prints a "
                              "summary and writes into --out\n" + outputs_help(), epilog=keys_help())
    p_looper.add_argument("--out", required=True, help="output folder (created if missing)")
    p_looper.add_argument("--config", default=None, help="TOML file overriding the built-in drive (keys below)")
    p_looper.set_defaults(func=looper)
    demo_help = "trace torus ∩ sphere of the looper drive and print the components"
    p_demo = sub.add_parser("demo", help=demo_help, description=demo_help[0].upper() + demo_help[1:] + ".")
    p_demo.add_argument("--tol", type=positive_float, default=1e-10,
                        help="accuracy relative to the scene scale (positive; default 1e-10)")
    p_demo.set_defaults(func=demo)
    bench_help = ("speed against error: every solve_ivp method and tolerance, OpenCascade (if installed), the looper "
                  "against a per-angle root solve, planar's cases; the kernels are compiled (or loaded) first")
    p_bench = sub.add_parser("bench", help=bench_help, description=bench_help[0].upper() + bench_help[1:] + ".")
    p_bench.add_argument("--out", default=None, help="folder for bench.csv, bench.png, bench_kinds.csv and bench_kinds.png (created if missing)")
    p_bench.add_argument("--quick", action="store_true", help="a short run: two cases, two tolerances, one repeat")
    p_bench.set_defaults(func=bench)
    warm_help = ("compile the numerical kernels ahead, spatialkin's and every installed package's (planar's), for an "
                 "image or a cluster's workers, and report the time")
    p_warm = sub.add_parser("warmup", help=warm_help, description=warm_help[0].upper() + warm_help[1:] + ".")
    p_warm.set_defaults(func=warm_up)
    # listed here for --help; ``main`` hands `spatialkin design ...` to spatialkin/cli/design.py before parsing
    sub.add_parser("design", help="fit a looper drive to targets and write its config (spatialkin design --help)")
    return top


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["design"]:      # spatialkin design --targets FILE.toml (spatialkin/cli/design.py)
        from .design import main_design
        return main_design(argv[1:])
    args = parser().parse_args(argv)
    from .._lib import warm
    warm.say_with(lambda line: print(line, file=sys.stderr, flush=True))
    try:
        return args.func(args)
    except USER_ERRORS as err:
        message = " ".join(str(err).split()) or type(err).__name__
        print(f"spatialkin {args.command}: {message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"spatialkin {args.command}: interrupted", file=sys.stderr)
        return 130

