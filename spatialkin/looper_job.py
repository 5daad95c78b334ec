"""The main job: the looper drive over a full turn -> CSV of the motion, a plot, a printed summary."""
import os
import time
import tomllib

import numpy as np

from .frame import Frame, rotation_to_z
from .io import atomic_path
from .mechanisms import LooperDrive

#: Keys a looper TOML file may hold, with the reference geometry's values as defaults.
DEFAULTS = {
    "crank_radius": 8.0, "coupler_length": 50.0, "rocker_length": 30.0, "omega": 1.0, "branch": 0,
    "step_deg": 0.1, "looper_link": "rocker_arm", "looper_tip": [40.0, 0.0, 12.0],
    "crank_frame": {"origin": [0.0, 0.0, 0.0]},
    "rocker_frame": {"origin": [6.0, 0.0, 75.0], "rotation": [[1, 0, 0], [0, 0, 1], [0, -1, 0]]},
}
#: The 3-D picture: crank angle (deg) at which the links are drawn, and its size in pixels.
PICTURE_CRANK_ANGLE_DEG = 60.0
PICTURE_SIZE = (800, 600)
COLUMNS = ["crank_angle", "x", "y", "z", "vx", "vy", "vz", "ax", "ay", "az",
           "u2", "v2", "u2_dot", "v2_dot", "u2_ddot", "v2_ddot",
           "tip_x", "tip_y", "tip_z", "tip_vx", "tip_vy", "tip_vz", "tip_ax", "tip_ay", "tip_az"]


def frame_from(name, table):
    """A Frame from a TOML table with 'origin' and either 'rotation' (3x3, columns = local axes) or
    'z_axis'."""
    if not isinstance(table, dict):
        raise ValueError(f"{name} must be a table with origin and rotation or z_axis")
    unknown = set(table) - {"origin", "rotation", "z_axis"}
    if unknown:
        raise ValueError(f"{name}: unknown keys {sorted(unknown)}")
    if "rotation" in table and "z_axis" in table:
        raise ValueError(f"{name}: give rotation or z_axis, not both")
    rotation = table.get("rotation")
    if "z_axis" in table:
        rotation = rotation_to_z(table["z_axis"])
    try:
        return Frame(table.get("origin", (0.0, 0.0, 0.0)), rotation)
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None


def load_config(path=None):
    """The job's settings: the defaults, overridden by a TOML file."""
    config = {k: (dict(v) if isinstance(v, dict) else v) for k, v in DEFAULTS.items()}
    if path is not None:
        with open(path, "rb") as f:
            user = tomllib.load(f)
        unknown = set(user) - set(DEFAULTS)
        if unknown:
            raise ValueError(f"{path}: unknown keys {sorted(unknown)}; allowed: {sorted(DEFAULTS)}")
        config.update(user)
    step = float(config["step_deg"])
    if not (0 < step <= 1.0):
        raise ValueError(f"step_deg must lie in (0, 1] so that a turn has at least 361 rows, got {step}")
    return config


def build(config):
    drive = LooperDrive(config["crank_radius"], config["coupler_length"], config["rocker_length"],
                        frame_from("crank_frame", config["crank_frame"]),
                        frame_from("rocker_frame", config["rocker_frame"]),
                        looper_tip=config["looper_tip"], looper_link=config["looper_link"])
    return drive


