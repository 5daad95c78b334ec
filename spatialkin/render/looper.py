"""The looper drive as a picture: links at one crank angle, the ball centre's and the looper tip's paths,
optionally the torus and sphere the ball centre runs on and velocity arrows."""
import numpy as np

from . import geometry as geo
from .._lib.units import METRES_PER_UNIT
from .scene import ARROW_FRACTION, Scene

#: Names drawn beside the joints (shaft centre, crank pin, ball centre, rocker centre) and the looper tip.
JOINT_NAMES = ("O1 crank shaft", "A crank pin (crank 1 = O1A)", "C ball joint", "P2 rocker centre")
TIP_NAME = "T looper tip"
#: Link names drawn at the middle of each link.
LINK_NAMES = {"coupler": "coupler 2", "rocker_arm": "rocker arm 3", "looper": "looper"}
#: Colour maps of the ball centre's and the looper tip's paths in a labelled picture (told apart at a glance).
PATH_CMAPS = ("winter", "autumn")
#: Consecutive crank angles further apart than this many times their median step leave a gap in the paths.
GAP_STEPS = 1.5
#: Colours of the ball centre's and the looper tip's velocity arrows (each of its path's family: blue, red).
ARROW_COLOURS = ("#08306b", "#a50f15")
#: Lower-left corners of the two colour bars (fractions of the window) in a labelled picture.
BAR_POSITIONS = ((0.05, 0.03), (0.55, 0.03))
#: Points per link where a path's name looks for the place seen farthest from the links.
PATH_SAMPLES = 40
#: Camera of a labelled picture: looking at the middle of the mechanism from this direction (fixed axes),
#: z up, zoomed so that the mechanism fills the frame between the title and the colour bars.
LABELLED_VIEW = (1.0, -0.75, 0.45)
LABELLED_ZOOM = 0.95


