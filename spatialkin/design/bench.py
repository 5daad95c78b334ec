"""Bench of spatialkin.design: exact sensitivities against central differences (time and error side by side),
and sweep throughput on 1 and 2 processes.

    python -m spatialkin.design.bench [--quick]
"""
import argparse
import sys
import time

import numpy as np

from .looper import LooperDesign
from .params import PARAMETERS
from .sensitivity import sensitivities
from .sweep import random_space, sweep

#: Crank angles of the sensitivity bench (0.1 deg steps over a full turn).
BENCH_ANGLES = 3601
#: Central-difference steps compared (length units / rad).
FD_STEPS = (1e-3, 1e-5, 1e-7)
#: Outputs compared: (0, 1, 2) derivatives in the crank angle of the ball centre and the looper tip.
FIELDS = ("ball_center", "ball_velocity", "ball_acceleration", "tip", "tip_velocity", "tip_acceleration",
          "rocker_angles")
#: The sweep bench draws its parameters within this fraction of the reference values.
SWEEP_REACH = 0.15
#: Geometries of the sweep bench.
SWEEP_GEOMETRIES = 400


def _best_of(repeats, func):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = func()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _motion_fields(design, angles):
    """The compared outputs straight from LooperDrive.solve (the cheapest evaluation for differences)."""
    motion = design.drive().solve(angles)
    tip = motion.looper_tip
    return {"ball_center": motion.ball_center, "ball_velocity": motion.ball_velocity,
            "ball_acceleration": motion.ball_acceleration, "tip": tip.position, "tip_velocity": tip.velocity,
            "tip_acceleration": tip.acceleration, "rocker_angles": motion.rocker_angles}


def sensitivity_rows(design, angles, repeats=3):
    """[(method, seconds, {field: max |error| / max |exact derivative|})] for exact and central differences."""
    t_exact, exact = _best_of(repeats, lambda: sensitivities(design, angles, free=PARAMETERS, turning=False))
    rows = [("exact (implicit function theorem)", t_exact, None)]
    for h in FD_STEPS:
        def central(h=h):
            cols = {f: [] for f in FIELDS}
            for name in PARAMETERS:
                plus, minus = (_motion_fields(design.replace(**{name: design.values[name] + sign * h}), angles)
                               for sign in (1, -1))
                for f in FIELDS:
                    cols[f].append((plus[f] - minus[f]) / (2 * h))
            return {f: np.moveaxis(np.array(v), 0, -1) for f, v in cols.items()}
        t_fd, fd = _best_of(1, central)
        errors = {f: float(np.max(np.abs(fd[f] - exact.jacobian(f))) / np.max(np.abs(exact.jacobian(f))))
                  for f in FIELDS}
        rows.append((f"central differences h={h:g}", t_fd, errors))
    return rows


def sweep_rows(design, count, process_counts=(1, 2)):
    """[(label, geometries, seconds, rate, failed)] of one sweep of random geometries per process count."""
    free = ("crank_radius", "coupler_length", "rocker_length", "rocker_x", "rocker_z")
    bounds = {n: tuple(sorted((design.values[n] * (1 - SWEEP_REACH), design.values[n] * (1 + SWEEP_REACH))))
              for n in free}
    space = random_space(LooperDesign(design.values, free, bounds), count, seed=0)
    sweep({"crank_radius": [design.values["crank_radius"]]}, ("swing",), base=design, processes=1, progress=False,
          as_frame=False)             # start the forkserver (it imports spatialkin and loads the kernels once)
    rows = []
    for p in (0,) + tuple(process_counts):
        t0 = time.perf_counter()
        table = sweep(space, ("swing", "min_transmission", "assembly_margin"), base=design, processes=p,
                      progress=False, as_frame=False)
        dt = time.perf_counter() - t0
        label = "in this process" if p == 0 else f"{p} process{'es' if p > 1 else ''}"
        rows.append((label, count, dt, count / dt, int((~table["ok"]).sum())))
    return rows


def design_bench(quick=False, echo=print):
    """Print (and return) the bench tables: sensitivities for 3601 crank angles x all 12 parameters against
    central differences, and sweep throughput on 1 and 2 processes."""
    design = LooperDesign.reference().replace(rocker_y=2.0, rocker_rz=0.05)
    angles = np.linspace(0.0, 2 * np.pi, 361 if quick else BENCH_ANGLES)
    sensitivities(design, angles[:10])             # load the jitted kernels before timing
    rows = sensitivity_rows(design, angles, repeats=1 if quick else 3)
    echo(f"sensitivities of the looper drive: {len(angles)} crank angles x {len(PARAMETERS)} parameters "
         "(error = max |d - exact| / max |exact|)")
    head = f"{'method':<36}{'time [s]':>10}" + "".join(f"{f:>20}" for f in FIELDS)
    echo(head)
    for method, seconds, errors in rows:
        cells = "".join(f"{'(reference)':>20}" if errors is None else f"{errors[f]:>20.2e}" for f in FIELDS)
        echo(f"{method:<36}{seconds:>10.3f}{cells}")
    count = 40 if quick else SWEEP_GEOMETRIES
    srows = sweep_rows(design, count)
    echo("")
    echo(f"sweep throughput: {count} random geometries (5 parameters within ±{100 * SWEEP_REACH:g} %), "
         "361 crank angles each, outputs swing, min_transmission, assembly_margin (wall time includes starting the pool; the "
         "forkserver that the workers fork from is started before timing)")
    echo(f"{'workers':<18}{'geometries':>11}{'time [s]':>10}{'geom/s':>9}{'failed':>8}")
    for label, n, dt, rate, failed in srows:
        echo(f"{label:<18}{n:>11d}{dt:>10.2f}{rate:>9.1f}{failed:>8d}")
    return rows, srows


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m spatialkin.design.bench", description=__doc__)
    parser.add_argument("--quick", action="store_true", help="361 angles, 40 geometries, no repeats")
    args = parser.parse_args(argv)
    design_bench(quick=args.quick)
    return 0


if __name__ == "__main__":
    sys.exit(main())
