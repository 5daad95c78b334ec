"""The main job: the looper drive over a crank turn at machine speed -> CSV of the motion (units in the
header), a JSON record of the run, pictures, a printed summary.

Every key a looper TOML file may hold is listed in KEYS with its unit and default (``spatialkin looper
--help`` prints the same table). A crank that cannot turn fully is analysed over the crank ranges it can
reach (it rocks between dead positions there); a geometry that never assembles is refused.
"""
import json
import math
import os
import platform
import textwrap
import time
import tomllib

import numpy as np

from . import looper_forces as forces
from ..plots import looper as figs
from ..mechanisms.looper import reference as ref
from ..geometry.frame import Frame, rotation_about, rotation_to_z
from .._lib.files import atomic_path, check_out_dir
from ..mechanisms import LooperDrive
from ..mechanisms.looper.analysis import CLEARANCE
from .._lib.units import METRES_PER_UNIT, STANDARD_GRAVITY
from .._lib.validation import check_choice, check_positive, check_real, orthonormalised

#: Crank speed of the built-in drive: industrial blind-stitch machines sew about 1500-3000 stitches per
#: minute with one looper-crank turn per stitch; 2000 rpm is a usual working speed.
DEFAULT_SPEED_RPM = 2000.0
#: A rotation typed in the TOML is re-orthonormalised (nearest rotation, by SVD) when max |R^T R - I| is
#: at most this: six decimals give about 1e-6. Beyond it the rotation is refused.
ROTATION_TOL = 1e-5
#: An x_hint (or a derived zero direction) shorter than this after removing its part along z is parallel to z.
PARALLEL_TOL = 1e-9

#: The reference rocker rotation as a user types it in the TOML: the exact quarter turn (integer entries).
REFERENCE_ROTATION = np.rint(ref.rocker_rotation()).astype(int).tolist()
#: The reference crank rotation (the crank shaft along global z, u1 = 0 along global x), typed likewise.
IDENTITY_ROTATION = np.eye(3, dtype=int).tolist()
#: The rotation forms of a frame table; a table gives exactly one of them beside its origin.
ROTATION_FORMS = ("rotation", "axis_angle", "z_axis")
#: The finest crank-angle step of the table (deg).
STEP_MIN_DEG = 1e-3
#: key: (default, unit, meaning) -- the keys a looper TOML file may hold (defaults: the reference drive).
KEYS = {
    "length_unit": ("mm", "-", "unit of every length below: mm, cm, m or in"),
    "crank_radius": (ref.CRANK_RADIUS, "length", "R1, crank pin axis to crank shaft"),
    "coupler_length": (ref.COUPLER_LENGTH, "length", "r1, ball centre C to crank pin axis"),
    "rocker_length": (ref.ROCKER_LENGTH, "length", "R2, ball centre C to rocker centre P2"),
    "speed_rpm": (DEFAULT_SPEED_RPM, "rpm", "crank speed (machine speed; one turn per stitch)"),
    "branch": (0, "-", "assembly branch, 0 or 1"),
    "step_deg": (0.1, "deg", "crank-angle step of the table, in [0.001, 1]"),
    "looper_link": ("rocker_arm", "-", "link carrying the looper: rocker_arm or rocker_shaft"),
    "looper_tip": (list(ref.LOOPER_TIP), "length", "looper tip in the looper link's frame (rocker arm: x from P2 to C)"),
    "picture_crank_angle_deg": (60.0, "deg", "crank angle at which the 3-D picture draws the links"),
    "cad_tolerance": (1e-5, "length", "largest distance of the CAD B-splines (DXF, STEP) from the exact paths"),
    "crank_frame": ({"origin": [0.0, 0.0, 0.0], "rotation": IDENTITY_ROTATION}, "length",
                    "table: origin (crank shaft point O1) and one rotation form (local z = shaft); u1 from local x"),
    "rocker_frame": ({"origin": list(ref.ROCKER_CENTRE), "rotation": REFERENCE_ROTATION}, "length",
                     "table: origin (rocker centre P2) and one rotation form (local z = rocker shaft)"),
    "links": (ref.STEEL_LINKS, "kg, length, kg*length^2",
              "table per link (crank, coupler, rocker_shaft, rocker_arm): mass, com [x, y, z] and inertia (3x3, or "
              "its diagonal) about the com, in the link's frame; the default is an example of steel links; {} "
              "turns the forces off"),
    "gravity_m_per_s2": ([0.0, 0.0, 0.0], "m/s^2", "gravity in fixed axes for the forces ([0, 0, -9.80665]: z up; "
                         "zeros: none)"),
}
DEFAULTS = {key: value[0] for key, value in KEYS.items()}
#: How a frame table is typed: origin and exactly one rotation form.
ROTATION_HELP = (
    "a frame table holds origin and exactly one rotation form (for no rotation: rotation = [[1, 0, 0], "
    "[0, 1, 0], [0, 0, 1]]): rotation = [[..], [..], [..]] (3x3, columns = local x, y, z; "
    f"re-orthonormalised when max |R^T R - I| <= {ROTATION_TOL:g}); axis_angle = {{ axis = [x, y, z], "
    "angle_deg = a }; z_axis = [x, y, z] with optional x_hint = [x, y, z] (x = hint made normal to z). "
    "z_axis alone fixes the angles by the physical drive: the crank's u1 = 0 points from its shaft towards "
    "the rocker centre; the rocker shaft is turned to the sense of (crank axis x (P2 - O1)) and its u2 = 0 is "
    "the crank's u1 = 0 direction made normal to it, so the same drive gives the same angles however its "
    "axes are typed.")
