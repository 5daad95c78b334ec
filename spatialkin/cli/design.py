"""``spatialkin design --targets FILE.toml [--out FITTED.toml]``: fit a looper drive to targets and write the
fitted geometry as a config that ``spatialkin looper --config`` accepts.

The targets file (angles in degrees, lengths in the drive's unit):

    [design]
    free = ["crank_radius", "rocker_length", "rocker_x", "rocker_z", "tip_x", "tip_z"]   # what the fit may move
    # start = "start.toml"        # optional: a looper config to start from (default: the reference drive)
    [design.bounds]               # optional, {parameter = [low, high]}
    crank_radius = [5.0, 12.0]

    [[tip]]                       # looper tip targets, any number
    crank_angle_deg = 90.0        # the reference drive's tip is at (-2.76, -0.56, 34.17) here
    point = [-4.0, -1.0, 35.0]
    [rocker]                      # optional
    swing_deg = 40.0              # the reference drive swings 37.16 deg
    u2_max_at_deg = 0.0           # optional pair: the rocker's turning points (the reference drive's: u2 is
    u2_min_at_deg = 180.0         # greatest at crank angle 0, least at 180)
    [limits]                      # optional
    min_transmission_deg = 50.0
    min_assembly_margin = 0.5
    [weights]                     # optional: tip, swing, timing, transmission, margin
    [tolerances]                  # optional: within which a target counts as met
    tip = 0.01                    # length (default 1e-5 of R1 + r1 + R2)
    angle_deg = 0.1               # swing, timing, transmission bound (default 0.01)
    margin = 0.01                 # assembly-margin bound, length (default 1e-5 of R1 + r1 + R2)

Parameter names: spatialkin.design.params.PARAMETERS.

Every target is printed with what the fitted drive achieves, its miss and the tolerance within which it counts as
met ([tolerances] above). A target missed by more than its
tolerance is named in one line with the parameters held fixed that could reach it (confirmed by a fit with each
freed) or that move it; the exit status is then 1, and the fitted config is written all the same.
"""
import argparse
import math
import os
import sys
import tomllib

import numpy as np

from . import USER_ERRORS, OneLineParser
from .._lib.files import atomic_path, check_out_file
from ..design.fit import FIT_SAMPLES, Targets
from ..design.looper import LooperDesign
from ..design.report import format_rows, target_rows

#: Keys of the [design] table.
DESIGN_KEYS = {"free", "start", "bounds"}
#: Keys of a looper config that the fitted geometry replaces (the start's other keys are kept).
GEOMETRY_KEYS = {"crank_radius", "coupler_length", "rocker_length", "looper_tip", "looper_link", "branch",
                 "crank_frame", "rocker_frame"}


def toml_value(value):
    """A TOML literal for a number, string, bool or (nested) list."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise ValueError(f"cannot write {type(value).__name__} to TOML")


def to_toml(config, comment=None):
    """TOML text of a flat config whose values are literals or one level of tables."""
    lines = [f"# {line}" for line in (comment or "").splitlines()]
    tables = {k: v for k, v in config.items() if isinstance(v, dict)}
    lines += [f"{k} = {toml_value(v)}" for k, v in config.items() if not isinstance(v, dict)]
    for name, table in tables.items():
        lines += ["", f"[{name}]"] + [f"{k} = {toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def read_targets(path):
    """(start design, Targets, job settings of the start config to carry over) from a targets TOML file."""
    with open(path, "rb") as f:
        try:
            table = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise ValueError(f"{path}: {err}") from None
    design_table = table.pop("design", {})
    if not isinstance(design_table, dict):
        raise ValueError(f"{path}: [design] must be a table")
    unknown = set(design_table) - DESIGN_KEYS
    if unknown:
        raise ValueError(f"{path}: [design] has unknown keys {sorted(unknown)}; allowed {sorted(DESIGN_KEYS)}")
    if "free" not in design_table:
        raise ValueError(f"{path}: [design] needs free = [parameter names]")
    job = {}
    if "start" in design_table:
        from .looper_job import build, load_config
        start = os.path.join(os.path.dirname(os.path.abspath(path)), design_table["start"])
        config = load_config(start)
        drive = build(config)
        design = LooperDesign.from_drive(drive, branch=int(config["branch"]))
        with open(start, "rb") as f:      # the start's own job settings (unit, speed, step, ...) carry over
            job = {k: v for k, v in tomllib.load(f).items() if k not in GEOMETRY_KEYS}
    else:
        design = LooperDesign.reference()
    bounds = design_table.get("bounds")
    design = LooperDesign(design.values, design_table["free"], bounds, design.crank_frame, design.looper_link,
                          design.branch)
    return design, Targets.from_dict(table), job


def main_design(argv=None):
    """Entry point of ``spatialkin design``; returns the exit status: 0 every target met, 1 the fit did not converge
    or a target is missed by more than its tolerance (the fitted config is written all the same), 2 an error."""
    parser = OneLineParser(prog="spatialkin design", description=__doc__,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--targets", required=True, help="TOML file with the targets (see above)")
    parser.add_argument("--out", default=None,
                        help="where to write the fitted config (default: <targets>_fitted.toml beside it)")
    args = parser.parse_args(argv)
    out = args.out or os.path.splitext(args.targets)[0] + "_fitted.toml"
    try:
        check_out_file(out)                       # (before the fit, not after it)
        design, targets, job = read_targets(args.targets)
        fitted = design.fit(targets)
        config = fitted.design.to_config(**job)
        os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
        with atomic_path(out) as tmp:
            with open(tmp, "w", encoding="utf-8") as f:
                f.write(to_toml(config, comment=f"looper drive fitted by spatialkin design to {args.targets}\n"
                                                f"free: {', '.join(design.free)}"))
    except USER_ERRORS as err:
        print(f"spatialkin design: {err}", file=sys.stderr)
        return 2
    a = fitted.achieved
    print(f"fit: {fitted.result.message} ({fitted.result.nfev} evaluations, cost {a['cost']:.3g})")
    for name in design.free:
        print(f"  {name:<15} {design.values[name]:>12.6g} -> {fitted.design.values[name]:>12.6g}")
    print(f"swing {math.degrees(a['swing']):.4f} deg, turning points at "
          + ", ".join(f"{math.degrees(x) % 360:.3f}" for x in a["turning_points"]) + " deg; "
          f"smallest transmission angle {math.degrees(a['min_transmission']):.3f} deg; "
          f"assembly margin {a['assembly_margin']:.4g}")
    rows = target_rows(fitted.design, targets, np.linspace(0.0, 2 * np.pi, FIT_SAMPLES))
    print("targets (angles in degrees, lengths in the drive's unit):")
    print("\n".join(format_rows(rows)))
    print(f"wrote {out} (spatialkin looper --config {out})")
    return 0 if fitted.success and all(r.met for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main_design())
