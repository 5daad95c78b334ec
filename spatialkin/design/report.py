"""How a fitted looper drive meets its targets: each target with what the drive achieves, the miss and the
tolerance within which it counts as met, and, for a target missed, the parameters held fixed that could reach it.

A parameter "could reach" a missed target when one step of it alone, the least-squares step of the target's
linearisation (its exact derivative by that parameter, spatialkin.design.sensitivity), brings the miss within the
tolerance and stays within the parameter's bounds. The linearisation is a first-order guide, not a promise: the
user frees the parameter and fits again.
"""
import math
from dataclasses import dataclass

import numpy as np

from .params import PARAMETERS

#: Unless the targets set their own (Targets.tolerances), a tip target counts as met within this share of the
#: drive's size (R1 + r1 + R2) ...
TIP_TOLERANCE_SHARE = 1e-5
#: ... an angle target (swing, the timing of the turning points, the transmission-angle bound) within this (rad)
ANGLE_TOLERANCE = math.radians(0.01)
#: ... and the assembly-margin bound within this share of the size.
MARGIN_TOLERANCE_SHARE = 1e-5


@dataclass(frozen=True)
class TargetRow:
    """One target of a fit. ``wanted``, ``achieved``, ``miss`` and ``tolerance`` in ``unit`` ('deg' or the drive's
    length unit, 'length'); a tip target's wanted and achieved are points (3,), its miss their distance; a bound's
    miss is how far the achieved value falls short of it (0 when it holds). ``reach``: the parameters held fixed
    that could bring a missed target within its tolerance, ``movers`` those that move it at all (both empty for a
    target met), the strongest first."""
    name: str
    wanted: object
    achieved: object
    miss: float
    tolerance: float
    unit: str
    reach: tuple = ()
    movers: tuple = ()

    @property
    def met(self):
        return bool(self.miss <= self.tolerance)


def target_rows(fitted, targets, grid, confirm=True):
    """The TargetRow of every target of ``targets`` (spatialkin.design.fit.Targets) for the LooperDesign
    ``fitted``, its turn sampled at the crank angles ``grid`` (rad) as the fit samples it. With ``confirm``, each
    candidate to reach a missed target is confirmed by a fit with it freed as well (one fit per candidate)."""
    turn = fitted.sensitivities(grid, free=PARAMETERS)
    size = sum(fitted.values[n] for n in ("crank_radius", "coupler_length", "rocker_length"))
    own = targets.tolerances
    tip_tol = own.get("tip", TIP_TOLERANCE_SHARE * size)
    angle_tol = own.get("angle", ANGLE_TOLERANCE)
    margin_tol = own.get("margin", MARGIN_TOLERANCE_SHARE * size)
    rows = []           # (name, wanted, achieved, residual (k,), derivative (k, P), tolerance, unit, scale)
    if len(targets.tip_angles):
        tips = fitted.sensitivities(targets.tip_angles, free=PARAMETERS, turning=False)
        for angle, want, got, d_got in zip(targets.tip_angles, targets.tip_points, tips.tip, tips.d_tip):
            rows.append((f"tip at {math.degrees(angle):g} deg", want, got, got - want, d_got,
                         tip_tol, "length", 1.0))
    if targets.swing is not None:
        rows.append(("swing", targets.swing, turn.swing, np.array([turn.swing - targets.swing]),
                     turn.d_swing[None], angle_tol, "deg", math.degrees(1.0)))
    if targets.timing is not None:
        u2 = turn.turning_u2
        for name, k, want in (("u2 max at", int(np.argmax(u2)), targets.timing[0]),
                              ("u2 min at", int(np.argmin(u2)), targets.timing[1])):
            got = turn.turning_points[k]
            rows.append((name, want % (2 * math.pi), got % (2 * math.pi),
                         np.array([math.remainder(got - want, 2 * math.pi)]), turn.d_turning_points[k][None],
                         angle_tol, "deg", math.degrees(1.0)))
    if targets.min_transmission is not None:
        short = max(targets.min_transmission - turn.min_transmission, 0.0)
        rows.append(("min transmission angle", targets.min_transmission, turn.min_transmission,
                     np.array([-short]), turn.d_min_transmission[None], angle_tol, "deg",
                     math.degrees(1.0)))
    if targets.min_margin is not None:
        short = max(targets.min_margin - turn.assembly_margin, 0.0)
        rows.append(("min assembly margin", targets.min_margin, turn.assembly_margin, np.array([-short]),
                     turn.d_assembly_margin[None], margin_tol, "length", 1.0))
    out = []
    for k, (name, want, got, residual, derivative, tolerance, unit, scale) in enumerate(rows):
        miss = float(np.linalg.norm(residual))
        reach, movers = ((), ()) if miss <= tolerance else reaching(fitted, residual, derivative, tolerance)
        if confirm:
            reach = tuple(n for n in reach if _met_when_freed(fitted, targets, grid, n, k))
        out.append(TargetRow(name, np.asarray(want, float) * scale, np.asarray(got, float) * scale, miss * scale,
                             tolerance * scale, unit, reach, movers))
    return out