#: Width of the --help text of the job's files (characters).
HELP_WIDTH = 110
#: The 3-D picture: its size in pixels.
PICTURE_SIZE = (900, 1000)
#: The table of the motion and the record of the run.
TABLE_FILE = "looper_motion.csv"
RECORD_FILE = "looper_run.json"
#: The paths of the ball centre and the looper tip as B-splines: DXF always, STEP with the cad extra.
CAD_FILES = ("looper_paths.dxf", "looper_paths.step")
#: Figures written by the job, besides the table and the record.
FIGURES = ("looper_cyclogram.png", "looper_transmission.png", "looper_speed.png", "looper_3d.png")
#: What each file of the job holds (--help lists output_files() with these).
FILE_NOTES = {
    TABLE_FILE: "the motion, one row per crank angle: ball centre C (ball_...), rocker angles u2, v2 and the looper "
                "tip (tip_...) with velocities and accelerations at machine speed (units in the header, angles in "
                "degrees)",
    RECORD_FILE: "the run's record: geometry, speed, branch, analysis, peaks, measured errors, times, versions, "
                 "the files written",
    "looper_cyclogram.png": "rocker angles and looper-tip coordinates against the crank angle",
    "looper_transmission.png": "the transmission angle at C over the turn, its minimum marked",
    "looper_speed.png": "speed and acceleration of C and the looper tip at machine speed",
    "looper_3d.png": "the mechanism in 3-D at picture_crank_angle_deg, the paths coloured by speed",
    "looper_paths.dxf": "the paths of C and the looper tip as B-splines within cad_tolerance",
    "looper_paths.step": "the same B-splines as STEP (only with the cad extra: OpenCascade)",
    "looper_forces.csv": "crank torque, power, joint loads, shaking force and moment over the turn (SI units; "
                         "not written when links = {})",
    "looper_torque.png": "the crank torque over the turn, its peak and the mean power (not written when links = {})",
    "looper_bearing_loads.png": "each joint's load in its bearing's plane, as polar diagrams (not written when "
                                "links = {})",
}


def output_files():
    """Every file the job can write, in the order it writes them (the names run uses)."""
    return (TABLE_FILE, RECORD_FILE) + FIGURES + CAD_FILES + forces.FILES


def outputs_help():
    """The files of the job with what each holds, for --help (one name a line, its note wrapped beside it)."""
    width = max(map(len, output_files())) + 4
    return "\n".join(textwrap.fill(f"  {name:<{width - 2}}{FILE_NOTES.get(name, '')}", HELP_WIDTH,
                                   subsequent_indent=" " * width) for name in output_files())


def keys_help():
    """The table of keys (name, unit, default, meaning) for --help."""
    lines = ["keys of a looper TOML file (lengths in length_unit; angles in degrees):"]
    for key, (default, unit, meaning) in KEYS.items():
        lines.append(f"  {key:<24} [{unit}] default {json.dumps(default)}\n      {meaning}")
    lines.append(ROTATION_HELP)
    return "\n".join(lines)


