"""The main job's forces: the crank torque, the joints' loads and the shaking force and moment at machine speed,
from the links' masses of the config (key ``links``: the reference drive's example steel links by default; an
empty table turns the forces off) and its gravity (``gravity_m_per_s2``, fixed axes) -> looper_forces.csv (SI units
in every header), looper_torque.png, looper_bearing_loads.png and the peaks in looper_run.json."""
import numpy as np

from ..dynamics import Body
from ..mechanisms.looper.loads import BEARING_PLANES, JOINTS, LINKS
from .._lib.files import atomic_path
from .._lib.units import METRES_PER_UNIT
from ..plots import forces as figs

#: Files written when the config gives masses.
FILES = ("looper_forces.csv", "looper_torque.png", "looper_bearing_loads.png")
#: A mean crank power below this fraction of the peak is that of frictionless joints (the summary says so).
IDEAL_MEAN = 1e-6


def bodies_of(links, unit):
    """{link: Body} from the config's ``links`` table (mass kg, com in the length unit, inertia in kg x unit^2: a
    3 x 3 table or its 3 diagonal entries); ValueError naming links.<link>.<key>."""
    if not isinstance(links, dict):
        raise ValueError(f"links must be a table of link -> {{mass, com, inertia}}, got {links!r}")
    out = {}
    for name, spec in links.items():
        if name not in LINKS:
            raise ValueError(f"links: unknown link {name!r}; the links are {list(LINKS)}")
        if not isinstance(spec, dict) or "mass" not in spec:
            raise ValueError(f"links.{name} must be a table with mass (kg), com ({unit}) and inertia (kg {unit}^2)")
        unknown = set(spec) - {"mass", "com", "inertia"}
        if unknown:
            raise ValueError(f"links.{name}: unknown keys {sorted(unknown)}; allowed: mass, com, inertia")
        inertia = spec.get("inertia")
        if isinstance(inertia, list) and len(inertia) == 3 and not isinstance(inertia[0], list):
            inertia = np.diag(np.asarray(inertia, dtype=float))
        try:
            out[name] = Body(spec["mass"], spec.get("com", (0.0, 0.0, 0.0)), inertia)
        except (ValueError, TypeError) as err:
            raise ValueError(f"links.{name}: {err}") from None
    return out


def gravity_of(config):
    """The config's gravity in the drive's length unit per s^2 (fixed axes), or None for a zero vector."""
    g = config["gravity_m_per_s2"]
    if not isinstance(g, list) or len(g) != 3 or not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                                         and np.isfinite(x) for x in g):
        raise ValueError(f"gravity_m_per_s2 must be a list of 3 finite numbers (m/s^2, fixed axes), got {g!r}")
    g = np.asarray(g, dtype=float)
    return None if not g.any() else g / METRES_PER_UNIT[config["length_unit"]]


def compute(config, motion):
    """The loads of the motion with the config's masses and gravity, or None when the config gives no masses."""
    bodies = bodies_of(config["links"], config["length_unit"])
    gravity = gravity_of(config)
    if not bodies:
        return None
    return motion.loads(bodies, gravity=gravity)


def columns():
    """The CSV header: every column with its SI unit."""
    out = ["crank_angle_deg", "crank_torque_N_m", "power_W"]
    for joint in JOINTS:
        out += [f"{joint}_F{c}_N" for c in "xyz"] + [f"{joint}_F_N"]
    out += [f"shaking_F{c}_N" for c in "xyz"] + [f"shaking_M{c}_N_m" for c in "xyz"]
    return out


def write(paths, config, motion, loads):
    """looper_forces.csv, looper_torque.png and looper_bearing_loads.png (each written whole or not at all)."""
    si = METRES_PER_UNIT[config["length_unit"]]
    angles = np.degrees(motion.crank_angle)
    torque = loads.crank_torque * si ** 2
    parts = [angles[:, None], torque[:, None], (torque * motion.omega)[:, None]]
    for joint in JOINTS:
        f = loads.joint_force[joint] * si
        parts += [f, np.linalg.norm(f, axis=1)[:, None]]
    parts += [loads.shaking_force * si, loads.shaking_moment * si ** 2]
    with atomic_path(paths["looper_forces.csv"]) as tmp:
        np.savetxt(tmp, np.hstack(parts), delimiter=",", header=",".join(columns()), comments="", fmt="%.15g")
    with atomic_path(paths["looper_torque.png"]) as tmp:
        figs.torque(angles, torque, motion.omega, tmp, title=f"crank torque at {config['speed_rpm']:g} rpm")
    with atomic_path(paths["looper_bearing_loads.png"]) as tmp:
        figs.bearing_loads({j: loads.joint_force_local[j] * si for j in JOINTS}, tmp, BEARING_PLANES,
                           title=f"joint loads at {config['speed_rpm']:g} rpm (N), in each bearing's plane")


def peaks(config, motion, loads):
    """The record's forces: peak crank torque, mean power, each joint's peak load and the shaking peaks, in SI
    ([value, crank angle in deg])."""
    si = METRES_PER_UNIT[config["length_unit"]]
    deg = np.degrees(motion.crank_angle)

    def peak(values):
        k = int(np.argmax(values))
        return [float(values[k]), float(deg[k])]
    torque = loads.crank_torque * si ** 2
    power = torque * motion.omega
    return {"crank_torque_N_m": peak(np.abs(torque)), "mean_power_W": float(np.mean(power)),
            "peak_power_W": peak(np.abs(power)),
            "joint_force_N": {j: peak(np.linalg.norm(loads.joint_force[j], axis=1) * si) for j in JOINTS},
            "shaking_force_N": peak(np.linalg.norm(loads.shaking_force, axis=1) * si),
            "shaking_moment_N_m": peak(np.linalg.norm(loads.shaking_moment, axis=1) * si ** 2),
            "note": "[peak magnitude, crank angle in deg]"}


def summary(record):
    """The printed lines of the forces."""
    joints = ", ".join(f"{j.replace('_', ' ')} {v[0]:.4g}" for j, v in record["joint_force_N"].items())
    return [f"forces: peak crank torque {record['crank_torque_N_m'][0]:.4g} N m (crank "
            f"{record['crank_torque_N_m'][1]:.1f} deg), peak power {record['peak_power_W'][0]:.3g} W, mean power "
            f"{record['mean_power_W']:.3g} W" + (" (frictionless joints: the links' energy is the same after a turn)"
                                                  if abs(record["mean_power_W"]) <= IDEAL_MEAN * record["peak_power_W"][0]
                                                  else ""),
            f"peak joint loads (N): {joints}",
            f"peak shaking force {record['shaking_force_N'][0]:.4g} N, moment {record['shaking_moment_N_m'][0]:.4g} N m"]
