"""Figures of a mechanism's loads over its cycle (matplotlib, Agg): the crank torque with its peak and mean power,
and polar diagrams of the joints' loads (the load's direction and size in each bearing's plane)."""
import numpy as np

from .looper import _pyplot


def torque(angles_deg, torque_nm, omega, path, title="crank torque at machine speed"):
    """The crank torque (N m) over the crank angle (deg), its peak marked, and the mean driving power (W) at the
    crank rate omega (rad/s), into a PNG at path."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(8.0, 4.2), dpi=110)
    ax.plot(angles_deg, torque_nm, color="#1f77b4", lw=1.4, label="crank torque")
    k = int(np.argmax(np.abs(torque_nm)))
    ax.plot(angles_deg[k], torque_nm[k], "o", color="#d62728",
            label=f"peak {torque_nm[k]:.4g} N m at {angles_deg[k]:.1f} deg")
    ax.axhline(0.0, color="0.6", lw=0.8)
    power = torque_nm * omega
    ax.set_xlabel("crank angle u1 [deg]")
    ax.set_ylabel("torque on the crank [N m]")
    ax.set_xlim(float(np.min(angles_deg)), float(np.max(angles_deg)))
    if np.ptp(angles_deg) >= 180.0:
        ax.set_xticks(np.arange(45.0 * np.ceil(np.min(angles_deg) / 45.0), np.max(angles_deg) + 1e-9, 45.0))
    ax.set_title(f"{title}: mean power {np.mean(power):.3g} W, peak power {np.max(np.abs(power)):.3g} W")
    ax.legend(loc="best", fontsize=9)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, format="png")
    plt.close(fig)


def bearing_loads(loads_by_joint, path, planes, title="joint loads at machine speed (N), in each bearing's plane"):
    """Polar diagrams: for each joint, the locus over the cycle of its load's two components normal to its axis
    (loads_by_joint: name -> (N, 3) in the child link's axes, N; planes: name -> (i, j) the components' indices),
    angle measured from component i towards j, radius in N, the peak of the third (axial) component named; into a
    PNG at path."""
    from matplotlib.ticker import FuncFormatter, MaxNLocator
    plt = _pyplot()
    names = list(loads_by_joint)
    cols = min(3, len(names))
    rows = (len(names) + cols - 1) // cols
    fig = plt.figure(figsize=(4.0 * cols, 4.1 * rows), dpi=100)
    axes_names = "xyz"
    for k, name in enumerate(names):
        ax = fig.add_subplot(rows, cols, k + 1, projection="polar")
        i, j = planes[name]
        f = np.asarray(loads_by_joint[name])
        theta, radius = np.arctan2(f[:, j], f[:, i]), np.hypot(f[:, i], f[:, j])
        ax.plot(np.append(theta, theta[:1]), np.append(radius, radius[:1]), color="#1f77b4", lw=1.2)
        peak = int(np.argmax(radius))
        axial = float(np.max(np.abs(f[:, 3 - i - j])))
        ax.plot(theta[peak], radius[peak], "o", color="#d62728")
        ax.set_title(f"{name.replace('_', ' ')}: in-plane peak {radius[peak]:.3g} N, along {axes_names[3 - i - j]} "
                     f"{axial:.3g} N\n(angle from link {axes_names[i]} towards {axes_names[j]})", fontsize=9)
        ax.tick_params(labelsize=7)
        ax.yaxis.set_major_locator(MaxNLocator(4))          # (four rings, named in N, beside the curve)
        ax.yaxis.set_major_formatter(FuncFormatter(lambda r, _: f"{r:.3g} N"))
        ax.set_rlabel_position(112.5)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(path, format="png")
    plt.close(fig)