# --- the config ---------------------------------------------------------------------------------------------
def _number(name, value, positive=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} must be a number, got {value!r}")
    return check_positive(name, value) if positive else check_real(name, value, finite=True)


def _vector(name, value):
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise ValueError(f"{name} must be a list of 3 numbers, got {value!r}")
    return np.array([_number(f"{name}[{i}]", v) for i, v in enumerate(value)])


def _unit(name, vector):
    n = np.linalg.norm(vector)
    if n == 0:
        raise ValueError(f"{name} must be a non-zero vector")
    return vector / n


def nearest_rotation(name, value):
    """A rotation typed to a few decimals, made exactly orthonormal (polar factor by SVD) when it is within
    ROTATION_TOL of one; ValueError naming it otherwise (see orthonormalised)."""
    rows = value if isinstance(value, (list, tuple)) else None
    if rows is None or len(rows) != 3:
        raise ValueError(f"{name}.rotation must be 3 rows of 3 numbers (columns = local x, y, z)")
    rot = np.array([_vector(f"{name}.rotation[{i}]", r) for i, r in enumerate(rows)])
    return orthonormalised(f"{name}.rotation", rot, ROTATION_TOL,
                           advice=" (type more decimals, or use axis_angle or z_axis + x_hint)")


def _normal_part(vector, z):
    """vector made normal to the unit z, normalised; None when it is (nearly) parallel to z."""
    x = vector - (vector @ z) * z
    n = np.linalg.norm(x)
    return x / n if n > PARALLEL_TOL * max(np.linalg.norm(vector), 1.0) else None


def frame_from(name, table, physical=None):
    """A Frame from a TOML table: 'origin' and exactly one rotation form (see ROTATION_HELP); ValueError naming
    the table otherwise.

    physical : callable (origin, z) -> (z, x) or None
        Fixes the sense of z and the zero direction x from the drive when z_axis is given without x_hint.
    """
    if not isinstance(table, dict):
        raise ValueError(f"{name} must be a table with origin and a rotation form")
    unknown = set(table) - {"origin", "rotation", "axis_angle", "z_axis", "x_hint"}
    if unknown:
        raise ValueError(f"{name}: unknown keys {sorted(unknown)}; allowed: origin, rotation, axis_angle, "
                         "z_axis, x_hint")
    forms = [k for k in ROTATION_FORMS if k in table]
    if len(forms) > 1:
        raise ValueError(f"{name}: give one of rotation, axis_angle, z_axis; got {forms}")
    if "x_hint" in table and "z_axis" not in table:
        raise ValueError(f"{name}: x_hint goes with z_axis")
    if not forms:
        raise ValueError(f"{name}: origin alone does not place a frame; add one rotation form: rotation, "
                         "axis_angle or z_axis (no rotation: rotation = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]; see "
                         "spatialkin looper --help)")
    origin = _vector(f"{name}.origin", table.get("origin", [0.0, 0.0, 0.0]))
    if "rotation" in table:
        rotation = nearest_rotation(name, table["rotation"])
    elif "axis_angle" in table:
        aa = table["axis_angle"]
        if not isinstance(aa, dict) or set(aa) != {"axis", "angle_deg"}:
            raise ValueError(f"{name}.axis_angle must be a table {{ axis = [x, y, z], angle_deg = a }}")
        axis = _unit(f"{name}.axis_angle.axis", _vector(f"{name}.axis_angle.axis", aa["axis"]))
        rotation = rotation_about(axis, math.radians(_number(f"{name}.axis_angle.angle_deg", aa["angle_deg"])))
    else:
        z = _unit(f"{name}.z_axis", _vector(f"{name}.z_axis", table["z_axis"]))
        x = None
        if "x_hint" in table:
            x = _normal_part(_vector(f"{name}.x_hint", table["x_hint"]), z)
            if x is None:
                raise ValueError(f"{name}.x_hint is parallel to z_axis; give a direction across it")
        elif physical is not None:
            z, x = physical(origin, z)
        rotation = rotation_to_z(z) if x is None else np.column_stack([x, np.cross(z, x), z])
    try:
        return Frame(origin, rotation)
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None


