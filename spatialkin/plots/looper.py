"""The looper job's figures (matplotlib, Agg): cyclogram, transmission angle, speed and acceleration at
machine speed. Each draws exactly the solved data it is given; gaps in the crank angles (a crank that cannot
turn fully) stay gaps."""
import numpy as np

from .._lib.units import METRES_PER_UNIT, STANDARD_GRAVITY

#: Colours: rocker/ball centre, looper tip, marks.
DEAD_COLOR = "#d62728"
BRANCH_COLOR = "#9467bd"


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def with_gaps(angles_deg, values, step_deg):
    """angles and values with a NaN row inserted wherever the angles jump by more than 1.5 steps, so that a
    line is not drawn across a crank range the drive cannot reach."""
    angles_deg = np.asarray(angles_deg, dtype=float)
    values = np.asarray(values, dtype=float)
    cut = np.nonzero(np.diff(angles_deg) > 1.5 * step_deg)[0] + 1
    return (np.insert(angles_deg, cut, np.nan),
            np.insert(values, cut, np.nan, axis=0))


def angle_span(values_deg):
    """(least, greatest) of angles (deg) on the circle: the shortest arc holding them all, least in
    (-180, 180]; the plain min and max when they span less than a turn without wrapping."""
    lo, hi = float(np.min(values_deg)), float(np.max(values_deg))
    if hi - lo < 180.0:
        return lo, hi
    a = np.sort(np.mod(values_deg, 360.0))
    gaps = np.diff(np.concatenate([a, [a[0] + 360.0]]))
    k = int(np.argmax(gaps))
    least = a[(k + 1) % len(a)]
    least = least - 360.0 if least > 180.0 else least
    return float(least), float(least + 360.0 - gaps[k])


def on_span(values_deg, span):
    """Angles (deg) shifted by whole turns onto the arc span = (least, greatest) from angle_span."""
    return span[0] + np.mod(np.asarray(values_deg, dtype=float) - span[0], 360.0)


def _marks(ax, marks, first):
    """Vertical lines at the dead positions and branch points (crank angles in rad); legend labels once."""
    for j, (a, b) in enumerate(marks.get("blocked", [])):
        ax.axvspan(np.degrees(a), np.degrees(b), color="0.85", zorder=0,
                   label="cannot assemble" if first and j == 0 else None)
    for key, color, style, label in (("dead", DEAD_COLOR, "--", "dead position"),
                                     ("branch", BRANCH_COLOR, ":", "branch point")):
        for j, x in enumerate(marks.get(key, [])):
            ax.axvline(np.degrees(x), color=color, ls=style, lw=1.2,
                       label=label if first and j == 0 else None)


def _crank_axis(ax):
    ax.set_xlabel("crank angle u1 [deg]")
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))


def cyclogram(motion, path, unit="mm", marks=None, step=None):
    """Rocker angles u2, v2 and the looper tip's coordinates against the crank angle, dead positions and
    branch points marked (vertical lines), the rocker's extreme positions marked (dots)."""
    plt = _pyplot()
    marks = marks or {}
    step_deg = np.degrees(step) if step else np.inf
    deg = np.degrees(motion.crank_angle)
    u2, v2 = (on_span(a, angle_span(a)) for a in np.degrees(motion.rocker_angles.T))
    tip = motion.looper_tip.position
    fig, axes = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    for ax, values, label, color in ((axes[0], u2, "u2 (rocker shaft) [deg]", "C0"),
                                     (axes[1], v2, "v2 (rocker arm) [deg]", "C1")):
        x, y = with_gaps(deg, values, step_deg)
        ax.plot(x, y, color=color, lw=1.6)
        for k, name in ((int(np.argmin(values)), "least"), (int(np.argmax(values)), "greatest")):
            ax.plot(deg[k], values[k], "o", color="k", ms=4, clip_on=False)
            left = deg[k] > 0.75 * np.nanmax(deg)         # (set off to the side with room, on a white box)
            ax.annotate(f"{name} {values[k]:.2f} deg\nat {deg[k]:.1f} deg", (deg[k], values[k]), fontsize=8,
                        xytext=(-8 if left else 8, -24 if name == "greatest" else 8), textcoords="offset points",
                        ha="right" if left else "left", bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="0.8",
                                                                  alpha=0.9), clip_on=False)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    x, y = with_gaps(deg, tip, step_deg)
    for j, c in enumerate("xyz"):
        axes[2].plot(x, y[:, j], lw=1.6, label=f"tip {c}")
    axes[2].set_ylabel(f"looper tip [{unit}]")
    axes[2].grid(True, alpha=0.3)
    for j, ax in enumerate(axes):
        _marks(ax, marks, first=j == 0)
    axes[2].legend(loc="best", fontsize=8, ncol=3)
    if marks.get("dead") or marks.get("branch"):
        axes[0].legend(loc="best", fontsize=8)
    _crank_axis(axes[2])
    note = "" if marks.get("dead") or marks.get("branch") else " (no dead position or branch point: full turn)"
    fig.suptitle(f"Looper drive cyclogram, branch {motion.branch}{note}", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100, format="png")
    plt.close(fig)


