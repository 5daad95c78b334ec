"""The looper drive's geometry as a vector of named design parameters, with bounds.

The crank frame is the fixed reference (the designer's axes); everything else is a parameter:

============== ====== ===========================================================================
name           unit   meaning
============== ====== ===========================================================================
crank_radius   length R1, crank pin axis to crank shaft
coupler_length length r1, ball centre C to the crank pin axis
rocker_length  length R2, C to the rocker centre P2
rocker_x/y/z   length P2, the rocker frame's origin (global)
rocker_rx/ry/rz rad   the rocker frame's rotation T2 = Rz(rz) Ry(ry) Rx(rx) (fixed-axis x, then y, then z)
tip_x/y/z      length the looper tip in the frame of the looper link (rocker arm: x from P2 to C)
============== ====== ===========================================================================
"""
import math

import numpy as np

from .._lib.validation import check_positive, check_real

#: Every design parameter, in the order of the design vector.
PARAMETERS = ("crank_radius", "coupler_length", "rocker_length", "rocker_x", "rocker_y", "rocker_z",
              "rocker_rx", "rocker_ry", "rocker_rz", "tip_x", "tip_y", "tip_z")
LENGTHS = ("crank_radius", "coupler_length", "rocker_length")
ANGLES = ("rocker_rx", "rocker_ry", "rocker_rz")
#: Default bounds: lengths within these factors of their value ...
LENGTH_FACTORS = (0.5, 2.0)
#: ... positions within this fraction of the drive's size (R1 + r1 + R2) of their value ...
POSITION_REACH = 0.5
#: ... and angles within this many radians of their value.
ANGLE_REACH = math.pi / 4


def check_names(names, argument="free"):
    """A tuple of parameter names, or ValueError naming the argument."""
    if isinstance(names, str):
        names = (names,)
    names = tuple(names)
    unknown = [n for n in names if n not in PARAMETERS]
    if unknown:
        raise ValueError(f"{argument}: unknown design parameters {unknown}; known: {list(PARAMETERS)}")
    if len(set(names)) != len(names):
        raise ValueError(f"{argument}: a parameter is named twice in {list(names)}")
    if not names:
        raise ValueError(f"{argument} must name at least one design parameter")
    return tuple(n for n in PARAMETERS if n in names)      # canonical order


def rotation_from_angles(rx, ry, rz):
    """T2 = Rz(rz) Ry(ry) Rx(rx) (3, 3)."""
    cx, sx, cy, sy, cz, sz = (math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz),
                              math.sin(rz))
    rot_x = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    rot_y = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rot_z = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rot_z @ rot_y @ rot_x


def angles_from_rotation(rotation):
    """(rx, ry, rz) with rotation = Rz(rz) Ry(ry) Rx(rx); ry in [-pi/2, pi/2]."""
    r = np.asarray(rotation, dtype=float)
    ry = -math.asin(max(-1.0, min(1.0, r[2, 0])))
    if abs(abs(r[2, 0]) - 1.0) < 1e-12:       # gimbal lock: put the whole turn about x
        return math.atan2(-r[1, 2], r[1, 1]), ry, 0.0
    return math.atan2(r[2, 1], r[2, 2]), ry, math.atan2(r[1, 0], r[0, 0])


def default_bounds(values):
    """Bounds {name: (low, high)} around the values {name: float}."""
    size = values["crank_radius"] + values["coupler_length"] + values["rocker_length"]
    out = {}
    for name, v in values.items():
        if name in LENGTHS:
            out[name] = (LENGTH_FACTORS[0] * v, LENGTH_FACTORS[1] * v)
        elif name in ANGLES:
            out[name] = (v - ANGLE_REACH, v + ANGLE_REACH)
        else:
            out[name] = (v - POSITION_REACH * size, v + POSITION_REACH * size)
    return out


def check_values(values, argument="values"):
    """{name: float} for every parameter, finite, lengths positive; ValueError naming the argument."""
    if not isinstance(values, dict):
        raise ValueError(f"{argument} must be a dict of design parameters, got {type(values).__name__}")
    missing = [n for n in PARAMETERS if n not in values]
    unknown = [n for n in values if n not in PARAMETERS]
    if missing or unknown:
        raise ValueError(f"{argument}: missing {missing}, unknown {unknown}")
    out = {}
    for n in PARAMETERS:
        name = f"{argument}: {n}"
        out[n] = check_positive(name, values[n]) if n in LENGTHS else check_real(name, values[n], finite=True)
    return out
