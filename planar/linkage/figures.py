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


def _axes(ax, size=(6.0, 6.0)):
    if ax is not None:
        return ax.figure, ax
    return new_figure(size)


def mechanism(motion, indices=(0,), ax=None, labels=True, title=None):
    """The linkage at the positions `indices` of a LinkageMotion (the first drawn dark, the rest light).
    Returns a matplotlib Figure."""
    fig, ax = _axes(ax)
    linkage = motion.linkage
    indices = np.atleast_1d(indices)
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
    ground = np.array(list(linkage.fixed.values()))
    ax.plot(ground[:, 0], ground[:, 1], "^", ms=JOINT_SIZE + 4, color=GROUND_COLOUR)
    ax.set_aspect("equal")
    ax.set_xlabel("x (length unit)")
    ax.set_ylabel("y (length unit)")
    ax.set_title(title or "mechanism at input angle(s) " + ", ".join(
        f"{math.degrees(motion.crank_angles[i]):.4g}" for i in indices[:4]) + " deg")
    return fig


def _segment(ax, p, q, colour, width, alpha):
    ax.plot([p[0], q[0]], [p[1], q[1]], color=colour, lw=width, alpha=alpha, solid_capstyle="round")


def paths(motion, joints=("B", "C", "K"), ax=None, with_mechanism=True, title=None):
    """Trajectories of the joints over the solved input angles, over the mechanism at the first one."""
    fig, ax = _axes(ax)
    if with_mechanism:
        mechanism(motion, (0,), ax=ax, labels=True)
    for j in joints:
        p = motion.position(j)
        ax.plot(p[:, 0], p[:, 1], lw=1.4, label=f"path of {j}")
    ax.legend(loc="best", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("x (length unit)")
    ax.set_ylabel("y (length unit)")
    ax.set_title(title or "joint trajectories")
    return fig


def velocity_plans(motion, index, joints=("A", "B", "C", "K", "D"), title=None):
    """Velocity plans at position `index`: one panel per crank with the others stopped (crank k's share
    of every joint's velocity, from the pole p) and one of the full motion, where each share is drawn
    tip to tail to show V = sum of the shares. Returns a matplotlib Figure."""
    cranks = len(motion.linkage.cranks)
    fig, axes = new_figure((4.0 * (cranks + 1), 4.2), columns=cranks + 1)
    panels = [(k + 1, f"crank {k + 1} alone (others stopped)") for k in range(cranks)]
    panels.append((None, "full motion = sum of the shares"))
    for ax, (crank, name) in zip(axes, panels):
        ax.plot(0, 0, "ko", ms=3)
        ax.annotate("p", (0, 0), xytext=(-10, -10), textcoords="offset points")
        for j in joints:
            v = motion.velocity(j, crank)[index]
            ax.annotate("", v, (0, 0), arrowprops=dict(arrowstyle="->", lw=1.3))
            ax.update_datalim([(0.0, 0.0), v])
            ax.annotate(j.lower(), v, xytext=(3, 3), textcoords="offset points", fontsize=9)
            if crank is None and cranks > 1:
                tail = np.zeros(2)
                for k in range(cranks):
                    share = motion.velocity(j, k + 1)[index]
                    ax.plot(*np.column_stack([tail, tail + share]), ls="--", lw=0.8, color=f"C{k}")
                    tail = tail + share
        ax.autoscale_view()
        ax.set_aspect("equal")
        ax.margins(0.15)
        ax.set_title(name, fontsize=9)
    fig.suptitle(title or f"velocity plans at input angle {math.degrees(motion.crank_angles[index]):.4g} "
                 f"deg (omega = {motion.omega:g})")
    return fig
