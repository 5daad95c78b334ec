"""Synthesis: fit a looper design's free parameters to targets by scipy.optimize.least_squares, with the exact
Jacobians of spatialkin.design.sensitivity.

Targets (all optional, at least one of the first three):
- tip points: the looper tip at given crank angles (residual: the distance components, length);
- swing: the rocker's swing max u2 - min u2 (rad);
- timing: the crank angles at which u2 reaches its maximum and its minimum (the rocker's turning points);
- min_transmission: a lower bound on the transmission angle over the whole turn (rad);
- min_margin: a lower bound on the assembly margin over the whole turn (length): the drive assembles, and so
  turns fully, at every crank angle (a margin above zero rules out dead positions of the crank).
Bounds enter as one-sided quadratic penalties (hinge residuals), active only when violated. A trial geometry
that cannot be assembled over the full turn gives non-finite residuals, which least_squares ('trf') rejects by
shrinking its trust region: so the fit never returns a drive that stops turning (nor one within CLEARANCE of
that).
"""
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from .._lib.validation import as_float_array, check_nonnegative, check_positive, check_real
from .params import check_names

#: Crank angles sampled over a full turn for swing, timing and the transmission angle during a fit.
FIT_SAMPLES = 721
#: Default weights: per length unit of a tip miss, per degree of an angle miss, per degree / length unit of a
#: violated bound.
WEIGHTS = {"tip": 1.0, "swing": 1.0, "timing": 1.0, "transmission": 100.0, "margin": 100.0}
#: Default lower bound on the assembly margin, relative to the drive's size (R1 + r1 + R2).
MARGIN_FRACTION = 0.01
#: A trial geometry whose assembly margin over the turn is below this (relative to the size) is rejected
#: outright, whatever the targets: so close to a dead position the two assembly branches nearly touch, the
#: drive barely turns, and tracing its nearly tangent torus ∩ sphere costs seconds instead of milliseconds.
CLEARANCE = 5e-4
#: Crank angles sampled for that check.
CLEARANCE_SAMPLES = 3600
_DEG = math.pi / 180
#: Tolerances a targets table may set (spatialkin.design.report); in TOML the angle is 'angle_deg'.
TOLERANCES = ("tip", "angle", "margin")


