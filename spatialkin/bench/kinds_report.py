"""The per-pair-kind side-by-side run (spatialkin.bench.sidebyside) written out: a CSV and a two-panel PNG (our
speed over OpenCascade's per pair kind, against parity; both errors), each written whole or not at all."""
import numpy as np

from .._lib.files import atomic_path
from .._lib import stages
from .report import write_table
from .baselines import OCC_DEFAULT_TOL
from .sidebyside import OUR_TOL

#: Columns of bench_kinds.csv: times in seconds, errors in length units, stage seconds per call.
COLUMNS = (["pair kind", "ours s", "OCC s", "OCC/ours", "our error", "OCC error", "our curves", "OCC curves"]
           + [f"{stages.LABELS[s]} s" for s in stages.STAGES] + ["compiled kernels s", "ours with points read s"])
#: The ratio axis reaches this many times past the largest ratio (room for the time labels).
LABEL_ROOM = 60.0
#: Errors below this are drawn at it (a log axis has no zero).
ERROR_FLOOR = 1e-17


def write_kinds_csv(rows, path):
    """One line per pair kind (sidebyside.KindRow), written whole or not at all."""
    write_table(path, COLUMNS, ([r.kind, cell(r.ours, ".6g"), cell(r.occ, ".6g"), cell(r.ratio, ".4g"),
                                 cell(r.our_error, ".3e"), cell(r.occ_error, ".3e"), r.our_curves, r.occ_curves]
                                + [f"{r.profile.seconds[s]:.6g}" for s in stages.STAGES]
                                + [cell(r.kernel, ".6g"), cell(r.ours_points, ".6g")]
                                for r in rows))


def cell(value, spec):
    """A CSV cell: the number formatted, or empty where it was not measured (OpenCascade not installed: NaN)."""
    return format(value, spec) if np.isfinite(value) else ""


def plot_kinds(rows, path, title):
    """Left: OCC time / our time per pair kind (log), with parity; right: both errors (log)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [r.kind for r in rows]
    y = np.arange(len(rows))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 0.32 * len(rows) + 1.8), sharey=True)
    ratios = np.array([r.ratio for r in rows])
    measured = np.isfinite(ratios)
    colours = ["tab:green" if q >= 1 else "tab:red" for q in ratios]
    left.barh(y, np.where(measured, ratios, 0.0), color=colours)
    if not measured.any():
        left.text(0.5, 0.5, "OpenCascade (cadquery-ocp) not installed:\nno side-by-side times",
                  transform=left.transAxes, ha="center", va="center", fontsize=8)
    left.axvline(1.0, color="grey", ls=":", lw=1, label="parity")
    left.set_xscale("log")
    finite = ratios[np.isfinite(ratios)]
    left.set_xlim(min(0.5, float(finite.min()) / 2) if finite.size else 0.1,
                  LABEL_ROOM * max(1.0, float(finite.max()) if finite.size else 1.0))
    left.set_xlabel("OpenCascade time / sk.intersect time (above 1: ours faster)")
    left.set_yticks(y, names)
    left.invert_yaxis()
    left.legend(fontsize=7, loc="upper right")
    left.grid(True, axis="x", which="both", alpha=0.3)
    for k, r in enumerate(rows):
        if not measured[k]:
            continue
        left.annotate(f"ours {1e3 * r.ours:.2f} ms, OCC {1e3 * r.occ:.2f} ms", (max(r.ratio, 1e-3), k), fontsize=6,
                      xytext=(3, -2), textcoords="offset points")
    right.plot([max(r.our_error, ERROR_FLOOR) for r in rows], y, "s", label=f"sk.intersect (tol {OUR_TOL:g})")
    if measured.any():
        right.plot([max(r.occ_error, ERROR_FLOOR) for r in rows], y, "X",
                   label=f"GeomAPI_IntSS (tol {OCC_DEFAULT_TOL:g})")
    right.set_xscale("log")
    right.set_xlabel("largest distance to either surface [length units]")
    right.legend(fontsize=7)
    right.grid(True, axis="x", which="both", alpha=0.3)
    fig.suptitle(title, fontsize=8)
    fig.tight_layout()
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=90, format="png")
    plt.close(fig)