def run(out_dir, config_path=None, echo=print):
    """Run the job; returns the LooperMotion. Every file is written whole or not at all."""
    t0 = time.perf_counter()
    config = load_config(config_path)
    drive = build(config)
    n = int(round(360.0 / float(config["step_deg"]))) + 1
    angles = np.linspace(0.0, 2 * np.pi, n)
    t_solve = time.perf_counter()
    motion = drive.solve(angles, omega=float(config["omega"]), branch=int(config["branch"]))
    t_solve = time.perf_counter() - t_solve
    tip = motion.looper_tip
    table = np.column_stack([angles, motion.ball_center, motion.ball_velocity, motion.ball_acceleration,
                             motion.rocker_angles, motion.rocker_rates, motion.rocker_accelerations,
                             tip.position, tip.velocity, tip.acceleration])
    os.makedirs(out_dir, exist_ok=True)
    csv_path = os.path.join(out_dir, "looper_motion.csv")
    with atomic_path(csv_path) as tmp:
        np.savetxt(tmp, table, delimiter=",", header=",".join(COLUMNS), comments="", fmt="%.15g")
    png_path = os.path.join(out_dir, "looper_speed.png")
    with atomic_path(png_path) as tmp:
        plot_speed(motion, tmp)
    t_picture = time.perf_counter()
    picture_path = os.path.join(out_dir, "looper_3d.png")
    picture_3d(motion, picture_path)
    t_picture = time.perf_counter() - t_picture
    # measured errors: exact distances of C to both surfaces; C by the coupler chain against the rocker chain
    on_torus = drive.torus.distance(motion.ball_center).max()
    on_sphere = drive.sphere.distance(motion.ball_center).max()
    chains = np.abs(motion.point("coupler", (drive.coupler_length, 0, 0)).position
                    - motion.point("rocker_arm", (drive.rocker_length, 0, 0)).position).max()
    u2, v2 = np.degrees(motion.rocker_angles.T)
    analysis = drive.analyse(branch=int(config["branch"]))
    mu, at = np.degrees(analysis.min_transmission)
    echo(f"looper drive: crank {drive.crank_radius:g}, coupler {drive.coupler_length:g}, rocker "
         f"{drive.rocker_length:g}; branch {motion.branch}; omega {motion.omega:g} rad/s; {n} crank angles")
    echo(f"ball centre: |v| max {np.max(np.linalg.norm(motion.ball_velocity, axis=1)):.6g}, "
         f"|a| max {np.max(np.linalg.norm(motion.ball_acceleration, axis=1)):.6g}")
    echo(f"rocker swing: u2 {u2.min():.3f}..{u2.max():.3f} deg, v2 {v2.min():.3f}..{v2.max():.3f} deg")
    if analysis.turns_fully:
        echo("the crank turns fully (no dead position)")
    else:
        echo("the crank cannot turn fully: dead positions at "
             + ", ".join(f"{np.degrees(x):.4f}" for x in analysis.dead_positions) + " deg")
    if analysis.branch_points:
        echo("assembly branches meet at crank angles "
             + ", ".join(f"{np.degrees(x):.4f}" for x in analysis.branch_points) + " deg")
    echo(f"smallest transmission angle {mu:.2f} deg at crank angle {at:.1f} deg")
    echo(f"measured error: C to torus {on_torus:.2e}, to sphere {on_sphere:.2e}, coupler vs rocker chain "
         f"{chains:.2e} (length units)")
    echo(f"time: solve {1e3 * t_solve:.1f} ms, 3-D picture {t_picture:.2f} s, whole job "
         f"{time.perf_counter() - t0:.2f} s")
    echo(f"wrote {csv_path}, {png_path} and {picture_path}")
    return motion


def picture_3d(motion, path, crank_angle_deg=PICTURE_CRANK_ANGLE_DEG):
    """The mechanism in 3-D to a PNG (off-screen): links and joints at the crank angle nearest to
    crank_angle_deg, the ball centre's and the looper tip's paths coloured by speed."""
    from .render import looper_scene
    wrapped = np.mod(motion.crank_angle - np.radians(crank_angle_deg) + np.pi, 2 * np.pi) - np.pi
    index = int(np.argmin(np.abs(wrapped)))
    looper_scene(motion, index, window_size=PICTURE_SIZE).screenshot(path)


def plot_speed(motion, path):
    """|v| and |a| of the ball centre and the looper tip against the crank angle, to a PNG."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees(motion.crank_angle)
    tip = motion.looper_tip
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for ax, (label, c, t) in zip(axes, (("|v|", motion.ball_velocity, tip.velocity),
                                        ("|a|", motion.ball_acceleration, tip.acceleration))):
        ax.plot(deg, np.linalg.norm(c, axis=1), label="ball centre C")
        ax.plot(deg, np.linalg.norm(t, axis=1), label="looper tip")
        ax.set_ylabel(f"{label} (omega = {motion.omega:g} rad/s)")
        ax.grid(True, alpha=0.3)
        ax.legend()
    axes[-1].set_xlabel("crank angle u1 [deg]")
    axes[-1].set_xlim(0, 360)
    fig.suptitle("Looper drive: speed and acceleration over one crank turn")
    fig.tight_layout()
    fig.savefig(path, dpi=100, format="png")
    plt.close(fig)


