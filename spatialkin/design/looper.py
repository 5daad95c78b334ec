"""LooperDesign: a looper drive as a vector of named design parameters with bounds, some of them free."""
import numpy as np

from ..frame import Frame
from ..mechanisms import LooperDrive
from ..validation import check_choice
from .params import (PARAMETERS, angles_from_rotation, check_names, check_values, default_bounds,
                     rotation_from_angles)

#: Crank angles of a full turn sampled by default (0.1 deg steps, both ends).
TURN_SAMPLES = 3601


class LooperDesign:
    """A looper drive's geometry as named design parameters (see spatialkin.design.params).

    Parameters
    ----------
    values : dict
        {name: float} for every name in PARAMETERS (lengths in the user's unit, angles in radians).
    free : sequence of str, optional
        The parameters a fit may move and sensitivities differentiate by; default all.
    bounds : dict, optional
        {name: (low, high)} overriding the default bounds (default_bounds).
    crank_frame : Frame, optional
        The fixed crank frame (default: global axes).
    looper_link : str
        'rocker_arm' or 'rocker_shaft', the link carrying the looper tip.
    branch : int
        Assembly branch (0 or 1).

    Raises
    ------
    ValueError
        Naming the argument: unknown or missing parameters, non-finite values, bounds not around the values.
    """

    def __init__(self, values, free=None, bounds=None, crank_frame=None, looper_link="rocker_arm", branch=0):
        self.values = check_values(values)
        self.free = PARAMETERS if free is None else check_names(free)
        self.bounds = default_bounds(self.values)
        if bounds is not None:
            if not isinstance(bounds, dict):
                raise ValueError(f"bounds must be a dict {{name: (low, high)}}, got {type(bounds).__name__}")
            check_names(tuple(bounds), "bounds")
            for name, pair in bounds.items():
                try:
                    lo, hi = (float(b) for b in pair)
                except (TypeError, ValueError):
                    raise ValueError(f"bounds: {name} must be a pair (low, high), got {pair!r}") from None
                if not lo < hi:
                    raise ValueError(f"bounds: {name} needs low < high, got ({lo}, {hi})")
                self.bounds[name] = (lo, hi)
        self.crank_frame = crank_frame if crank_frame is not None else Frame()
        if not isinstance(self.crank_frame, Frame):
            raise ValueError(f"crank_frame must be a spatialkin.Frame, got {type(crank_frame).__name__}")
        check_choice("looper_link", looper_link, ("rocker_arm", "rocker_shaft"))
        check_choice("branch", branch, (0, 1))
        self.looper_link, self.branch = looper_link, branch
        self._drive = None

    @classmethod
    def from_drive(cls, drive, free=None, bounds=None, branch=0):
        """The design vector of a LooperDrive (its crank frame stays the fixed reference)."""
        if not isinstance(drive, LooperDrive):
            raise ValueError(f"drive must be a LooperDrive, got {type(drive).__name__}")
        rx, ry, rz = angles_from_rotation(drive.rocker_frame.rotation)
        values = dict(crank_radius=drive.crank_radius, coupler_length=drive.coupler_length,
                      rocker_length=drive.rocker_length, rocker_rx=rx, rocker_ry=ry, rocker_rz=rz)
        values.update(zip(("rocker_x", "rocker_y", "rocker_z"), drive.rocker_frame.origin))
        values.update(zip(("tip_x", "tip_y", "tip_z"), drive.looper_tip))
        return cls(values, free, bounds, drive.crank_frame, drive.looper_link, branch)

    @classmethod
    def reference(cls, free=None, bounds=None):
        """The reference drive of ../shared/reference/looper-drive.md (LooperDrive.reference())."""
        return cls.from_drive(LooperDrive.reference(), free, bounds)

    # --- the vector --------------------------------------------------------------------------------
    @property
    def x(self):
        """The free parameters' values (P,)."""
        return np.array([self.values[n] for n in self.free])

    @property
    def lower(self):
        return np.array([self.bounds[n][0] for n in self.free])

    @property
    def upper(self):
        return np.array([self.bounds[n][1] for n in self.free])

    def replace(self, x=None, free=None, **values):
        """A new design: the free parameters set to x (P,) and/or named values changed."""
        new = dict(self.values)
        free = self.free if free is None else check_names(free)
        if x is not None:
            x = np.asarray(x, dtype=float)
            if x.shape != (len(free),):
                raise ValueError(f"x must have shape ({len(free)},) for free={list(free)}, got {x.shape}")
            new.update(zip(free, x.tolist()))
        check_names(tuple(values) or free, "values")
        new.update(values)
        return LooperDesign(new, free, dict(self.bounds), self.crank_frame, self.looper_link, self.branch)

    def with_free(self, free):
        return self.replace(free=free)

    # --- the drive ---------------------------------------------------------------------------------
    @property
    def rocker_rotation(self):
        v = self.values
        return rotation_from_angles(v["rocker_rx"], v["rocker_ry"], v["rocker_rz"])

    def drive(self):
        """The LooperDrive of these values (built once). Raises ValueError if it cannot be assembled."""
        if self._drive is None:
            v = self.values
            rocker = Frame((v["rocker_x"], v["rocker_y"], v["rocker_z"]), self.rocker_rotation)
            self._drive = LooperDrive(v["crank_radius"], v["coupler_length"], v["rocker_length"],
                                      self.crank_frame, rocker, looper_tip=(v["tip_x"], v["tip_y"], v["tip_z"]),
                                      looper_link=self.looper_link)
        return self._drive

    def sensitivities(self, crank_angles=None, omega=1.0, free=None, turning=True):
        """Exact sensitivities of every output at the crank angles (default: a full turn in 0.1 deg steps).
        See spatialkin.design.sensitivity.sensitivities."""
        from .sensitivity import sensitivities
        angles = np.linspace(0.0, 2 * np.pi, TURN_SAMPLES) if crank_angles is None else crank_angles
        return sensitivities(self, angles, omega, None if free is None else check_names(free), turning)

    def dead_positions(self, free=None):
        """The crank's dead positions (K,) (rad) of a drive that cannot turn fully and their exact derivatives
        (K, P); empty when the crank turns fully. See spatialkin.design.sensitivity.dead_positions."""
        from .sensitivity import dead_positions
        return dead_positions(self, None if free is None else check_names(free))

    def fit(self, targets, free=None, **options):
        """Fit the free parameters to targets; see spatialkin.design.fit.fit."""
        from .fit import fit
        return fit(self, targets, free=free, **options)

    def tolerance(self, tolerances, **options):
        """Linear and Monte-Carlo tolerance analysis; see spatialkin.design.tolerance.tolerance."""
        from .tolerance import tolerance
        return tolerance(self, tolerances, **options)

    def to_config(self, **job):
        """The geometry as a config of the main job (spatialkin/looper_job.py: DEFAULTS keys), extra job keys
        (omega, step_deg, ...) passed through."""
        v = self.values
        config = {"crank_radius": v["crank_radius"], "coupler_length": v["coupler_length"],
                  "rocker_length": v["rocker_length"], "branch": self.branch, "looper_link": self.looper_link,
                  "looper_tip": [v["tip_x"], v["tip_y"], v["tip_z"]],
                  "crank_frame": {"origin": self.crank_frame.origin.tolist(),
                                  "rotation": self.crank_frame.rotation.tolist()},
                  "rocker_frame": {"origin": [v["rocker_x"], v["rocker_y"], v["rocker_z"]],
                                   "rotation": self.rocker_rotation.tolist()}}
        config.update(job)
        return config

    def __repr__(self):
        body = ", ".join(f"{n}={self.values[n]:.6g}" for n in PARAMETERS)
        return f"LooperDesign({body}; free={list(self.free)})"