@dataclass
class Targets:
    """What the fitted drive must do. Angles in radians, lengths in the drive's unit.

    Attributes
    ----------
    tip_angles : (K,) crank angles of the tip targets
    tip_points : (K, 3) the looper tip there
    swing : float or None, max u2 - min u2
    timing : (2,) or None, crank angles of the rocker's turning points (u2 max, u2 min)
    min_transmission : float or None, lower bound on the transmission angle over the turn
    min_margin : float or None, lower bound on the assembly margin (default MARGIN_FRACTION x size)
    weights : dict, overriding WEIGHTS (per length unit, per degree)
    tolerances : dict, within which a target counts as met (spatialkin.design.report): 'tip' and 'margin' in the
        length unit, 'angle' in radians; each defaults to report's TIP_TOLERANCE_SHARE x size, ANGLE_TOLERANCE,
        MARGIN_TOLERANCE_SHARE x size
    """
    tip_angles: np.ndarray = field(default_factory=lambda: np.empty(0))
    tip_points: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))
    swing: float = None
    timing: tuple = None
    min_transmission: float = None
    min_margin: float = None
    weights: dict = field(default_factory=dict)
    tolerances: dict = field(default_factory=dict)

    def __post_init__(self):
        self.tip_angles = np.atleast_1d(as_float_array("targets: tip_angles", self.tip_angles))
        points = as_float_array("targets: tip_points", self.tip_points)
        if points.size and points.shape[-1:] != (3,):
            raise ValueError(f"targets: tip_points must have shape (K, 3), got {points.shape}")
        self.tip_points = points.reshape(-1, 3) if points.size else np.empty((0, 3))
        if self.tip_angles.shape != (len(self.tip_points),) or not np.all(np.isfinite(self.tip_points)) \
                or not np.all(np.isfinite(self.tip_angles)):
            raise ValueError("tip targets: tip_angles (K,) and tip_points (K, 3) must be finite and match, got "
                             f"{self.tip_angles.shape} and {self.tip_points.shape}")
        for name in ("min_transmission", "min_margin"):
            if getattr(self, name) is not None:
                setattr(self, name, check_real(f"targets: {name}", getattr(self, name), finite=True, strict=True))
        self.swing = check_positive("targets: swing", self.swing, allow_none=True, strict=True)
        if self.timing is not None:
            t = as_float_array("targets: timing", self.timing)
            if t.shape != (2,) or not np.all(np.isfinite(t)):
                raise ValueError(f"targets: timing must be two finite crank angles (u2 max, u2 min), got "
                                 f"{self.timing!r}")
            self.timing = t
        unknown = set(self.weights) - set(WEIGHTS)
        if unknown:
            raise ValueError(f"targets: unknown weights {sorted(unknown)}; known {sorted(WEIGHTS)}")
        self.weights = {name: check_nonnegative(f"targets: weight {name}", value, strict=True)
                        for name, value in self.weights.items()}
        unknown = set(self.tolerances) - set(TOLERANCES)
        if unknown:
            raise ValueError(f"targets: unknown tolerances {sorted(unknown)}; known {sorted(TOLERANCES)}")
        self.tolerances = {name: check_positive(f"targets: tolerance {name}", value, strict=True)
                           for name, value in self.tolerances.items()}
        if not len(self.tip_angles) and self.swing is None and self.timing is None:
            raise ValueError("targets: give tip points, a swing or a timing to fit to")

    @classmethod
    def from_dict(cls, table):
        """Targets from a dict as read from TOML (angles in degrees):

            [[tip]]                       # any number of tip points
            crank_angle_deg = 60.0
            point = [40.0, 10.0, 80.0]
            [rocker]
            swing_deg = 40.0              # optional
            u2_max_at_deg = 180.0         # optional, both or neither
            u2_min_at_deg = 0.0
            [limits]
            min_transmission_deg = 50.0   # optional
            min_assembly_margin = 0.5     # optional (length)
            [weights]                     # optional: tip, swing, timing, transmission, margin
            [tolerances]                  # optional: tip (length), angle_deg, margin (length)
        """
        if not isinstance(table, dict):
            raise ValueError(f"targets must be a table, got {type(table).__name__}")
        unknown = set(table) - {"tip", "rocker", "limits", "weights", "tolerances"}
        if unknown:
            raise ValueError(f"targets: unknown keys {sorted(unknown)}; allowed tip, rocker, limits, weights")
        tips = table.get("tip", [])
        try:
            angles = [float(t["crank_angle_deg"]) * _DEG for t in tips]
            points = [list(map(float, t["point"])) for t in tips]
        except (KeyError, TypeError, ValueError) as err:
            raise ValueError(f"targets: every [[tip]] needs crank_angle_deg and point = [x, y, z] ({err})") from None
        rocker, limits = table.get("rocker", {}), table.get("limits", {})
        for name, t, keys in (("rocker", rocker, {"swing_deg", "u2_max_at_deg", "u2_min_at_deg"}),
                              ("limits", limits, {"min_transmission_deg", "min_assembly_margin"})):
            bad = set(t) - keys
            if bad:
                raise ValueError(f"targets: [{name}] has unknown keys {sorted(bad)}; allowed {sorted(keys)}")
        timing = None
        if ("u2_max_at_deg" in rocker) != ("u2_min_at_deg" in rocker):
            raise ValueError("targets: [rocker] needs both u2_max_at_deg and u2_min_at_deg, or neither")
        if "u2_max_at_deg" in rocker:
            timing = (float(rocker["u2_max_at_deg"]) * _DEG, float(rocker["u2_min_at_deg"]) * _DEG)
        swing = rocker.get("swing_deg")
        mu = limits.get("min_transmission_deg")
        return cls(np.array(angles), np.array(points).reshape(-1, 3),
                   swing=None if swing is None else float(swing) * _DEG, timing=timing,
                   min_transmission=None if mu is None else float(mu) * _DEG,
                   min_margin=limits.get("min_assembly_margin"), weights=dict(table.get("weights", {})),
                   tolerances=tolerances_from(table.get("tolerances", {})))


def tolerances_from(table):
    """The tolerances of a TOML [tolerances] table ('angle_deg' in degrees) in Targets' units."""
    if not isinstance(table, dict):
        raise ValueError(f"targets: [tolerances] must be a table, got {type(table).__name__}")
    keys = {"tip", "angle_deg", "margin"}
    if set(table) - keys:
        raise ValueError(f"targets: [tolerances] has unknown keys {sorted(set(table) - keys)}; allowed {sorted(keys)}")
    out = {k: table[k] for k in ("tip", "margin") if k in table}
    if "angle_deg" in table:
        out["angle"] = check_positive("targets: tolerance angle_deg", table["angle_deg"]) * _DEG
    return out


@dataclass
class FitResult:
    """A fit's outcome: the fitted design, scipy's OptimizeResult, and what the fitted drive achieves."""
    design: object
    result: object
    achieved: dict

    @property
    def success(self):
        return bool(self.result.success)

    def __repr__(self):
        got = self.achieved
        parts = [f"swing {math.degrees(got['swing']):.6g} deg",
                 f"min transmission {math.degrees(got['min_transmission']):.6g} deg",
                 f"assembly margin {got['assembly_margin']:.6g}"]
        if "tip_miss" in got:
            parts.append(f"tip miss {got['tip_miss']:.3g}")
        return (f"FitResult(success={self.success}, cost={got['cost']:.3g}, evaluations={self.result.nfev}; "
                f"{', '.join(parts)}; {self.design!r})")