def load_config(path=None):
    """The job's settings: the defaults, overridden by a TOML file; every value checked (ValueError naming
    the key)."""
    config = json.loads(json.dumps(DEFAULTS))          # a deep copy
    if path is not None:
        try:
            with open(path, "rb") as f:
                user = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise ValueError(f"{path}: not valid TOML: {err}") from None
        if "omega" in user:
            raise ValueError(f"{path}: no key 'omega': the crank speed is 'speed_rpm' (in rpm)")
        unknown = set(user) - set(DEFAULTS)
        if unknown:
            raise ValueError(f"{path}: unknown keys {sorted(unknown)}; allowed: {sorted(DEFAULTS)}")
        config.update(user)
    for key in ("crank_radius", "coupler_length", "rocker_length", "speed_rpm", "cad_tolerance"):
        config[key] = _number(key, config[key], positive=True)
    step = _number("step_deg", config["step_deg"])
    if not (STEP_MIN_DEG <= step <= 1.0):
        raise ValueError(f"step_deg must lie in [{STEP_MIN_DEG:g}, 1] so that a turn has 361 to 360001 rows, got "
                         f"{step}")
    config["picture_crank_angle_deg"] = _number("picture_crank_angle_deg", config["picture_crank_angle_deg"])
    check_choice("branch", config["branch"], (0, 1))
    if isinstance(config["branch"], bool):
        raise ValueError(f"branch must be 0 or 1, got {config['branch']!r}")
    check_choice("length_unit", config["length_unit"], sorted(METRES_PER_UNIT))
    check_choice("looper_link", config["looper_link"], ("rocker_arm", "rocker_shaft"))
    config["looper_tip"] = _vector("looper_tip", config["looper_tip"]).tolist()
    forces.bodies_of(config["links"], config["length_unit"])        # (checked here: bad input before any work)
    forces.gravity_of(config)
    return config


def build(config):
    """The LooperDrive of a config. A frame given by z_axis alone gets its zero angle from the drive (see
    ROTATION_HELP), so the same physical drive gives the same angles."""
    rocker_origin = _vector("rocker_frame.origin", config["rocker_frame"].get("origin", [0.0, 0.0, 0.0])) \
        if isinstance(config["rocker_frame"], dict) else None

    def crank_zero(origin, z):          # u1 = 0 towards the rocker centre
        return z, (None if rocker_origin is None else _normal_part(rocker_origin - origin, z))

    crank = frame_from("crank_frame", config["crank_frame"], crank_zero)

    def rocker_zero(origin, z):         # shaft sense by the crank axis x (P2 - O1); u2 = 0 along the crank's x
        sense = np.cross(crank.rotation[:, 2], origin - crank.origin)
        if np.linalg.norm(sense) > PARALLEL_TOL * max(np.linalg.norm(origin - crank.origin), 1.0) and z @ sense < 0:
            z = -z
        x = _normal_part(crank.rotation[:, 0], z)
        return z, (x if x is not None else _normal_part(crank.rotation[:, 1], z))

    rocker = frame_from("rocker_frame", config["rocker_frame"], rocker_zero)
    return LooperDrive(config["crank_radius"], config["coupler_length"], config["rocker_length"], crank, rocker,
                       looper_tip=config["looper_tip"], looper_link=config["looper_link"])


# --- the run ------------------------------------------------------------------------------------------------
def reachable_angles(drive, step_deg):
    """Crank angles (rad) of a turn on a grid of step_deg where the drive assembles with margin (CLEARANCE x
    size, as the analysis): the whole turn when the crank turns fully."""
    n = int(round(360.0 / step_deg)) + 1
    angles = np.linspace(0.0, 2 * np.pi, n)
    if not drive.blocked_ranges:
        return angles
    return angles[drive.assembly_margin(angles) > CLEARANCE * drive.size]


def crank_ranges(angles, step):
    """Contiguous runs [(first, last)] of sorted angles in [0, 2 pi] on a grid of the given step (rad); a run
    through crank angle 0 is one range with last < first."""
    breaks = np.nonzero(np.diff(angles) > 1.5 * step)[0]
    starts = np.concatenate([[0], breaks + 1])
    ends = np.concatenate([breaks, [len(angles) - 1]])
    out = [(float(angles[a]), float(angles[b])) for a, b in zip(starts, ends)]
    if len(out) > 1 and out[0][0] < step / 2 and out[-1][1] > 2 * np.pi - step / 2:
        out = [(out[-1][0], out[0][1])] + out[1:-1]          # the first and last runs meet at 0 = 360 deg
    return out


