"""Pictures of a planar linkage's motion (matplotlib; kept apart from the kinematics).

* mechanism(motion, indices): the linkage drawn at chosen positions
* paths(motion, joints): trajectories of joints over the solved angles
* velocity_plans(motion, index): the velocity plans of Koshel and Koshel - each crank alone (the other stopped) and the
  full motion - from the pole p, drawn from the analytic velocities

References
----------
S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian):
velocity plans by stopping one crank, superposition.
"""
import math

import numpy as np

from ..plotting import new_figure

#: Grey levels and widths of the drawing.
LINK_COLOUR, GROUND_COLOUR, TERNARY_FILL = "0.25", "0.45", "0.85"
JOINT_SIZE = 4.0
#: The input angles a mechanism picture's title lists (the rest counted).
TITLE_ANGLES = 8


def _axes(ax, size=(6.0, 6.0)):
    if ax is not None:
        return ax.figure, ax
    return new_figure(size)


def mechanism(motion, indices=(0,), ax=None, labels=True, title=None, unit=None):
    """The linkage at the positions `indices` of a LinkageMotion (the first drawn dark with its joints named, the
    rest light, each with its input angle beside its first crank pin); the title lists the angles (the first
    TITLE_ANGLES); the axes in `unit`, the linkage's length unit (e.g. "mm"; None: "length unit"). Returns a
    matplotlib Figure."""
    fig, ax = _axes(ax)
    linkage = motion.linkage
    indices = np.atleast_1d(indices)
    angles = [math.degrees(motion.crank_angles[i]) for i in indices]
    for rank, i in enumerate(indices):
        alpha = 1.0 if rank == 0 else 0.35
        p = {j: motion.position(j)[i] for j in linkage.joints}
        for c in linkage.cranks:
            _segment(ax, p[c.pivot], p[c.pin], LINK_COLOUR, 2.2, alpha)
        for lk in linkage.links:
            pts = np.array([p[j] for j in lk.joints])
            if len(pts) > 2:
                ax.fill(pts[:, 0], pts[:, 1], color=TERNARY_FILL, alpha=alpha, ec=LINK_COLOUR, lw=1.6)
            else:
                _segment(ax, pts[0], pts[1], LINK_COLOUR, 1.6, alpha)
        moving = np.array([p[j] for j in linkage.moving])
        ax.plot(moving[:, 0], moving[:, 1], "o", ms=JOINT_SIZE, mfc="white", mec="k", alpha=alpha)
        if labels and rank == 0:
            for j in linkage.joints:
                ax.annotate(j, p[j], xytext=(4, 4), textcoords="offset points", fontsize=8)
        elif len(indices) > 1:                   # a light position: its input angle beside its first crank pin
            ax.annotate(f"{angles[rank]:.4g}°", p[linkage.cranks[0].pin], xytext=(5, -9), textcoords="offset points",
                        fontsize=7, color=LINK_COLOUR)
    ground = np.array(list(linkage.fixed.values()))
    ax.plot(ground[:, 0], ground[:, 1], "^", ms=JOINT_SIZE + 4, color=GROUND_COLOUR)
    ax.set_aspect("equal")
    _label_axes(ax, ("x", "y"), unit)
    if title is None:
        shown = ", ".join(f"{a:.4g}" for a in angles[:TITLE_ANGLES])
        more = f" and {len(angles) - TITLE_ANGLES} more" if len(angles) > TITLE_ANGLES else ""
        title = (f"mechanism at input angle {shown} deg" if len(angles) == 1 else
                 f"mechanism at input angles {shown}{more} deg (the first dark)")
    ax.set_title(title)
    return fig


def _label_axes(ax, names, unit, per_second=False):
    """Axis labels "name [unit]" (x first, then y; None leaves one as it is), "name (length unit)" without a unit;
    per_second: a velocity's, "[unit/s]" or "(length unit / s)"."""
    shown = (f"[{unit}/s]" if per_second else f"[{unit}]") if unit else (
        "(length unit / s)" if per_second else "(length unit)")
    for name, setter in zip(names, (ax.set_xlabel, ax.set_ylabel)):
        if name is not None:
            setter(f"{name} {shown}")


def _segment(ax, p, q, colour, width, alpha):
    ax.plot([p[0], q[0]], [p[1], q[1]], color=colour, lw=width, alpha=alpha, solid_capstyle="round")


def paths(motion, joints=("B", "C", "K"), ax=None, with_mechanism=True, title=None, unit=None):
    """Trajectories of the joints over the solved input angles, over the mechanism at the first one; the axes in
    `unit` (as mechanism's)."""
    fig, ax = _axes(ax)
    if with_mechanism:
        mechanism(motion, (0,), ax=ax, labels=True)
    for j in joints:
        p = motion.position(j)
        ax.plot(p[:, 0], p[:, 1], lw=1.4, label=f"path of {j}")
    ax.legend(loc="best", fontsize=8)
    ax.set_aspect("equal")
    _label_axes(ax, ("x", "y"), unit)
    ax.set_title(title or "joint trajectories")
    return fig


def velocity_plans(motion, index, joints=("A", "B", "C", "K", "D"), title=None, unit=None):
    """Velocity plans at position `index`: one panel per crank with the others stopped (crank k's share
    of every joint's velocity, from the pole p) and one of the full motion, where each share is drawn
    tip to tail (dashed, a legend naming the cranks) to show V = sum of the shares; every panel on one scale, in
    `unit` (the linkage's length unit; None: "length unit") per second. Returns a matplotlib Figure."""
    cranks = len(motion.linkage.cranks)
    fig, axes = new_figure((4.2 * (cranks + 1), 4.6), columns=cranks + 1)
    panels = [(k + 1, f"crank {k + 1} alone (others stopped)") for k in range(cranks)]
    panels.append((None, "full motion = sum of the shares"))
    ends = [np.zeros(2)]
    for ax, (crank, name) in zip(axes, panels):
        ax.plot(0, 0, "ko", ms=3)
        ax.annotate("p", (0, 0), xytext=(-10, -10), textcoords="offset points")
        for j in joints:
            v = motion.velocity(j, crank)[index]
            ends.append(v)
            ax.annotate("", v, (0, 0), arrowprops=dict(arrowstyle="->", lw=1.3))
            ax.annotate(j.lower(), v, xytext=(3, 3), textcoords="offset points", fontsize=9)
            if crank is None and cranks > 1:
                tail = np.zeros(2)
                for k in range(cranks):
                    share = motion.velocity(j, k + 1)[index]
                    ax.plot(*np.column_stack([tail, tail + share]), ls="--", lw=0.8, color=f"C{k}",
                            label=f"crank {k + 1}'s share" if j == joints[0] else None)
                    tail = tail + share
                    ends.append(tail)
        ax.set_title(name, fontsize=9)
        _label_axes(ax, ("v_x",), unit, per_second=True)
        ax.grid(True, alpha=0.3)
        if crank is None and cranks > 1:
            ax.legend(fontsize=7, loc="best")
    _label_axes(axes[0], (None, "v_y"), unit, per_second=True)
    ends = np.array(ends)                    # one scale for every panel: a joint's arrows compare across them
    lo, hi = ends.min(axis=0), ends.max(axis=0)
    pad = 0.12 * float(np.max(hi - lo)) or 1.0
    for ax in axes:
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal", adjustable="box")
    fig.suptitle(title or f"velocity plans at input angle {math.degrees(motion.crank_angles[index]):.4g} "
                 f"deg (omega = {motion.omega:g} rad/s)")
    return fig