class _Problem:
    """Residuals and their Jacobian for least_squares, sharing one evaluation per x."""

    def __init__(self, design, targets, free):
        self.design, self.targets, self.free = design, targets, free
        w = dict(WEIGHTS, **targets.weights)
        self.w = w
        size = sum(design.values[n] for n in ("crank_radius", "coupler_length", "rocker_length"))
        self.min_margin = MARGIN_FRACTION * size if targets.min_margin is None else float(targets.min_margin)
        self.grid = np.linspace(0.0, 2 * np.pi, FIT_SAMPLES)
        self._key, self._value = None, None
        self.m = 3 * len(targets.tip_angles) + (targets.swing is not None) + 2 * (targets.timing is not None) \
            + (targets.min_transmission is not None) + 1

    def evaluate(self, x):
        key = np.asarray(x, dtype=float).tobytes()
        if key != self._key:
            self._key = key
            try:
                trial = self.design.replace(x, free=self.free)
                self._check_clearance(trial)
                self._value = self._residuals(trial)
            except ValueError:        # cannot be assembled over the full turn, or a branch point: rejected
                self._value = (np.full(self.m, np.nan), np.full((self.m, len(self.free)), np.nan), None)
        return self._value

    @staticmethod
    def _check_clearance(design):
        drive = design.drive()
        grid = np.linspace(0.0, 2 * np.pi, CLEARANCE_SAMPLES, endpoint=False)
        if np.min(drive.assembly_margin(grid)) < CLEARANCE * drive.size:
            raise ValueError("the drive is within CLEARANCE of a dead position")

    def _residuals(self, design):
        t, w = self.targets, self.w
        turn = design.sensitivities(self.grid)
        rows, jac = [], []
        if len(t.tip_angles):
            tips = design.sensitivities(t.tip_angles, turning=False)
            rows.append(w["tip"] * (tips.tip - t.tip_points).ravel())
            jac.append(w["tip"] * tips.d_tip.reshape(-1, len(self.free)))
        per_deg = 1 / _DEG
        if t.swing is not None:
            rows.append([w["swing"] * per_deg * (turn.swing - t.swing)])
            jac.append(w["swing"] * per_deg * turn.d_swing[None])
        if t.timing is not None:
            if len(turn.turning_points) < 2:
                raise ValueError("the rocker has no turning points")
            u2 = turn.turning_u2
            for k, target in zip((int(np.argmax(u2)), int(np.argmin(u2))), t.timing):
                miss = math.remainder(turn.turning_points[k] - target, 2 * math.pi)
                rows.append([w["timing"] * per_deg * miss])
                jac.append(w["timing"] * per_deg * turn.d_turning_points[k][None])
        if t.min_transmission is not None:
            short = t.min_transmission - turn.min_transmission
            active = short > 0
            rows.append([w["transmission"] * per_deg * short * active])
            jac.append(-w["transmission"] * per_deg * turn.d_min_transmission[None] * active)
        short = self.min_margin - turn.assembly_margin
        active = short > 0
        rows.append([w["margin"] * short * active])
        jac.append(-w["margin"] * turn.d_assembly_margin[None] * active)
        return np.concatenate([np.ravel(r) for r in rows]), np.vstack(jac), (design, turn)

    def fun(self, x):
        return self.evaluate(x)[0]

    def jac(self, x):
        return self.evaluate(x)[1]


def fit(design, targets, free=None, xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=200, verbose=0):
    """Fit the free parameters of a LooperDesign to targets (scipy.optimize.least_squares, method 'trf',
    within the design's bounds, exact Jacobians).

    Parameters
    ----------
    design : LooperDesign
        The start; its values of the parameters not free stay fixed.
    targets : Targets or dict
        A dict is read by Targets.from_dict (TOML layout, degrees).
    free : sequence of str, optional
        Parameters to fit; default design.free.
    xtol, ftol, gtol, max_nfev, verbose
        Passed to least_squares.

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        For bad targets or free names, or a start that cannot be assembled over the full turn.
    """
    if isinstance(targets, dict):
        targets = Targets.from_dict(targets)
    if not isinstance(targets, Targets):
        raise ValueError(f"targets must be Targets or a dict, got {type(targets).__name__}")
    free = design.free if free is None else check_names(free)
    design = design.replace(free=free)
    problem = _Problem(design, targets, free)
    x0 = design.x
    lo, hi = design.lower, design.upper
    if np.any(x0 < lo) or np.any(x0 > hi):
        raise ValueError("design: the start lies outside its bounds")
    first = problem.evaluate(x0)
    if first[2] is None:
        raise ValueError("design: the start cannot be assembled over a full crank turn on its branch")
    result = least_squares(problem.fun, x0, jac=problem.jac, bounds=(lo, hi), method="trf", x_scale="jac",
                           xtol=xtol, ftol=ftol, gtol=gtol, max_nfev=max_nfev, verbose=verbose)
    fitted, turn = problem.evaluate(result.x)[2]
    achieved = {"swing": turn.swing, "turning_points": turn.turning_points, "turning_u2": turn.turning_u2,
                "min_transmission": turn.min_transmission, "assembly_margin": turn.assembly_margin,
                "cost": float(result.cost)}
    if len(targets.tip_angles):
        tips = fitted.sensitivities(targets.tip_angles, turning=False).tip
        achieved["tip_points"] = tips
        achieved["tip_miss"] = float(np.max(np.linalg.norm(tips - targets.tip_points, axis=1)))
    return FitResult(fitted, result, achieved)