def reaching(design, residual, derivative, tolerance):
    """(reach, movers): the parameters not free in ``design`` whose least-squares step alone brings ``residual``
    (k,) within ``tolerance`` by its linearisation (``derivative`` (k, P) over PARAMETERS) within their bounds, and
    those that move it by more than the tolerance across their bounds; each the strongest first."""
    reach, movers = [], []
    for p, name in enumerate(PARAMETERS):
        if name in design.free:
            continue
        g = derivative[:, p]
        gg = float(g @ g)
        low, high = design.bounds[name]
        strength = math.sqrt(gg) * (high - low)
        if strength <= tolerance:
            continue
        movers.append((strength, name))
        step = -float(g @ residual) / gg
        if np.linalg.norm(residual + g * step) <= tolerance and low <= design.values[name] + step <= high:
            reach.append((strength, name))
    return tuple(n for _, n in sorted(reach, reverse=True)), tuple(n for _, n in sorted(movers, reverse=True))


def _met_when_freed(fitted, targets, grid, name, index):
    """Whether the fit from ``fitted`` with ``name`` freed as well meets target row ``index``."""
    try:
        refit = fitted.fit(targets, free=fitted.free + (name,))
    except ValueError:
        return False
    return target_rows(refit.design, targets, grid, confirm=False)[index].met


def format_rows(rows):
    """The rows as lines of text: target, wanted, achieved, miss, tolerance (degrees or the length unit)."""
    lines = []
    for r in rows:
        def text(value, digits=".4f" if r.unit == "deg" else ".6g"):
            value = np.where(np.abs(value) < 5e-13 * max(1.0, float(np.max(np.abs(value)))), 0.0, value)
            return f"{float(value):{digits}}" if np.ndim(value) == 0 else \
                "(" + ", ".join(f"{v:{digits}}" for v in value) + ")"

        unit = " deg" if r.unit == "deg" else ""
        state = "met" if r.met else "MISSED"
        lines.append(f"  {r.name:<24} wanted {text(r.wanted)}{unit}, achieved {text(r.achieved)}{unit}, "
                     f"miss {r.miss:.3g}{unit} (tolerance {r.tolerance:.3g}{unit}): {state}")
    for r in rows:
        if not r.met:
            if r.reach:
                could = f"freeing {', '.join(r.reach)} could reach it"
            elif r.movers:
                could = (f"no parameter held fixed reaches it alone within its bounds; {', '.join(r.movers)} move "
                         "it (free them together, or widen their bounds)")
            else:
                could = "no design parameter moves it"
            lines.append(f"missed: {r.name} by {r.miss:.3g}{' deg' if r.unit == 'deg' else ''}; {could}")
    return lines
