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
    """The work–precision figure (log–log), written whole or not at all. Per torus–sphere case, two panels
    against the wall time per curve: above, the relative error of the arc length s (what a solve_ivp method's
    tolerance buys: one line per method over the tolerances, and sk.intersect); below, the largest distance of
    the returned points and dense samples to either surface (Newton puts them on both whatever the tolerance),
    beside certify=True's proven bound and OpenCascade's points at its tolerances. The looper drive's panel: the
    position error against the closed form per crank angle. An exact zero is drawn at PLOT_ERROR_FLOOR, marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = [c for c in dict.fromkeys(r.case for r in rows) if c != "looper drive"]
    drive = [r for r in rows if r.case == "looper drive"]
    ncol = len(cases) + bool(drive)
    fig, axes = plt.subplots(2, ncol, figsize=(3.6 * ncol + 1.8, 6.6), squeeze=False)
    colours = {"sk.intersect (tol 1e-10)": "tab:olive", "certify=True: measured; proven bound (hollow)": "tab:cyan",
               "OpenCascade GeomAPI_IntSS (tol 1e-7, 1e-10)": "black"}
    methods = list(dict.fromkeys(r.method for r in rows if r.solver == "trace"))

    def colour(label):
        if label not in colours:            # (the methods' lines C0.., the drive's solvers after them)
            method = label.split(" ")[1] if label.startswith("trace ") else None
            colours[label] = f"C{(methods.index(method) if method in methods else len(colours)) % 10}"
        return colours[label]

    def floor(values):
        return [max(v, PLOT_ERROR_FLOOR) for v in values]

    for k, case in enumerate(cases):
        mine = [r for r in rows if r.case == case]
        top, bottom = axes[0, k], axes[1, k]
        for method in dict.fromkeys(r.method for r in mine if r.solver == "trace"):
            pts = sorted((r.per_curve, r.length_error, r.error) for r in mine
                         if r.solver == "trace" and r.method == method and not np.isnan(r.length_error))
            if pts:
                x, y, d = zip(*pts)
                label = f"trace {method} (rtol 1e-4 .. 1e-12)"
                top.plot(x, floor(y), "o-", ms=3, lw=1, color=colour(label), label=label)
                bottom.plot(x, floor(d), "o", ms=3, color=colour(label), alpha=0.6)
        for r in mine:
            if r.solver == "intersect":
                label = "sk.intersect (tol 1e-10)"
                top.plot([r.per_curve], floor([r.length_error]), "s", ms=8, color=colour(label), label=label)
                bottom.plot([r.per_curve], floor([r.error]), "s", ms=8, color=colour(label))
            elif r.solver == "certified":
                label = "certify=True: measured; proven bound (hollow)"
                bottom.plot([r.per_curve], floor([r.error]), "D", ms=7, color=colour(label), label=label)
                bound = proven_bound(r.extra)
                if bound is not None:
                    bottom.plot([r.per_curve], [bound], "D", ms=7, mfc="none", color=colour(label))
            elif r.solver == "OCC IntSS":
                label = "OpenCascade GeomAPI_IntSS (tol 1e-7, 1e-10)"
                bottom.plot([r.per_curve], floor([r.error]), "X", ms=9, color=colour(label), label=label)
        top.set_title(case)
        top.set_ylabel("arc length s: relative error")
        bottom.set_ylabel("points: distance to the surfaces")
        for ax in (top, bottom):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
        bottom.set_xlabel("wall time per curve [s]")
    if drive:
        ax = axes[0, -1]
        for r in drive:
            label = f"looper drive: {r.solver}"
            ax.plot([r.per_curve], floor([r.error]), "D", ms=8, color=colour(label), label=label)
            if r.error == 0.0:
                ax.annotate("exact (0)", (r.per_curve, PLOT_ERROR_FLOOR), textcoords="offset points", xytext=(8, 0),
                            va="center", fontsize=7)
        ax.set_title("looper drive, a turn")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time per crank angle [s]")
        ax.set_ylabel("position error vs closed form [mm]")
        ax.grid(True, which="both", alpha=0.3)
        axes[1, -1].set_visible(False)
    handles, labels = [], []
    for ax in axes.ravel():
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    fig.legend(handles, labels, loc="lower right", fontsize=7, frameon=False)
    fig.suptitle(f"speed against error (lengths in the cases' unit, mm for the drive); {title}", fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=90, format="png")
    plt.close(fig)


def proven_bound(extra):
    """The proven distance bound a certified row's notes give ('distance <= 6.7e-13'), or None."""
    _, found, rest = extra.partition("distance <= ")
    try:
        return float(rest.split()[0].rstrip(",;")) if found else None
    except (ValueError, IndexError):
        return None
