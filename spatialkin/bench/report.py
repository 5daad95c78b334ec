"""The bench's table (text and CSV), its plot (error against time, log–log) and the machine it ran on."""
import csv
import os
import platform

import numpy as np

from .._lib.files import atomic_path

#: Errors are drawn no lower than this on the log axis (an exact zero has no logarithm).
PLOT_ERROR_FLOOR = 1e-17
COLUMNS = ("case", "solver", "method", "rtol", "curves", "expected", "seconds", "per_curve", "error",
           "length_error", "nfev", "extra")


def machine():
    """CPU model, cores and the versions that matter, as one line."""
    import numba
    import scipy
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    return (f"{cpu}, {os.cpu_count()} cores; Python {platform.python_version()}, numpy {np.__version__}, "
            f"scipy {scipy.__version__}, numba {numba.__version__}")


def _tol(r):
    return "-" if np.isnan(r.rtol) else f"{r.rtol:.0e}"


def _len(r):
    return "-" if np.isnan(r.length_error) else f"{r.length_error:.1e}"


def table(rows):
    """The work–precision table as text lines."""
    head = (f"{'case':<13} {'solver':<11} {'method':<7} {'rtol/tol':>8} {'curves':>6} {'ms/call':>9} "
            f"{'ms/curve':>9} {'max error':>9} {'len err':>8} {'nfev':>6}  notes")
    lines = [head, "-" * len(head)]
    for r in rows:
        found = f"{r.curves}/{r.expected}" if r.solver not in ("LooperDrive", "closed form", "scipy root") \
            else f"{r.curves}"
        lines.append(f"{r.case:<13} {r.solver:<11} {r.method:<7} {_tol(r):>8} {found:>6} {1e3 * r.seconds:>9.3f} "
                     f"{1e3 * r.per_curve:>9.4f} {r.error:>9.1e} {_len(r):>8} {r.nfev or '':>6}  {r.extra}")
    return lines


def comparison_lines(c, runner_module):
    """The measured ratios against the peers (c: runner.Comparisons) and the start-up time, one line each;
    runner_module is where COMPARE_ERROR is defined (spatialkin.bench.runner)."""
    def measured(value, detail):
        return detail if np.isnan(value) else f"{value:.1f}x; {detail}"
    startup = "not measured (--quick)" if np.isnan(c.startup) else f"{c.startup:.2f} s"
    angles = f", {c.looper_angles} crank angles" if c.looper_angles else ""
    return [
        f"vs OpenCascade: closed loop within {runner_module.COMPARE_ERROR:g} of both surfaces, OCC IntSS time / "
        f"trace time per curve: {measured(c.occ_ratio, c.occ_detail)}",
        f"vs per-angle root solve: looper full turn{angles} with velocities and accelerations, scipy root time / "
        f"LooperDrive time: {measured(c.looper_ratio, c.looper_detail)}",
        f"start-up: import + first intersect in a fresh process (warm numba cache): {startup}",
    ] + ([f"calls: one sk.intersect of the looper's pair calls {c.calls[0]} Python functions, each compiled kernel "
          f"one of them ({c.calls[1]} with C builtins; cProfile)"] if c.calls else [])


def write_table(path, columns, lines):
    """A CSV file of a header (columns) and lines (lists of cells), written whole or not at all."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(columns)
            w.writerows(lines)


def write_csv(rows, path):
    """The table as CSV (seconds, lengths in the cases' units), written whole or not at all."""
    write_table(path, COLUMNS, ([r.case, r.solver, r.method, r.rtol, r.curves, r.expected, f"{r.seconds:.6g}",
                                 f"{r.per_curve:.6g}", f"{r.error:.3e}", f"{r.length_error:.3e}", r.nfev, r.extra]
                                for r in rows))


def plot(rows, path, title):
    """Error against wall time per curve (log–log), one panel per case, written whole or not at all."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(dict.fromkeys(r.case for r in rows))
    ncol = min(3, len(cases))
    nrow = -(-len(cases) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.8 * nrow), squeeze=False)
    for ax, case in zip(axes.ravel(), cases):
        mine = [r for r in rows if r.case == case]
        for method in dict.fromkeys(r.method for r in mine if r.solver == "trace"):
            pts = sorted((r.per_curve, r.error) for r in mine if r.solver == "trace" and r.method == method)
            x, y = zip(*pts)
            ax.plot(x, np.maximum(y, PLOT_ERROR_FLOOR), "o-", ms=4, label=f"trace {method}")
        for r in mine:
            if r.solver == "trace":
                continue
            label = r.solver if np.isnan(r.rtol) else f"{r.solver} tol {r.rtol:g}"
            marker = {"intersect": "s", "OCC IntSS": "X"}.get(r.solver, "D")
            ax.plot([r.per_curve], [max(r.error, PLOT_ERROR_FLOOR)], marker, ms=8, label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(case)
        ax.set_xlabel("wall time per curve [s]" if case != "looper drive" else "wall time per crank angle [s]")
        ax.set_ylabel("max distance to the exact curve")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    for ax in axes.ravel()[len(cases):]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=8)
    fig.tight_layout()
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=90, format="png")
    plt.close(fig)
