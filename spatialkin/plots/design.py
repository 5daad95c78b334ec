"""Pictures of spatialkin.design's results with matplotlib (presentation layer): the tip-path tolerance
envelope, and a sweep's outputs over two swept parameters."""
import math

import numpy as np

#: Half-width of the drawn envelope in standard deviations.
ENVELOPE_SIGMAS = 3.0
#: The envelope's half-width drawn at least this fraction of the path's size (deviations exaggerated), and the
#: Monte-Carlo paths drawn at most.
VISIBLE, MC_DRAWN = 0.04, 100


def _figure(size):
    """A matplotlib Figure outside pyplot (no global state, no backend switch; notebooks display it)."""
    from matplotlib.figure import Figure
    return Figure(figsize=size)


def path_plane(points):
    """Two orthonormal axes (3,), (3,) spanning the plane that fits the points (N, 3) best (PCA)."""
    centred = points - points.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    return vt[0], vt[1]


def exaggeration(width, size):
    """The factor (1, 2 or 5 times a power of ten; at least 1) that draws a band of half-width `width` at VISIBLE
    of a picture of `size` or more."""
    if not width > 0 or width >= VISIBLE * size:
        return 1
    want = VISIBLE * size / width
    decade = 10.0 ** math.floor(math.log10(want))
    return next(f * decade for f in (1, 2, 5, 10) if f * decade >= want)


def tolerance_figure(result, path=None, sigmas=ENVELOPE_SIGMAS, unit="mm"):
    """The looper tip's path with its tolerance envelope: left, the path in its best-fit plane with the
    Monte-Carlo paths and the linear +-sigmas band (normal to the path, in that plane), the deviations from the
    nominal path drawn times a round factor where the band would be thinner than VISIBLE of the path (the
    legend and title give it); right, the RMS deviation of the tip against the crank angle, linear and
    Monte-Carlo, as they are.

    Parameters
    ----------
    result : spatialkin.design.tolerance.ToleranceResult
    path : str, optional
        Write a PNG there (atomically); otherwise only return the figure.
    sigmas : float
        Half-width of the envelope in standard deviations.
    unit : str
        The design's length unit, for the labels.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .._lib.files import atomic_path
    e1, e2 = path_plane(result.tip)
    centre = result.tip.mean(axis=0)
    xy = np.column_stack([(result.tip - centre) @ e1, (result.tip - centre) @ e2])
    tangent = np.gradient(xy, axis=0)
    normal2 = np.column_stack([-tangent[:, 1], tangent[:, 0]])
    normal2 /= np.linalg.norm(normal2, axis=1, keepdims=True)
    normal3 = normal2[:, :1] * e1 + normal2[:, 1:] * e2                           # (N, 3)
    sigma_n = np.sqrt(np.einsum("ni,nij,nj->n", normal3, result.tip_covariance, normal3))
    k = exaggeration(sigmas * float(np.max(sigma_n)), float(np.max(np.ptp(xy, axis=0))))
    times = "" if k == 1 else f", deviations ×{k:g}"
    fig = _figure((11, 5.2))
    ax, ax2 = fig.subplots(1, 2)
    for tips in result.mc_tips[:MC_DRAWN]:          # (each drawn as its deviation from the nominal path, times k)
        ax.plot(*(xy + k * np.column_stack([(tips - result.tip) @ e1, (tips - result.tip) @ e2])).T,
                color="0.75", lw=0.5)
    ax.plot(*xy.T, color="C0", lw=1.5, label="nominal tip path")
    for sign in (1, -1):
        band = xy + sign * k * sigmas * sigma_n[:, None] * normal2
        ax.plot(*band.T, color="C3", lw=1.0, ls="--",
                label=f"linear ±{sigmas:g}σ envelope{times}" if sign == 1 else None)
    ax.plot([], [], color="0.75", lw=0.5,
            label=f"Monte-Carlo ({min(MC_DRAWN, len(result.mc_tips))} of {len(result.mc_tips)}){times}")
    ax.set_aspect("equal")
    ax.set_xlabel(f"along the path's main axis [{unit}]")
    ax.set_ylabel(f"across [{unit}]")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, frameon=False)    # (off the paths)
    ax.set_title("looper tip path (best-fit plane)" + (f": deviations drawn ×{k:g}" if k != 1 else ""))
    deg = np.degrees(result.crank_angles)
    ax2.plot(deg, result.tip_rms_linear, color="C3", label="linear (sensitivities)")
    ax2.plot(deg, result.tip_rms_mc, color="k", ls=":", label="Monte-Carlo")
    ax2.set_xlabel("crank angle u1 [deg]")
    ax2.set_ylabel(f"RMS tip deviation [{unit}]")
    ax2.set_xlim(0, 360)
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    ax2.set_title("how far the tip strays")
    fig.tight_layout()
    if path is not None:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=100, format="png")
    return fig


#: Columns of a sweep table that are angles (radians in the table, drawn in degrees).
ANGLES = {"swing", "u2_min", "u2_max", "v2_min", "v2_max", "u2_max_at", "u2_min_at", "min_transmission",
          "min_transmission_at", "rocker_rx", "rocker_ry", "rocker_rz"}
#: Columns that are rates at the design's omega (1 rad/s unless set): per second.
RATES = {"tip_speed_max": "/s", "ball_speed_max": "/s", "tip_acceleration_max": "/s^2",
         "ball_acceleration_max": "/s^2"}


def _with_unit(name, values, unit):
    """(values to draw, axis label with its unit) of a sweep column."""
    if name in ANGLES:
        return np.degrees(values), f"{name} [deg]"
    return values, f"{name} [{unit}{RATES.get(name, '')}]"


def sweep_figure(table, x, y, output, path=None, unit="mm"):
    """An output of a sweep over two swept parameters as a scatter coloured by the output; failed geometries
    as crosses.

    Parameters
    ----------
    table : numpy structured array or pandas.DataFrame (from spatialkin.design.sweep)
    x, y, output : str
        Column names (angles drawn in degrees).
    path : str, optional
        Write a PNG there (atomically).
    unit : str
        The design's length unit, for the labels.
    """
    from .._lib.files import atomic_path
    for name in (x, y, output):
        if name not in (table.dtype.names if hasattr(table, "dtype") and table.dtype.names else table.columns):
            raise ValueError(f"{name!r} is not a column of the table")
    cols = {k: np.asarray(table[k]) for k in (x, y, output, "ok")}
    ok = cols["ok"].astype(bool)
    fig = _figure((6, 4.6))
    ax = fig.subplots()
    (xs, x_label), (ys, y_label), (cs, c_label) = (_with_unit(k, cols[k], unit) for k in (x, y, output))
    sc = ax.scatter(xs[ok], ys[ok], c=cs[ok], s=18, cmap="viridis")
    ax.scatter(xs[~ok], ys[~ok], marker="x", color="C3", s=14, label="failed")
    fig.colorbar(sc, ax=ax, label=c_label)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    if np.any(~ok):
        ax.legend(fontsize=8)
    fig.tight_layout()
    if path is not None:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=100, format="png")
    return fig
