"""The per-pair-kind side-by-side run (spatialkin.bench.sidebyside) written out: a CSV and a PNG (per pair kind,
OpenCascade's time over ours drawn from parity, both times, both errors), each written whole or not at all."""
import numpy as np

from .._lib.files import atomic_path
from .._lib import stages
from .report import write_table
from .baselines import OCC_DEFAULT_TOL
from .sidebyside import OUR_TOL

#: Columns of bench_kinds.csv: times in seconds, errors in length units, stage seconds per call.
#: "ours s", "OCC s" and "OCC/ours" are warm (each side's second call in a row), the cold ones its first (right after
#: the other library's calls), the loop ones per call in blocks of calls back to back (sidebyside.KindRow).
COLUMNS = (["pair kind", "ours s", "OCC s", "OCC/ours", "our error", "OCC error", "our curves", "OCC curves"]
           + [f"{stages.LABELS[s]} s" for s in stages.STAGES] + ["compiled kernels s", "ours with points read s",
                                                                  "ours cold s", "OCC cold s", "OCC/ours cold",
                                                                  "ours loop s", "OCC loop s", "OCC/ours loop"])
#: The ratio axis reaches this factor past the smallest and the largest ratio (and parity), room for their labels.
RATIO_MARGIN = 2.5
#: Errors below this are drawn at it (a log axis has no zero).
ERROR_FLOOR = 1e-17
#: Colours of a bar: sk.intersect faster (ratio above 1), OpenCascade faster; of the cold ratio's marker.
FASTER_COLOR, SLOWER_COLOR, COLD_COLOR = "tab:green", "tab:red", "black"
#: Rows of the error panel: ours drawn this far (rows) above the row's centre, OpenCascade's as far below.
ERROR_OFFSET = 0.2
#: Figure size: width (inches), height per pair kind and for the title and axis labels; dots per inch.
FIGURE_WIDTH, ROW_HEIGHT, FRAME_HEIGHT, DPI = 10.0, 0.34, 1.9, 100
#: Text sizes (points): tick labels, axis labels, legends, per-bar numbers, title; characters a title line holds.
TICK_SIZE, LABEL_SIZE, LEGEND_SIZE, NUMBER_SIZE, TITLE_SIZE, TITLE_WIDTH = 10, 10, 9, 9, 10, 110
#: Widths of the three panels: ratio bars, the times column, errors.
PANEL_WIDTHS = (1.0, 0.38, 1.0)


def write_kinds_csv(rows, path):
    """One line per pair kind (sidebyside.KindRow), written whole or not at all."""
    write_table(path, COLUMNS, ([r.kind, cell(r.ours, ".6g"), cell(r.occ, ".6g"), cell(r.ratio, ".4g"),
                                 cell(r.our_error, ".3e"), cell(r.occ_error, ".3e"), r.our_curves, r.occ_curves]
                                + [f"{r.profile.seconds[s]:.6g}" for s in stages.STAGES]
                                + [cell(r.kernel, ".6g"), cell(r.ours_points, ".6g"), cell(r.ours_cold, ".6g"),
                                   cell(r.occ_cold, ".6g"), cell(r.cold_ratio, ".4g"), cell(r.ours_loop, ".6g"),
                                   cell(r.occ_loop, ".6g"), cell(r.loop_ratio, ".4g")]
                                for r in rows))


def cell(value, spec):
    """A CSV cell: the number formatted, or empty where it was not measured (OpenCascade not installed: NaN)."""
    return format(value, spec) if np.isfinite(value) else ""


def plot_kinds(rows, path, title):
    """Write kinds_figure(rows, title) as a PNG, whole or not at all."""
    fig = kinds_figure(rows, title)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=DPI, format="png")