def _ranges_text(ranges):
    return ", ".join(f"[{np.degrees(a):.3f}, {np.degrees(b):.3f}]" + (" (through 0)" if b < a else "")
                     for a, b in ranges)


def columns(unit):
    """CSV header: every column with its unit (ball_: the ball centre C, tip_: the looper tip T)."""
    v, a = f"{unit}_per_s", f"{unit}_per_s2"
    return (["crank_angle_deg", "time_s"] + [f"ball_{c}_{unit}" for c in "xyz"] + [f"ball_v{c}_{v}" for c in "xyz"]
            + [f"ball_a{c}_{a}" for c in "xyz"]
            + ["u2_deg", "v2_deg", "u2_dot_deg_per_s", "v2_dot_deg_per_s", "u2_ddot_deg_per_s2", "v2_ddot_deg_per_s2"]
            + [f"tip_{c}_{unit}" for c in "xyz"] + [f"tip_v{c}_{v}" for c in "xyz"] + [f"tip_a{c}_{a}" for c in "xyz"])


def _versions():
    import numba
    import scipy

    from .. import __version__
    return {"spatialkin": __version__, "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "numba": numba.__version__}


def _peak(values, angles):
    k = int(np.argmax(values))
    return float(values[k]), float(np.degrees(angles[k]))


def run(out_dir, config_path=None, echo=print):
    """Run the job; returns the LooperMotion. Every file is written whole or not at all."""
    t0 = time.perf_counter()
    check_out_dir(out_dir)
    config = load_config(config_path)
    drive = build(config)
    branch = int(config["branch"])
    omega = config["speed_rpm"] * 2 * np.pi / 60.0
    angles = reachable_angles(drive, config["step_deg"])
    if len(angles) < 2:
        raise ValueError("the crank can reach no range of angles wider than the table's step (the coupler's "
                         "circle only grazes the rocker sphere)")
    t_solve = time.perf_counter()
    motion = drive.solve(angles, omega=omega, branch=branch)
    t_solve = time.perf_counter() - t_solve
    analysis = drive.analyse(branch=branch, motion=motion)
    found = findings(drive, motion, analysis, math.radians(config["step_deg"]))
    # what may still fail (a CAD tolerance out of reach, the forces) before any file is written
    t_cad = time.perf_counter()
    splines = path_splines(drive, motion, config["cad_tolerance"], math.radians(config["step_deg"]))
    t_cad = time.perf_counter() - t_cad
    t_forces = time.perf_counter()
    loads = forces.compute(config, motion)
    t_forces = time.perf_counter() - t_forces

    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as err:
        raise OSError(f"--out {out_dir}: cannot make the folder ({err.strerror or err})") from None
    paths = {name: os.path.join(out_dir, name) for name in (TABLE_FILE, RECORD_FILE) + FIGURES}
    with atomic_path(paths[TABLE_FILE]) as tmp:
        np.savetxt(tmp, table(motion), delimiter=",", header=",".join(columns(config["length_unit"])),
                   comments="", fmt="%.15g")
    for line in summary(config, drive, motion, analysis, found):
        echo(line)
    t_fig = time.perf_counter()
    write_figures(paths, config, motion, analysis, found)
    t_fig = time.perf_counter() - t_fig
    t_picture = time.perf_counter()
    picture_3d(motion, paths["looper_3d.png"], config["picture_crank_angle_deg"], config["length_unit"],
               config["speed_rpm"])
    t_picture = time.perf_counter() - t_picture
    t_write = time.perf_counter()
    written = list(FIGURES) + write_cad(out_dir, splines, config, echo)
    t_cad += time.perf_counter() - t_write
    t_write = time.perf_counter()
    peaks = None
    if loads is not None:
        forces.write({name: os.path.join(out_dir, name) for name in forces.FILES}, config, motion, loads)
        peaks = forces.peaks(config, motion, loads)
        for line in forces.summary(peaks):
            echo(line)
        written += list(forces.FILES)
    t_forces += time.perf_counter() - t_write
    times = {"solve": t_solve, "figures": t_fig, "picture_3d": t_picture, "cad": t_cad, "forces": t_forces,
             "job": time.perf_counter() - t0}
    with atomic_path(paths[RECORD_FILE]) as tmp:
        with open(tmp, "w") as f:
            rec = record(config, drive, motion, analysis, found, times)
            if peaks is not None:
                rec["forces"] = peaks
            rec["files"] = [TABLE_FILE, *written]         # what this run wrote (STEP needs the extra)
            json.dump(rec, f, indent=1)
    echo(f"time: solve {1e3 * t_solve:.1f} ms, figures {t_fig:.2f} s, 3-D picture {t_picture:.2f} s, CAD paths "
         f"{t_cad:.2f} s, forces {t_forces:.2f} s, whole job {time.perf_counter() - t0:.2f} s")
    echo(f"wrote {', '.join(os.path.join(out_dir, n) for n in [TABLE_FILE, RECORD_FILE] + written)}")
    return motion


def path_splines(drive, motion, tol, step):
    """B-splines (crank angle in rad) of the ball-centre and tip paths over each reachable crank range, within
    tol (length) of the exact paths: [(name, range index, BSpline)]."""
    scale = min(drive.torus.size, drive.sphere.size)
    out = []
    ranges = crank_ranges(motion.crank_angle, step)
    for k, (a, b) in enumerate(ranges):
        full = len(ranges) == 1 and a == 0.0 and b >= 2 * np.pi - step / 2
        b = b + 2 * np.pi if b < a else b
        part = motion if full else drive.solve(np.linspace(a, b, 16), omega=motion.omega, branch=motion.branch)
        for which in ("ball", "tip"):
            out.append((which, k, part.path_bspline(which, tol / scale)))
    return out


def write_cad(out_dir, splines, config, echo=print):
    """looper_paths.dxf (always) and looper_paths.step (with the cad extra; a line names it otherwise): the
    ball-centre and tip paths' B-splines (path_splines, within config['cad_tolerance']). Returns the names
    written."""
    from ..export import write_dxf, write_step
    curves = [sp for _, _, sp in splines]
    written = []
    for name, writer in zip(CAD_FILES, (write_dxf, write_step)):
        try:
            writer(os.path.join(out_dir, name), curves, unit=config["length_unit"])
            written.append(name)
        except ImportError as err:
            echo(f"not written: {name} ({err})")
    worst = max(sp.deviation for sp in curves)
    echo(f"CAD paths: {len(curves)} B-splines (ball centre, looper tip), degree 5, "
         f"{sum(len(sp.c) for sp in curves)} control points, within {worst:.2g} {config['length_unit']} of the "
         "exact paths (measured)")
    return written


def table(motion):
    """The CSV's rows (see columns): angles in degrees, time at the motion's crank speed."""
    deg = np.degrees
    tip = motion.looper_tip
    return np.column_stack([deg(motion.crank_angle), motion.crank_angle / motion.omega, motion.ball_center,
                            motion.ball_velocity, motion.ball_acceleration, deg(motion.rocker_angles),
                            deg(motion.rocker_rates), deg(motion.rocker_accelerations), tip.position, tip.velocity,
                            tip.acceleration])


def findings(drive, motion, analysis, step):
    """What the summary and the record report, from the solved motion (angles in degrees, lengths in the
    drive's unit, peaks at the motion's crank speed as (value, crank angle in deg))."""
    deg = np.degrees
    angles = motion.crank_angle
    tip = motion.looper_tip
    u2, v2 = deg(motion.rocker_angles.T)
    u2_span, v2_span = figs.angle_span(u2), figs.angle_span(v2)
    u2_seen = figs.on_span(u2, u2_span)
    at_lo, at_hi = float(deg(angles[int(np.argmin(u2_seen))])), float(deg(angles[int(np.argmax(u2_seen))]))
    peaks = {name: _peak(np.linalg.norm(x, axis=1), angles) for name, x in
             (("ball_v", motion.ball_velocity), ("ball_a", motion.ball_acceleration),
              ("tip_v", tip.velocity), ("tip_a", tip.acceleration))}
    rates = {name: _peak(np.abs(deg(x)), angles) for name, x in
             (("u2_dot", motion.rocker_rates[:, 0]), ("v2_dot", motion.rocker_rates[:, 1]),
              ("u2_ddot", motion.rocker_accelerations[:, 0]), ("v2_ddot", motion.rocker_accelerations[:, 1]))}
    # measured errors: exact distances of C to both surfaces; C by the coupler chain against the rocker chain
    errors = {"C_to_torus": float(drive.torus.distance(motion.ball_center).max()),
              "C_to_sphere": float(drive.sphere.distance(motion.ball_center).max()),
              "coupler_vs_rocker_chain": float(np.abs(
                  motion.point("coupler", (drive.coupler_length, 0, 0)).position
                  - motion.point("rocker_arm", (drive.rocker_length, 0, 0)).position).max())}
    return {"ranges": crank_ranges(angles, step), "step": step, "u2_span": u2_span, "v2_span": v2_span,
            "u2_least_at": at_lo, "u2_greatest_at": at_hi, "forward": (at_hi - at_lo) % 360.0,
            "peaks": peaks, "rates": rates, "errors": errors,
            "min_transmission": tuple(float(x) for x in deg(analysis.min_transmission))}


def summary(config, drive, motion, analysis, found):
    """The printed summary, line by line."""
    deg = np.degrees
    unit, rpm, si = config["length_unit"], config["speed_rpm"], METRES_PER_UNIT[config["length_unit"]]
    lines = [f"looper drive: crank {drive.crank_radius:g} {unit}, coupler {drive.coupler_length:g} {unit}, rocker "
             f"{drive.rocker_length:g} {unit}; branch {motion.branch}; {rpm:g} rpm ({motion.omega:.4g} rad/s, "
             f"{60e3 / rpm:.4g} ms per turn); {len(motion)} crank angles"]
    if analysis.turns_fully:
        lines.append("crank: turns fully (no dead position, no branch point)")
    else:
        lines.append("crank: cannot turn fully; it reaches (and rocks within) " + _ranges_text(found["ranges"])
                     + f" deg; branch {motion.branch} analysed there, {CLEARANCE:g} x size clear of the dead positions")
        lines.append("dead positions at crank angles " + ", ".join(f"{deg(x):.4f}" for x in analysis.dead_positions)
                     + " deg" + ("; blocked: " + _ranges_text(analysis.blocked_ranges) + " deg"
                                 if analysis.blocked_ranges else ""))
        lines.append("note: at a dead position the crank cannot be driven at constant speed; speeds and "
                     "accelerations at machine speed grow without bound towards it")
    if analysis.branch_points:
        lines.append("assembly branches meet at crank angles "
                     + ", ".join(f"{deg(x):.4f}" for x in analysis.branch_points) + " deg")
    (u_lo, u_hi), (v_lo, v_hi) = found["u2_span"], found["v2_span"]
    lines.append(f"rocker swing: u2 {u_lo:.3f}..{u_hi:.3f} deg ({u_hi - u_lo:.3f} deg), "
                 f"v2 {v_lo:.3f}..{v_hi:.3f} deg ({v_hi - v_lo:.3f} deg)")
    timing = f"timing: u2 least at crank {found['u2_least_at']:.1f} deg, greatest at {found['u2_greatest_at']:.1f} deg"
    if analysis.turns_fully:
        forward = found["forward"]
        timing += (f": forward stroke {forward:.1f} deg of crank ({forward / 360 * 60e3 / rpm:.3g} ms), return "
                   f"{360 - forward:.1f} deg")
    lines.append(timing)
    for label, v, a in (("ball centre C", "ball_v", "ball_a"), ("looper tip", "tip_v", "tip_a")):
        (vmax, vat), (amax, aat) = found["peaks"][v], found["peaks"][a]
        lines.append(f"at {rpm:g} rpm, {label}: peak speed {vmax * si:.4g} m/s (crank {vat:.1f} deg), peak "
                     f"acceleration {amax * si:.4g} m/s^2 = {amax * si / STANDARD_GRAVITY:.4g} g (crank {aat:.1f} deg)")
    rates = found["rates"]
    lines.append(f"at {rpm:g} rpm, rocker: peak |du2/dt| {rates['u2_dot'][0]:.4g} deg/s, |dv2/dt| "
                 f"{rates['v2_dot'][0]:.4g} deg/s, |d2u2/dt2| {rates['u2_ddot'][0]:.4g} deg/s^2, |d2v2/dt2| "
                 f"{rates['v2_ddot'][0]:.4g} deg/s^2")
    mu, mu_at = found["min_transmission"]
    lines.append(f"smallest transmission angle {mu:.2f} deg at crank angle {mu_at:.1f} deg")
    e = found["errors"]
    lines.append(f"measured error: C to torus {e['C_to_torus']:.2e} {unit}, to sphere {e['C_to_sphere']:.2e} {unit}, "
                 f"coupler vs rocker chain {e['coupler_vs_rocker_chain']:.2e} {unit}")
    return lines


def write_figures(paths, config, motion, analysis, found):
    """The cyclogram, transmission and speed figures (PNG, each written whole or not at all)."""
    unit, step = config["length_unit"], found["step"]
    marks = {"dead": list(analysis.dead_positions), "branch": list(analysis.branch_points),
             "blocked": list(analysis.blocked_ranges)}
    for name, draw in (("looper_cyclogram.png", lambda p: figs.cyclogram(motion, p, unit, marks, step)),
                       ("looper_transmission.png", lambda p: figs.transmission(analysis, p, step)),
                       ("looper_speed.png", lambda p: figs.speed(motion, p, unit, config["speed_rpm"], step))):
        with atomic_path(paths[name]) as tmp:
            draw(tmp)


def record(config, drive, motion, analysis, found, times):
    """The run's record (looper_run.json): geometry, speed, branch, ranges, analysis, peaks, errors, versions."""
    deg = np.degrees
    si = METRES_PER_UNIT[config["length_unit"]]
    mu, mu_at = found["min_transmission"]
    return {
        "length_unit": config["length_unit"],
        "geometry": {"crank_radius": drive.crank_radius, "coupler_length": drive.coupler_length,
                     "rocker_length": drive.rocker_length,
                     "crank_frame": {"origin": drive.crank_frame.origin.tolist(),
                                     "rotation": drive.crank_frame.rotation.tolist()},
                     "rocker_frame": {"origin": drive.rocker_frame.origin.tolist(),
                                      "rotation": drive.rocker_frame.rotation.tolist()},
                     "looper_link": drive.looper_link, "looper_tip": drive.looper_tip.tolist()},
        "speed": {"rpm": config["speed_rpm"], "omega_rad_per_s": motion.omega, "turn_ms": 60e3 / config["speed_rpm"]},
        "branch": motion.branch, "step_deg": config["step_deg"], "rows": len(motion),
        "crank_ranges_deg": [[deg(a), deg(b)] for a, b in found["ranges"]],
        "analysis": {"turns_fully": analysis.turns_fully,
                     "dead_positions_deg": deg(analysis.dead_positions).tolist(),
                     "branch_points_deg": deg(analysis.branch_points).tolist(),
                     "blocked_ranges_deg": [[deg(a), deg(b)] for a, b in analysis.blocked_ranges],
                     "u2_range_deg": list(found["u2_span"]), "v2_range_deg": list(found["v2_span"]),
                     "u2_least_at_crank_deg": found["u2_least_at"], "u2_greatest_at_crank_deg": found["u2_greatest_at"],
                     "min_transmission_angle_deg": mu, "min_transmission_at_crank_deg": mu_at},
        "peaks_at_machine_speed": {
            **{f"{k}_{'m_per_s' if k.endswith('v') else 'm_per_s2'}": [p[0] * si, p[1]]
               for k, p in found["peaks"].items()},
            **{f"{k}_{'deg_per_s2' if k.endswith('ddot') else 'deg_per_s'}": list(p)
               for k, p in found["rates"].items()},
            "note": "[value, crank angle in deg]"},
        "measured_error": {**found["errors"], "unit": config["length_unit"]},
        "time_s": times,
        "versions": _versions(),
        "files": [TABLE_FILE, *FIGURES, *CAD_FILES],
    }


def picture_3d(motion, path, crank_angle_deg=60.0, unit="mm", speed_rpm=None):
    """The mechanism in 3-D to a PNG (off-screen): links and joints named at the crank angle nearest to
    crank_angle_deg, the ball centre's and the looper tip's paths coloured by speed, axes marker, title."""
    from ..render import looper_scene
    wrapped = np.mod(motion.crank_angle - np.radians(crank_angle_deg) + np.pi, 2 * np.pi) - np.pi
    index = int(np.argmin(np.abs(wrapped)))
    looper_scene(motion, index, window_size=PICTURE_SIZE, labels=True, unit=unit,
                 title=f"Looper drive at crank angle {np.degrees(motion.crank_angle[index]):.1f} deg"
                 + (f", {speed_rpm:g} rpm" if speed_rpm else "")).screenshot(path)
