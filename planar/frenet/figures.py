"""The pictures of Pylypaka et al. as functions returning matplotlib figures (kept apart from the kinematics).

* positions(link, ...): a family of link positions with point trajectories (the paper's Fig. 3, 8, 10, 12, 15, 16)
* vectors(link, ...): velocity or acceleration vectors along trajectories, a scale factor m and a density
  set by the step ds (Fig. 4, 6, 9, 11, 13b)
* magnitudes(link, ...): |v| or |a| against the crank angle (Fig. 5, 7, 14)

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven member
using Frenet trihedron", 2017.
"""
import numpy as np

from spatialkin._lib.validation import check_choice, check_positive

from ..plotting import new_figure

#: What vectors() and magnitudes() draw.
KINDS = ("velocity", "acceleration")
#: Default density of vectors(): this many vectors per crank turn along each trajectory.
VECTORS_PER_TURN = 36


def _turn(link, samples):
    return np.linspace(0.0, 2 * np.pi / link.k, samples)


def positions(link, rhos, link_from=-4.0, link_to=None, count=12, samples=721, title=None):
    """Link positions at `count` crank angles over a turn (segments from rho = link_from to link_to) and
    the trajectories of the points at the signed distances rhos. Returns a matplotlib Figure."""
    fig, ax = new_figure()
    rhos = np.atleast_1d(np.asarray(rhos, dtype=float))
    link_to = float(rhos.max()) if link_to is None else link_to
    s_all = _turn(link, samples)
    r = 1.0 / link.k
    circle = np.linspace(0, 2 * np.pi, 361)
    ax.plot(r * np.cos(circle), r * np.sin(circle), color="0.6", lw=0.8)
    for s in _turn(link, count + 1)[:-1]:
        ends = link.position(np.array([s, s]), np.array([link_from, link_to]))
        ax.plot(ends[:, 0], ends[:, 1], color="0.4", lw=0.8)
        pin = link.position(s, 0.0)
        ax.plot([0, pin[0]], [0, pin[1]], color="0.75", lw=0.8)
    for rho in rhos:
        path = link.position(s_all, rho)
        ax.plot(path[:, 0], path[:, 1], lw=1.6, label=f"rho = {rho:g}")
    ax.set_aspect("equal")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("x (length unit)")
    ax.set_ylabel("y (length unit)")
    ax.set_title(title or "link positions and point trajectories")
    return fig


def vectors(link, rhos, kind="velocity", scale=0.5, ds=None, samples=721, title=None):
    """Velocity or acceleration vectors (times `scale`, in s or s²: an arrow is a length) drawn from trajectory
    points spaced ds apart (default: 36 per turn) along the trajectories of the points rhos, each point's path
    and arrows in one colour, named in the legend."""
    check_choice("kind", kind, KINDS)
    check_positive("scale", scale)
    turn = 2 * np.pi / link.k
    ds = turn / VECTORS_PER_TURN if ds is None else check_positive("ds", ds)
    fig, ax = new_figure()
    for k, rho in enumerate(np.atleast_1d(rhos)):
        path = link.position(_turn(link, samples), rho)
        ax.plot(path[:, 0], path[:, 1], lw=1.2, color=f"C{k}", label=f"rho = {rho:g}")
        s = np.arange(0.0, turn, ds)
        t = link.trajectory(s, rho)
        vec = scale * (t.velocity if kind == "velocity" else t.acceleration)
        ax.quiver(t.position[:, 0], t.position[:, 1], vec[:, 0], vec[:, 1], angles="xy", scale_units="xy",
                  scale=1.0, width=0.004, color=f"C{k}")
        ax.update_datalim(t.position + vec)          # (quiver leaves its arrows' tips out of the limits)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel("x (length unit)")
    ax.set_ylabel("y (length unit)")
    ax.legend(fontsize=8, loc="best")
    unit = "s" if kind == "velocity" else "s²"
    letter = "v" if kind == "velocity" else "a"
    ax.set_title(title or f"{kind} vectors, drawn as m {letter} with m = {scale:g} {unit}")
    return fig


def magnitudes(link, rhos, kind="velocity", samples=721, title=None):
    """|v| or |a| of the points rhos against the crank angle (degrees) over one turn."""
    check_choice("kind", kind, KINDS)
    fig, ax = new_figure((7.0, 4.0))
    s = _turn(link, samples)
    deg = np.degrees(link.crank_angle(s))
    for rho in np.atleast_1d(rhos):
        t = link.trajectory(s, rho)
        ax.plot(deg, t.speed if kind == "velocity" else t.acceleration_magnitude, label=f"rho = {rho:g}")
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel("|v| (length unit / s)" if kind == "velocity" else "|a| (length unit / s²)")
    ax.set_xlim(0, 360)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or f"{kind} magnitude against crank angle")
    return fig
