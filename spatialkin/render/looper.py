"""The looper drive as a picture: links at one crank angle, the ball centre's and the looper tip's paths,
optionally the torus and sphere the ball centre runs on and velocity arrows."""
import numpy as np

from .scene import ARROW_FRACTION, Scene



def looper_scene(motion, index=0, surfaces=False, velocities=0, color_by="speed", **scene_args):
    """A Scene of the looper drive.

    Parameters
    ----------
    motion : LooperMotion
        From ``LooperDrive.solve(crank_angles)``; its crank angles should cover the turn for whole paths.
    index : int
        The crank angle (index into ``motion.crank_angle``) at which the links are drawn.
    surfaces : bool
        Also the torus and the sphere (translucent) whose intersection is the ball centre's path.
    velocities : int
        Velocity arrows drawn on each of the two paths (spread evenly over the motion's crank angles, one
        length scale for both); 0 for none.
    color_by : {'speed', 's', None}
        Colour of the two paths: speed |v| of the point, arc length, or plain.
    **scene_args
        Passed to Scene (window_size, theme, camera_position, zoom).

    Returns
    -------
    Scene
        Items 'torus', 'sphere' (if asked), 'ball_path', 'tip_path', 'looper', 'ball_velocity' and
        'tip_velocity' (if asked).
    """
    count = int(velocities)
    if count != velocities or count < 0:
        raise ValueError(f"velocities must be a non-negative integer (arrows per path), got {velocities!r}")
    scene = Scene(**scene_args)
    drive = motion.drive
    if surfaces:
        scene.add_surface(drive.torus, name="torus", color="#9ecae1")
        scene.add_surface(drive.sphere, name="sphere", color="#fdae6b")
    tip = motion.looper_tip
    speeds = [np.linalg.norm(motion.ball_velocity, axis=1), np.linalg.norm(tip.velocity, axis=1)]
    lo, hi = min(map(np.min, speeds)), max(map(np.max, speeds))
    clim = (lo, hi) if color_by == "speed" and hi > lo else None        # one colour scale for both paths
    for name, position, speed in (("ball", motion.ball_center, speeds[0]), ("tip", tip.position, speeds[1])):
        scene.add_curve(position, name=f"{name}_path", color_by=color_by, speed=speed, clim=clim,
                        scalar_bar=name == "tip" or clim is None)
    scene.add_looper(motion, index, name="looper")
    if count:
        every = np.unique(np.linspace(0, len(motion.crank_angle) - 1, count).round().astype(int))
        longest = max(np.max(np.linalg.norm(motion.ball_velocity, axis=1)),
                      np.max(np.linalg.norm(tip.velocity, axis=1)))
        scale = ARROW_FRACTION * scene.extent() / longest if longest > 0 else 1.0     # one scale for both
        scene.add_arrows(motion.ball_center[every], motion.ball_velocity[every], scale=scale,
                         name="ball_velocity", color="#d62728")
        scene.add_arrows(tip.position[every], tip.velocity[every], scale=scale, name="tip_velocity",
                         color="#2ca02c")
    return scene