def transmission(analysis, path, step=None):
    """The transmission angle at C over the crank angles of the analysis, its minimum marked."""
    plt = _pyplot()
    step_deg = np.degrees(step) if step else np.inf
    deg = np.degrees(analysis.crank_angles)
    mu = np.degrees(analysis.transmission_angle)
    fig, ax = plt.subplots(figsize=(8, 4.8))
    x, y = with_gaps(deg, mu, max(step_deg, np.ptp(deg) / max(len(deg) - 1, 1)))
    ax.plot(x, y, lw=1.6, color="C0", label="transmission angle at C")
    m, at = np.degrees(analysis.min_transmission)
    ax.plot(at, m, "o", color=DEAD_COLOR, ms=6, label=f"least {m:.2f} deg at crank {at:.1f} deg")
    ax.axhline(40.0, color="0.5", ls="--", lw=1, label="40 deg (a usual lower limit)")
    _marks(ax, {"dead": analysis.dead_positions, "branch": analysis.branch_points,
                "blocked": analysis.blocked_ranges}, first=True)
    ax.set_ylim(0, 92)
    ax.set_ylabel("transmission angle [deg]")
    ax.grid(True, alpha=0.3)
    _crank_axis(ax)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, fontsize=8, frameon=False)
    ax.set_title("Transmission angle: 90 deg ideal, 0 deg the coupler cannot drive C", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100, format="png")
    plt.close(fig)


def speed(motion, path, unit="mm", speed_rpm=None, step=None):
    """|v| and |a| of the ball centre and the looper tip against the crank angle at the motion's crank speed,
    in m/s and m/s^2 (g on the right-hand axis)."""
    plt = _pyplot()
    si = METRES_PER_UNIT[unit]
    step_deg = np.degrees(step) if step else np.inf
    deg = np.degrees(motion.crank_angle)
    tip = motion.looper_tip
    gaps = bool(np.any(np.diff(deg) > 1.5 * step_deg))
    fig, axes = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for ax, (label, c, t) in zip(axes, (("speed |v| [m/s]", motion.ball_velocity, tip.velocity),
                                        ("acceleration |a| [m/s²]", motion.ball_acceleration,
                                         tip.acceleration))):
        for values, name in ((c, "ball centre C"), (t, "looper tip")):
            x, y = with_gaps(deg, np.linalg.norm(values, axis=1) * si, step_deg)
            ax.plot(x, y, lw=1.6, label=name)
            k = int(np.nanargmax(y))
            ax.plot(x[k], y[k], "o", color="k", ms=4)
            ax.annotate(f"{y[k]:.4g}", (x[k], y[k]), xytext=(4, 4), textcoords="offset points", fontsize=8)
        ax.set_ylabel(label)
        if gaps:       # speeds grow without bound towards the dead positions: a log scale keeps the rest
            ax.set_yscale("log")
        else:
            ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    g_axis = axes[1].secondary_yaxis("right", functions=(lambda a: a / STANDARD_GRAVITY,
                                                         lambda g: g * STANDARD_GRAVITY))
    g_axis.set_ylabel("acceleration [g]")
    _crank_axis(axes[1])
    rpm = f" at {speed_rpm:g} rpm ({motion.omega:.4g} rad/s)" if speed_rpm else f" at {motion.omega:.4g} rad/s"
    fig.suptitle("Looper drive: speed and acceleration" + rpm, fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100, format="png")
    plt.close(fig)