def looper_scene(motion, index=0, surfaces=False, velocities=0, color_by="speed", labels=False, unit=None,
                 **scene_args):
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
        length scale for both, given in the scene's note: length per unit of speed); 0 for none.
    color_by : {'speed', 's', None}
        Colour of the two paths: speed |v| of the point, arc length, or plain.
    labels : bool
        A picture to read at a glance: joints, links and paths named (each name set off clear of the drawing,
        with a leader line), an axes marker, a scale bar (in `unit`; the view then a parallel projection) and a
        colour bar per path titled with its quantity and unit (speeds in m/s when `unit` is mm, cm, m or in),
        each path on its own colour scale; the camera closer. Give a title through scene_args.
    unit : str, optional
        The drive's length unit, for the colour bars' titles and the scale bar.
    **scene_args
        Passed to Scene (window_size, theme, camera_position, zoom, title, axes).

    Returns
    -------
    Scene
        Items 'torus', 'sphere' (if asked), 'ball_path', 'tip_path', 'looper', 'names' (with labels),
        'ball_velocity' and 'tip_velocity' (if asked).
    """
    count = int(velocities)
    if count != velocities or count < 0:
        raise ValueError(f"velocities must be a non-negative integer (arrows per path), got {velocities!r}")
    if labels:
        scene_args.setdefault("axes", True)
        scene_args.setdefault("scale_bar", True)
        scene_args.setdefault("zoom", LABELLED_ZOOM)
        scene_args.setdefault("fit", ("ball_path", "tip_path", "looper"))     # (the surfaces cut at the edges)
        if "camera_position" not in scene_args:
            links, joints = geo.looper_links(motion, index)
            pts = np.vstack([joints, *links.values(), motion.ball_center, motion.looper_tip.position])
            centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
            view = np.asarray(LABELLED_VIEW) / np.linalg.norm(LABELLED_VIEW)
            reach = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
            scene_args["camera_position"] = [tuple(centre + 3 * reach * view), tuple(centre), (0.0, 0.0, 1.0)]
    scene = Scene(unit=unit, **scene_args)
    drive = motion.drive
    if surfaces:
        scene.add_surface(drive.torus, name="torus", color="#9ecae1")
        scene.add_surface(drive.sphere, name="sphere", color="#fdae6b")
    tip = motion.looper_tip
    speeds = [np.linalg.norm(motion.ball_velocity, axis=1), np.linalg.norm(tip.velocity, axis=1)]
    lo, hi = min(map(np.min, speeds)), max(map(np.max, speeds))
    clim = (lo, hi) if color_by == "speed" and hi > lo and not labels else None   # one colour scale for both
    factor, speed_unit = (METRES_PER_UNIT[unit], "m/s") if unit in METRES_PER_UNIT else (1.0, f"{unit or 'length'}/s")
    # a crank that cannot turn fully: no path drawn across the crank ranges it cannot reach
    step = np.diff(motion.crank_angle)
    breaks = (np.nonzero(np.abs(step) > GAP_STEPS * np.median(np.abs(step)))[0] + 1) if len(step) else []
    for j, (name, title, position, speed) in enumerate((("ball", "ball centre C", motion.ball_center, speeds[0]),
                                                        ("tip", "looper tip T", tip.position, speeds[1]))):
        if labels:
            bar = f"{title}: speed [{speed_unit}]" if color_by == "speed" else f"{title}: arc length s"
            scene.add_curve(position, name=f"{name}_path", color_by=color_by, speed=speed * factor,
                            bar_title=bar, bar_position=BAR_POSITIONS[j],
                            cmap=PATH_CMAPS[j], breaks=breaks)
        else:
            scene.add_curve(position, name=f"{name}_path", color_by=color_by, speed=speed, clim=clim,
                            scalar_bar=name == "tip" or clim is None, breaks=breaks)
    scene.add_looper(motion, index, name="looper")
    if labels:
        links, joints = geo.looper_links(motion, index)
        points = np.vstack([joints, links["looper"][-1:],
                            [0.5 * (links[k][0] + links[k][-1]) if k != "looper" else links[k][1] for k in LINK_NAMES]])
        # each path named at its point seen farthest from the other path and the links
        paths = [(motion.ball_center, joints[2], "path of C"), (tip.position, links["looper"][-1], "path of T")]
        drawn = [densified(pts, PATH_SAMPLES) for pts in links.values()]
        path_points = [clearest_point(p, np.vstack([*drawn, other]), scene.camera_position, now)
                       for (p, now, _), other in zip(paths, (tip.position, motion.ball_center))]
        scene.add_labels(np.vstack([points, path_points]),
                         [*JOINT_NAMES, TIP_NAME, *LINK_NAMES.values(), *(name for _, _, name in paths)], name="names")
    if count:
        every = np.unique(np.linspace(0, len(motion.crank_angle) - 1, count).round().astype(int))
        longest = max(np.max(np.linalg.norm(motion.ball_velocity, axis=1)),
                      np.max(np.linalg.norm(tip.velocity, axis=1)))
        scale = ARROW_FRACTION * scene.extent() / longest if longest > 0 else 1.0     # one scale for both
        scene.add_arrows(motion.ball_center[every], motion.ball_velocity[every], scale=scale,
                         name="ball_velocity", color=ARROW_COLOURS[0])
        scene.add_arrows(tip.position[every], tip.velocity[every], scale=scale, name="tip_velocity",
                         color=ARROW_COLOURS[1])
        length = (f"{scale / factor:.3g} {unit} per {speed_unit}" if unit else f"length = {scale:.3g} s x speed")
        scene.note = f"velocity arrows: {length} (C dark blue, T dark red)"
    return scene


def densified(points, count):
    """count points evenly along each segment of a polyline (N, 3): (count * (N - 1), 3)."""
    t = np.linspace(0.0, 1.0, count)[:, None]
    return np.vstack([a + t * (b - a) for a, b in zip(points[:-1], points[1:])])


def clearest_point(path, others, camera_position, now):
    """The point of path (N, 3) farthest, as the camera sees it (projected on the plane facing it), from the
    nearest of others (M, 3); for a camera given by name ('iso', ...), the point of path farthest from now (3,)."""
    if isinstance(camera_position, str):
        return path[int(np.argmax(np.linalg.norm(path - now, axis=1)))]
    position, focal, up = (np.asarray(x, dtype=float) for x in camera_position)
    view = (position - focal) / np.linalg.norm(position - focal)
    right = np.cross(up, view)
    right /= np.linalg.norm(right)
    basis = np.column_stack([right, np.cross(view, right)])
    seen, clutter = path @ basis, others @ basis
    gaps = np.min(np.linalg.norm(seen[:, None, :] - clutter[None, :, :], axis=2), axis=1)
    return path[int(np.argmax(gaps))]
