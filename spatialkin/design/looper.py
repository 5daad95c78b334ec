"""LooperDesign: a looper drive as a vector of named design parameters with bounds, some of them free."""
import numpy as np

from ..geometry.frame import Frame
from ..mechanisms import LooperDrive
from .._lib.validation import TOO_LARGE, check_choice
from .params import (LENGTHS, PARAMETERS, angles_from_rotation, check_names, check_values, default_bounds,
                     rotation_from_angles)

#: Crank angles of a full turn sampled by default (0.1 deg steps, both ends).
TURN_SAMPLES = 3601


class LooperDesign:
    """A looper drive's geometry as named design parameters, some of them free, with bounds.

    The crank frame is the fixed reference; the parameters (spatialkin.design.params.PARAMETERS) are the three
    lengths R1, r1, R2 (crank_radius, coupler_length, rocker_length), the rocker centre (rocker_x, rocker_y,
    rocker_z), the rocker frame's rotation Rz(rocker_rz) Ry(rocker_ry) Rx(rocker_rx) and the looper tip
    (tip_x, tip_y, tip_z). The free ones form the vector ``x`` that fits move and sensitivities differentiate by.

    Parameters
    ----------
    values : dict
        {name: float} for every name in PARAMETERS (lengths in the user's unit, angles in radians).
    free : sequence of str, optional
        The parameters a fit may move and sensitivities differentiate by; default all. Kept in the order of
        PARAMETERS.
    bounds : dict, optional
        {name: (low, high)} overriding the default bounds (default_bounds: lengths within a factor 0.5 to 2,
        positions within half the drive's size, angles within pi/4).
    crank_frame : Frame, optional
        The fixed crank frame (default: global axes).
    looper_link : {'rocker_arm', 'rocker_shaft'}
        The link carrying the looper tip.
    branch : {0, 1}
        Assembly branch.

    Attributes
    ----------
    values : dict
        {name: float}, every parameter.
    free : tuple of str (P,)
    bounds : dict
        {name: (low, high)}.
    x, lower, upper : ndarray, shape (P,)
        The free parameters' values and bounds.

    Raises
    ------
    ValueError
        Naming the argument: unknown or missing parameters, non-finite values, bounds not around the values, a
        crank_frame that is not a Frame, an unknown looper_link or branch.

    See Also
    --------
    spatialkin.mechanisms.LooperDrive : the drive itself (``design.drive()``).

    Examples
    --------
    >>> from spatialkin.design import LooperDesign
    >>> design = LooperDesign.reference(free=("rocker_length", "crank_radius"))
    >>> design.free, design.x.tolist()
    (('crank_radius', 'rocker_length'), [8.0, 30.0])
    >>> longer = design.replace(x=[8.0, 31.0])
    >>> longer.drive().rocker_length
    31.0
    >>> design.replace(x=[8.0])
    Traceback (most recent call last):
    ...
    ValueError: x must have shape (2,) for free=['crank_radius', 'rocker_length'], got (1,)
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
                except OverflowError:
                    raise ValueError(f"bounds: {name} must be finite, got {TOO_LARGE}") from None
                except (TypeError, ValueError):
                    raise ValueError(f"bounds: {name} must be a pair (low, high), got {pair!r}") from None
                if not lo < hi:
                    raise ValueError(f"bounds: {name} needs low < high, got ({lo}, {hi})")
                if name in LENGTHS and not lo > 0.0:
                    raise ValueError(f"bounds: {name} is a length: its low bound must be > 0, got {lo}")
                if not lo <= self.values[name] <= hi:
                    raise ValueError(f"bounds: {name} = {self.values[name]:g} lies outside its bounds ({lo}, {hi})")
                self.bounds[name] = (lo, hi)
        self.crank_frame = crank_frame if crank_frame is not None else Frame()
        if not isinstance(self.crank_frame, Frame):
            raise ValueError(f"crank_frame must be a spatialkin.Frame, got {type(crank_frame).__name__}")
        looper_link = check_choice("looper_link", looper_link, ("rocker_arm", "rocker_shaft"))
        branch = check_choice("branch", branch, (0, 1))
        self.looper_link, self.branch = looper_link, branch
        self._drive = None

    @classmethod
    def from_drive(cls, drive, free=None, bounds=None, branch=0):
        """The design vector of a LooperDrive (its crank frame stays the fixed reference).

        Parameters
        ----------
        drive : LooperDrive
            The drive whose lengths, rocker frame (origin and the angles of its rotation) and looper tip become
            the values.
        free : sequence of str, optional
            Names of the free parameters (default all).
        bounds : dict, optional
            {name: (low, high)} overriding the default bounds.
        branch : {0, 1}
            Assembly branch.

        Returns
        -------
        LooperDesign

        Raises
        ------
        ValueError
            Naming `drive` when it is not a LooperDrive, or `free` / `bounds` for unknown names or bad bounds.

        Examples
        --------
        >>> import numpy as np
        >>> from spatialkin.mechanisms import LooperDrive
        >>> from spatialkin.design import LooperDesign
        >>> drive = LooperDrive.reference()
        >>> design = LooperDesign.from_drive(drive, free=("rocker_length", "crank_radius"))
        >>> design.values["coupler_length"], design.values["rocker_z"]
        (50.0, 75.0)
        >>> np.allclose(design.drive().rocker_frame.rotation, drive.rocker_frame.rotation)
        True
        >>> LooperDesign.from_drive(drive, free=("crank_length",))
        Traceback (most recent call last):
        ...
        ValueError: free: unknown design parameters ['crank_length']; known: [...]
        """
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
        """The design of the reference drive, LooperDrive.reference() (lengths in mm; assumed dimensions)."""
        return cls.from_drive(LooperDrive.reference(), free, bounds)

    # --- the vector --------------------------------------------------------------------------------
    @property
    def x(self):
        """The free parameters' values (P,)."""
        return np.array([self.values[n] for n in self.free])

    @property
    def lower(self):
        """Lower bounds (P,) of the free parameters."""
        return np.array([self.bounds[n][0] for n in self.free])

    @property
    def upper(self):
        """Upper bounds (P,) of the free parameters."""
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
        """The same values with other free parameters."""
        return self.replace(free=free)

    # --- the drive ---------------------------------------------------------------------------------
    @property
    def rocker_rotation(self):
        """The rocker frame's rotation (3, 3), Rz(rocker_rz) Ry(rocker_ry) Rx(rocker_rx)."""
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

        The motion's outputs (ball centre, looper tip, rocker angles with their velocities and accelerations, the
        transmission angle, the rocker's turning points and swing, the assembly margin) and their exact
        derivatives by the free parameters, by the implicit function theorem on the closure torus = sphere in
        Taylor arithmetic [1]_ [2]_ (spatialkin.design.sensitivity.sensitivities).

        Parameters
        ----------
        crank_angles : array_like, shape (N,), optional
            Crank angles (radians). With turning=True they must increase and should sample a full turn; default
            3601 angles over [0, 2 pi].
        omega : float
            Crank rate (rad per unit time): velocities scale with omega, accelerations with omega^2.
        free : sequence of str, optional
            Parameters to differentiate by (P of them); default self.free.
        turning : bool
            Also refine the rocker's turning points and give the swing and the assembly margin.

        Returns
        -------
        Sensitivities
            Every output with its derivative ``d_<output>`` (the output's shape + (P,)); lengths in the drive's
            unit, angles in radians, time in the unit of 1/omega.

        Raises
        ------
        ValueError
            For unknown `free` names; crank angles that do not increase (turning=True); a drive that cannot be
            assembled at the angles (see LooperDrive.solve); Newton failing at a turning point.

        References
        ----------
        .. [1] A. Griewank, A. Walther, Evaluating Derivatives, SIAM, 2008, ch. 13.
        .. [2] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
           machines of the light industry" (in Ukrainian).

        Examples
        --------
        The swing's derivative by the crank radius against a difference quotient:

        >>> import numpy as np
        >>> from spatialkin.design import LooperDesign
        >>> design = LooperDesign.reference(free=("crank_radius",))
        >>> angles = np.linspace(0.0, 2 * np.pi, 361)
        >>> sens = design.sensitivities(angles)
        >>> sens.ball_center.shape, sens.d_ball_center.shape, sens.d_swing.shape
        ((361, 3), (361, 3, 1), (1,))
        >>> h = 1e-6
        >>> moved = design.replace(x=design.x + h).sensitivities(angles)
        >>> bool(abs((moved.swing - sens.swing) / h - sens.d_swing[0]) < 1e-5)
        True
        """
        from .sensitivity import sensitivities
        angles = np.linspace(0.0, 2 * np.pi, TURN_SAMPLES) if crank_angles is None else crank_angles
        return sensitivities(self, angles, omega, None if free is None else check_names(free), turning)

    def dead_positions(self, free=None):
        """The crank's dead positions (K,) (rad) of a drive that cannot turn fully and their exact derivatives
        (K, P); empty when the crank turns fully. See spatialkin.design.sensitivity.dead_positions."""
        from .sensitivity import dead_positions
        return dead_positions(self, None if free is None else check_names(free))

    def fit(self, targets, free=None, **options):
        """Fit the free parameters to targets by scipy.optimize.least_squares with exact Jacobians.

        Within the design's bounds, method 'trf'; the fitted drive assembles over the full turn with a margin
        (see spatialkin.design.fit).

        Parameters
        ----------
        targets : Targets or dict
            Tip points at crank angles, a swing, a timing of the rocker's turning points, bounds on the
            transmission angle and the assembly margin (radians, the drive's length unit); a dict is read by
            Targets.from_dict (the TOML layout, degrees).
        free : sequence of str, optional
            Parameters to fit; default self.free.
        **options
            xtol, ftol, gtol, max_nfev, verbose: passed to least_squares.

        Returns
        -------
        FitResult
            ``design`` (the fitted LooperDesign), ``result`` (scipy's OptimizeResult), ``achieved`` (dict: swing,
            turning points, min_transmission, assembly_margin, cost, tip_points and tip_miss) and ``success``.

        Raises
        ------
        ValueError
            For bad targets or free names, or a start outside its bounds or that cannot be assembled over the
            full turn.

        Examples
        --------
        Widen the rocker's swing by 2 degrees with the crank radius and the rocker length:

        >>> import numpy as np
        >>> from spatialkin.design import LooperDesign, Targets
        >>> design = LooperDesign.reference(free=("crank_radius", "rocker_length"))
        >>> swing = design.sensitivities(np.linspace(0.0, 2 * np.pi, 361)).swing      # rad
        >>> fitted = design.fit(Targets(swing=swing + np.radians(2.0)))
        >>> fitted.success
        True
        >>> round(float(np.degrees(fitted.achieved["swing"] - swing)), 6)
        2.0
        >>> fitted.design.free
        ('crank_radius', 'rocker_length')
        """
        from .fit import fit
        return fit(self, targets, free=free, **options)

    def tolerance(self, tolerances, **options):
        """Linear and Monte-Carlo tolerance analysis; see spatialkin.design.tolerance.tolerance."""
        from .tolerance import tolerance
        return tolerance(self, tolerances, **options)

    def to_config(self, **job):
        """The geometry as a config of the main job (spatialkin/cli/looper_job.py: DEFAULTS keys), extra job keys
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