def kinds_figure(rows, title):
    """Per pair kind (one row each), a matplotlib Figure of three panels sharing the rows.

    Left: OpenCascade's time over ours on a log axis, each bar drawn from parity (1) to the warm ratio (each side's
    second call in a row): to the right (green) where sk.intersect is faster, to the left (red) where OpenCascade
    is; a black mark at the cold ratio (each side's first call, right after the other library's) and a hollow
    diamond at the loop ratio (calls back to back), where measured; the warm ratio written past the row's marks.
    Middle: both times in ms. Right: the largest measured distance to either surface of each answer (log),
    ours above the row's centre and OpenCascade's below it, so that equal errors do not hide each other.

    Parameters
    ----------
    rows : list of sidebyside.KindRow
        Times in seconds (OpenCascade's NaN when it is not installed), errors in length units.
    title : str
        Wrapped at its '; ' to lines of about TITLE_WIDTH characters.
    """
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator

    y = np.arange(len(rows))
    ratios = np.array([r.ratio for r in rows], dtype=float)
    measured = np.isfinite(ratios)
    colds = np.array([r.cold_ratio for r in rows], dtype=float)
    cold = np.isfinite(colds)
    loops = np.array([r.loop_ratio for r in rows], dtype=float)
    loop = np.isfinite(loops)
    fig = Figure(figsize=(FIGURE_WIDTH, ROW_HEIGHT * len(rows) + FRAME_HEIGHT), layout="constrained")
    left, middle, right = fig.subplots(1, 3, sharey=True, gridspec_kw={"width_ratios": PANEL_WIDTHS})
    for ax in (left, middle, right):
        for k in y[::2]:                                  # bands that carry the eye along a row
            ax.axhspan(k - 0.5, k + 0.5, color="0.95", zorder=0, lw=0)
        ax.tick_params(labelsize=TICK_SIZE)

    colours = [FASTER_COLOR if q >= 1 else SLOWER_COLOR for q in np.where(measured, ratios, 1.0)]
    left.barh(y[measured], ratios[measured] - 1.0, left=1.0, height=0.6, color=np.array(colours)[measured],
              zorder=2)
    left.axvline(1.0, color="black", lw=1, zorder=3)
    left.set_xscale("log")
    if cold.any():
        left.plot(colds[cold], y[cold], "|", ms=14, mew=2.5, color=COLD_COLOR, zorder=4)
    if loop.any():
        left.plot(loops[loop], y[loop], "D", ms=6, mew=1.5, mfc="none", color=COLD_COLOR, zorder=4)
    drawn = np.concatenate([ratios[measured], colds[cold], loops[loop]])
    low = min(1.0, float(drawn.min())) if drawn.size else 1.0
    high = max(1.0, float(drawn.max())) if drawn.size else 1.0
    left.set_xlim(low / RATIO_MARGIN, high * RATIO_MARGIN)
    left.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    left.xaxis.set_minor_locator(NullLocator())
    left.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
    for k in np.nonzero(measured)[0]:
        q = ratios[k]                   # the warm ratio, written past the bar's end and the row's marks
        marks = [x for x in (q, colds[k], loops[k]) if np.isfinite(x)]
        at = max(marks) if q >= 1 else min(marks)
        left.annotate(f"{q:.2g}\u00d7", (at, k), xytext=(8 if q >= 1 else -8, 0), textcoords="offset points",
                      ha="left" if q >= 1 else "right", va="center", fontsize=NUMBER_SIZE)
    if measured.any():
        handles = [Patch(color=FASTER_COLOR, label="sk.intersect faster"),
                   Patch(color=SLOWER_COLOR, label="OpenCascade faster")]
        if cold.any():
            handles.append(Line2D([], [], marker="|", ms=10, mew=2.5, ls="none", color=COLD_COLOR,
                                  label="cold: each call after\nthe other library's"))
        if loop.any():
            handles.append(Line2D([], [], marker="D", ms=6, mew=1.5, mfc="none", ls="none", color=COLD_COLOR,
                                  label="loop: calls\nback to back"))
        left.legend(handles=handles, fontsize=LEGEND_SIZE, loc="upper right")
    else:
        left.text(0.5, 0.5, "OpenCascade (cadquery-ocp) not installed:\nno side-by-side times",
                  transform=left.transAxes, ha="center", va="center", fontsize=LABEL_SIZE,
                  bbox={"facecolor": "white", "edgecolor": "none"}, zorder=4)
    left.set_xlabel("OpenCascade time / sk.intersect time\n(bars: warm; 1 = parity; right: ours faster)",
                    fontsize=LABEL_SIZE)
    left.set_yticks(y, [r.kind for r in rows])
    left.set_ylim(len(rows) - 0.5, -0.5)                  # first row on top
    left.grid(True, axis="x", alpha=0.3)

    middle.set_xlim(0.0, 1.0)
    middle.tick_params(left=False, bottom=False, labelbottom=False)
    for side in middle.spines.values():
        side.set_visible(False)
    for k, r in enumerate(rows):
        occ = f"{1e3 * r.occ:.3g}" if np.isfinite(r.occ) else "\u2013"
        middle.text(0.5, k, f"{1e3 * r.ours:.3g} / {occ}", ha="center", va="center", fontsize=NUMBER_SIZE)
    middle.set_xlabel("ms per call, warm\nsk.intersect / OpenCascade", fontsize=LABEL_SIZE)

    right.plot([max(r.our_error, ERROR_FLOOR) for r in rows], y - ERROR_OFFSET, "s", ms=6, color="tab:blue",
               label=f"sk.intersect (tol {OUR_TOL:g})", zorder=3)
    if measured.any():
        right.plot([max(r.occ_error, ERROR_FLOOR) for r in rows], y + ERROR_OFFSET, "X", ms=7, color="tab:orange",
                   label=f"GeomAPI_IntSS (tol {OCC_DEFAULT_TOL:g})", zorder=3)
    right.set_xscale("log")
    drawn = [max(e, ERROR_FLOOR) for r in rows for e in (r.our_error, r.occ_error) if np.isfinite(e)]
    if drawn:                                 # whole decades, labelled at the decades only (no crowded minor labels)
        lo, hi = np.floor(np.log10(min(drawn))), np.ceil(np.log10(max(drawn)))
        right.set_xlim(10.0 ** lo, 10.0 ** max(hi, lo + 1))
    from matplotlib.ticker import NullFormatter
    right.xaxis.set_minor_formatter(NullFormatter())
    right.set_xlabel("largest distance to either surface\n[length units]", fontsize=LABEL_SIZE)
    right.legend(fontsize=LEGEND_SIZE, loc="upper center")
    right.grid(True, axis="x", which="major", alpha=0.3)
    fig.suptitle(wrap_title(title), fontsize=TITLE_SIZE)
    return fig


def wrap_title(title, width=TITLE_WIDTH):
    """title broken into lines at its '; ' (kept as ';'), each line as many parts as fit in width characters."""
    lines = []
    for part in str(title).split("; "):
        if lines and len(lines[-1]) + 2 + len(part) <= width:
            lines[-1] += "; " + part
        else:
            lines.append(part)
    return ";\n".join(lines)
