"""General planar linkages of revolute joints: fixed joints, binary and ternary (or larger) links, one or
more driving cranks geared to one input angle.

The loop-closure equations F(q, phi) = 0 are written in natural coordinates (the moving joints' x, y;
see planar.linkage.kernels), so a class III group (a triad) is solved as one system with no dyad decomposition.
The configuration curve is followed along the input by arc length with spatialkin's continuation pipeline
(solve_ivp with the compiled engine over the jitted right-hand side), each requested input angle is then
solved exactly by Newton from the traced prediction (or, next to an angle solved before it, from that
solution's second-order expansion), and velocities and accelerations come analytically (y', y'' of the
curve, mapped to time by the trajectory pipeline); each crank's share of the velocity is
-J_q^-1 dF/dtheta_k theta_k' (the velocities are linear in the crank rates at a fixed position). The
systems in J_q are solved by block elimination of the explicit joints (crank pins, rigid links' further
joints): one small LU on the joints the distance constraints couple (planar.linkage.kernels).

References
----------
S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian): the
double-crank six-link of the FNF warp-knitting machine, velocity plans by stopping one crank at a time,
superposition (exact: at a fixed position the velocities are linear in the crank rates).
"""
import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from scipy.optimize import least_squares

from spatialkin.continuation import CurveKernels, solve_at, trace_cycle
from spatialkin._lib.validation import (check_angles, check_count, check_omega, check_positive, check_real,
                                        check_vector)

from . import kernels as kn
from .motion import LinkageMotion, LockError

#: Random starts of the assembly search at one input angle (deterministic seed).
ASSEMBLY_STARTS = 200
ASSEMBLY_SEED = 20261121
#: Residual (in units of the linkage's mean length) below which a configuration is assembled.
ASSEMBLY_TOL = 1e-11
#: Two assemblies closer than this (mean length units) are the same.
SAME_ASSEMBLY = 1e-6
#: Newton from a hint may move the joints this far (mean length units) before the hint counts as rough.
HINT_REACH = 0.05
#: Newton at fixed input: residual tolerance (mean length units) and iterations.
NEWTON_TOL = 1e-14
NEWTON_ITER = 30
#: ... or this many ulps of the joints' scaled coordinates, where larger (a linkage far from the origin).
ROUNDOFF_ULPS = 8.0
#: A Newton solution further than this (mean length units) from its traced prediction is another branch.
BRANCH_JUMP = 1e-3
#: A requested input within this much (rad) of the one solved before it (in order along the branch) is
#: predicted by that solution's second-order expansion, error ~ |d3q/dphi3| h^3 / 6: below the traced
#: prediction's for such steps, so that one Newton step reaches round-off.
TAYLOR_REACH = 0.01
#: Largest denominator of a gear ratio (the input period is 2 pi times their least common multiple).
MAX_DENOMINATOR = 64
#: Input angles scanned when the linkage does not assemble at the requested one.
SCAN_ANGLES = 36
#: Integration tolerance of the traced configuration curve: a predictor, each angle is then solved by Newton
#: (from 1e-8 one quadratic step reaches the round-off floor), and where the lock positions are located.
TRACE_RTOL = 1e-8
#: Arc-length budget of one configuration curve, per unit of input period and unknown.
LENGTH_BUDGET = 200.0


def linkage_kernels():
    """A linkage's configuration-curve kernels (read when used: spatialkin._lib.jit may switch their form)."""
    return CurveKernels(kn.linkage_rhs, kn.linkage_events, kn.linkage_advance)


@dataclass(frozen=True)
class Crank:
    """A driving crank: pin = pivot + radius (cos theta, sin theta), theta = phase + ratio * phi.

    phi is the linkage's input angle (crank 1's angle: ratio 1, phase 0), angles in radians. A gear pair z1, z2
    in external mesh gives ratio -z1/z2.

    Parameters
    ----------
    name : str
    pivot, pin : str
        Joint names: the pivot (usually fixed) and the pin.
    radius : float
        Pivot to pin (length), > 0.
    ratio : float
        d theta / d phi, a gear ratio (a fraction with denominator up to 64), non-zero.
    phase : float
        theta at phi = 0 (radians).
    """
    name: str
    pivot: str
    pin: str
    radius: float
    ratio: float = 1.0
    phase: float = 0.0


@dataclass(frozen=True)
class Link:
    """A rigid link through its joints.

    Parameters
    ----------
    name : str
    joints : tuple of str
        Its joints (at least two, distinct).
    shape : array_like, shape (k, 2), optional
        The joints' coordinates in the link's own frame (length).
    length : float, optional
        For a binary link instead of shape: the distance between its two joints.
    """
    name: str
    joints: tuple
    shape: tuple = None
    length: float = None

    def local(self):
        if self.shape is not None:
            return np.asarray(self.shape, dtype=float)
        return np.array([[0.0, 0.0], [float(self.length), 0.0]])


def _block_layout(ci, n):
    """Block structure of J_q for kernels.factor_reduced / solve_reduced: (pattern, slot, rows, cols,
    explicit columns) (see there).

    A crank's pin and a rigid link's further joint are explicit (defined by their constraint's two rows),
    taken in an order where each depends only on implicit and earlier explicit joints; a joint defined twice,
    or on a cycle of definitions, keeps only its first definition or none (its rows then count as implicit)."""
    joints_of, defining = {}, {}
    for kind, row, j0, j1, j2, _ in ci:
        joints = (j0, j1) if kind != kn.RIGID else (j0, j1, j2)
        rows = (row,) if kind == kn.DIST else (row, row + 1)
        for r in rows:
            joints_of[r] = [j for j in joints if j >= 0]
        if kind != kn.DIST:
            target = joints[-1]
            deps = [j for j in joints[:-1] if j >= 0]
            if target not in defining and target not in deps:
                defining[target] = (row, deps)
    order, pending = [], dict(defining)
    while pending:
        ready = [j for j, (_, deps) in pending.items() if all(d not in pending for d in deps)]
        if not ready:                                   # a cycle of definitions: its first joint is implicit
            pending.pop(next(iter(pending)))
            continue
        for j in ready:
            order.append((j, pending.pop(j)[0]))
    erow = [r for _, row in order for r in (row, row + 1)]
    ecol = [c for j, _ in order for c in (2 * j, 2 * j + 1)]
    own = {r: j for j, row in order for r in (row, row + 1)}
    rows = erow + [r for r in range(n) if r not in erow]
    cols = ecol + [c for c in range(n) if c not in ecol]
    pattern = np.full((n, 6), -1, dtype=np.int64)
    for r in range(n):
        coupled = [c for j in joints_of[r] if j != own.get(r) for c in (2 * j, 2 * j + 1)]
        pattern[r, :len(coupled)] = coupled
    slot = np.empty(n, dtype=np.int64)
    slot[cols] = np.arange(n)
    slot[cols[len(ecol):]] = -1 - np.arange(n - len(ecol))
    return pattern, slot, np.array(rows, dtype=np.int64), np.array(cols, dtype=np.int64), len(ecol)


class Linkage:
    """A planar linkage of revolute joints driven by geared cranks.

    The loop-closure equations are written in the moving joints' coordinates, so any group (a dyad, a class III
    triad) is solved as one system; the configuration curve is traced once by arc length and each requested
    input angle solved exactly by Newton (see the module's description).

    Parameters
    ----------
    fixed : dict name -> (x, y)
        Fixed joints (frame pivots), in the user's length unit.
    cranks : list of Crank
        Driving cranks; the first is the input (its ratio must be 1 and phase 0).
    links : list of Link
        The other moving links.
    hint : dict name -> (x, y), optional
        Approximate moving-joint positions at input angle hint_angle: selects the assembly.
    hint_angle : float
        Input angle of the hint (and of the start of the traced configuration curve), radians.

    Attributes
    ----------
    fixed : dict name -> ndarray (2,)
    cranks, links : list
    moving : list of str
        The moving joints, in the order of the state vector.
    joints : list of str
        Fixed then moving joints.
    period : float
        The input's period: 2 pi times the least common multiple of the gear ratios' denominators.

    Raises
    ------
    ValueError
        For no crank, a first crank that is not the input, non-positive radii or lengths, a link with fewer than
        two distinct joints or a bad shape, a ratio that is not a gear ratio, or equations that do not drive the
        linkage to one degree of freedom.

    Examples
    --------
    A four-bar whose crank cannot turn fully (its rocker and coupler line up at about +-90.9 deg):

    >>> import numpy as np
    >>> import planar
    >>> four = planar.Linkage(
    ...     fixed={"O": (0.0, 0.0), "P": (4.0, 0.0)}, cranks=[planar.Crank("1", "O", "A", 2.0)],
    ...     links=[planar.Link("2", ("A", "B"), length=3.0), planar.Link("3", ("P", "B"), length=1.5)],
    ...     hint={"A": (2.0, 0.0), "B": (4.69, 1.33)})
    >>> four.moving
    ['A', 'B']
    >>> np.round(np.degrees(four.lock_positions()), 1).tolist()
    [90.9, -90.9]
    """

    def __init__(self, fixed, cranks, links, hint=None, hint_angle=0.0):
        if not isinstance(fixed, dict):
            raise TypeError(f"fixed must be a dict of joint name -> (x, y), got {type(fixed).__name__}")
        self.fixed = {str(k): check_vector(f"fixed[{k!r}]", v, 2) for k, v in fixed.items()}
        self.cranks = list(cranks)
        self.links = list(links)
        for k, c in enumerate(self.cranks):
            if not isinstance(c, Crank):
                raise TypeError(f"cranks[{k}] must be a planar.Crank, got {type(c).__name__}")
        for k, lk in enumerate(self.links):
            if not isinstance(lk, Link):
                raise TypeError(f"links[{k}] must be a planar.Link, got {type(lk).__name__}")
        if not self.cranks:
            raise ValueError("cranks: a linkage needs at least one driving crank")
        if self.cranks[0].ratio != 1.0 or self.cranks[0].phase != 0.0:
            raise ValueError("cranks: the first crank is the input (ratio 1, phase 0)")
        self.moving = self._moving_joints()
        self.mean_length = float(np.mean([c.radius for c in self.cranks] + [
            np.max(np.linalg.norm(lk.local() - lk.local()[0], axis=1)) for lk in self.links]))
        self.ci, self.cf, self.fixed_xy = self._constraints()
        # Newton's residual to NEWTON_TOL, or to the round-off of joints far from the origin (in mean lengths)
        reach = float(np.max(np.abs(self.fixed_xy))) if self.fixed_xy.size else 0.0
        self.newton_tol = max(NEWTON_TOL, ROUNDOFF_ULPS * np.finfo(float).eps * reach)
        self.layout = _block_layout(self.ci, 2 * len(self.moving))
        self.period = self._period()
        if hint is not None:
            if not isinstance(hint, dict):
                raise TypeError(f"hint must be a dict of joint name -> (x, y), got {type(hint).__name__}")
            missing = [j for j in self.moving if j not in hint]
            unknown = [j for j in hint if j not in self.moving and j not in self.fixed]
            if missing or unknown:
                raise ValueError(f"hint must give every moving joint {self.moving}; missing {missing}, not a joint "
                                 f"{unknown}")
            hint = {k: check_vector(f"hint[{k!r}]", v, 2) for k, v in hint.items()}
        self.hint = hint
        self.hint_angle = check_real("hint_angle", hint_angle, finite=True, strict=True)
        self._cycles = {}

    # --- model -----------------------------------------------------------------------------------
    def _moving_joints(self):
        names = []
        for c in self.cranks:
            check_positive(f"crank {c.name} radius", c.radius)
            if not (math.isfinite(c.ratio) and c.ratio != 0 and math.isfinite(c.phase)):
                raise ValueError(f"crank {c.name}: ratio must be finite and non-zero, phase finite")
            for j in (c.pivot, c.pin):
                if j not in self.fixed and j not in names:
                    names.append(j)
            if c.pin in self.fixed:
                raise ValueError(f"crank {c.name}: its pin {c.pin!r} is a fixed joint")
        for lk in self.links:
            if len(lk.joints) < 2 or len(set(lk.joints)) != len(lk.joints):
                raise ValueError(f"link {lk.name}: needs at least two distinct joints, got {lk.joints}")
            if lk.shape is None:
                if lk.length is None:
                    raise ValueError(f"link {lk.name}: give shape (joint coordinates) or length")
                check_positive(f"link {lk.name} length", lk.length)
            shape = lk.local()
            if shape.shape != (len(lk.joints), 2) or not np.all(np.isfinite(shape)):
                raise ValueError(f"link {lk.name}: shape must be finite ({len(lk.joints)}, 2)")
            check_positive(f"link {lk.name} distance {lk.joints[0]}-{lk.joints[1]}",
                            np.linalg.norm(shape[1] - shape[0]))
            for j in lk.joints:
                if j not in self.fixed and j not in names:
                    names.append(j)
        return names

    def _code(self, joint):
        if joint in self.fixed:
            return -list(self.fixed).index(joint) - 1
        return self.moving.index(joint)

    def _constraints(self):
        ell = self.mean_length
        ci, cf, row = [], [], 0
        for k, c in enumerate(self.cranks):
            ci.append((kn.CRANK, row, self._code(c.pivot), self._code(c.pin), 0, k))
            cf.append((c.radius / ell, c.ratio, c.phase))
            row += 2
        for lk in self.links:
            shape = lk.local()
            e = shape[1] - shape[0]
            ci.append((kn.DIST, row, self._code(lk.joints[0]), self._code(lk.joints[1]), 0, 0))
            cf.append((np.linalg.norm(e) / ell, 0.0, 0.0))
            row += 1
            for j, p in zip(lk.joints[2:], shape[2:]):
                d = p - shape[0]
                a = np.dot(d, e) / np.dot(e, e)
                b = (e[0] * d[1] - e[1] * d[0]) / np.dot(e, e)
                ci.append((kn.RIGID, row, self._code(lk.joints[0]), self._code(lk.joints[1]),
                           self._code(j), 0))
                cf.append((a, b, 0.0))
                row += 2
        unknowns = 2 * len(self.moving)
        if row != unknowns:
            raise ValueError(f"the linkage is not driven to one degree of freedom: {unknowns} joint "
                             f"coordinates but {row} equations (moving joints {self.moving})")
        fixed = np.array(list(self.fixed.values()), dtype=float).reshape(-1, 2) / ell
        return np.array(ci, dtype=np.int64), np.array(cf, dtype=float), fixed

    def _period(self):
        lcm = 1
        for c in self.cranks:
            frac = Fraction(c.ratio).limit_denominator(MAX_DENOMINATOR)
            if abs(float(frac) - c.ratio) > 1e-12 * abs(c.ratio):
                raise ValueError(f"crank {c.name}: ratio {c.ratio} is not a gear ratio (a fraction with "
                                 f"denominator up to {MAX_DENOMINATOR})")
            lcm = math.lcm(lcm, frac.denominator)
        return 2 * math.pi * lcm

    @property
    def joints(self):
        """Every joint's name: the fixed ones, then the moving ones."""
        return list(self.fixed) + self.moving

    def residual(self, state):
        """F (n,) and its Jacobian (n, n+1) at a state (n+1,) in scaled units."""
        n = len(state) - 1
        f, jac = np.empty(n), np.empty((n, n + 1))
        kn.linkage_system(np.asarray(state, float), self.ci, self.cf, self.fixed_xy, f, jac,
                          np.empty((n, len(self.cranks))))
        return f, jac

    def state(self, positions, angle):
        """Scaled state from a dict of moving-joint positions and the input angle."""
        q = np.concatenate([np.asarray(positions[j], float) for j in self.moving]) / self.mean_length
        return np.append(q, angle)

    def positions(self, state):
        """Dict joint -> (x, y) of one scaled state (fixed joints included): the moving joints' scaled (x, y) in
        their order, then the input angle (2 x moving joints + 1 floats); ValueError naming `state` for another
        shape or a value that is not finite, TypeError for what is no array of numbers."""
        state = check_vector("state", state, 2 * len(self.moving) + 1)
        out = {k: v.copy() for k, v in self.fixed.items()}
        q = state[:-1].reshape(-1, 2) * self.mean_length
        out.update({j: q[i] for i, j in enumerate(self.moving)})
        return out

    # --- assembly --------------------------------------------------------------------------------
    def _least_squares(self, q0, angle):
        n = q0.size

        def fun(q):
            return self.residual(np.append(q, angle))[0]

        def jac(q):
            return self.residual(np.append(q, angle))[1][:, :n]
        res = least_squares(fun, q0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
        return res.x, float(np.max(np.abs(res.fun)))

    def assemblies(self, angle):
        """Every assembly found at one input angle: a list of dicts joint -> (x, y), by multi-start
        Levenberg-Marquardt from random joint positions (deterministic)."""
        return [self.positions(s) for s in self._assemblies(float(angle))[0]]

    def _assemblies(self, angle, starts=ASSEMBLY_STARTS, first=False):
        """(distinct assembled states, (worst residual, joints) of the best failed start) from `starts`
        random starts (deterministic); with first=True it stops at the first assembly."""
        rng = np.random.default_rng(ASSEMBLY_SEED)
        centre = np.mean(self.fixed_xy, axis=0) if len(self.fixed_xy) else np.zeros(2)
        reach = np.max(np.linalg.norm(self.fixed_xy - centre, axis=1), initial=0.0) + 3.0
        found, best = [], (np.inf, None)
        for _ in range(starts):
            q0 = (centre + reach * rng.uniform(-1, 1, (len(self.moving), 2))).ravel()
            q, worst = self._least_squares(q0, angle)
            if worst < ASSEMBLY_TOL:
                state = np.append(q, angle)
                if all(np.max(np.abs(state - s)) > SAME_ASSEMBLY for s in found):
                    found.append(state)
                if first:
                    break
            elif worst < best[0]:
                best = (worst, q)
        return found, best

    def assemble(self, angle, assembly=None):
        """Scaled state at an input angle: the assembly nearest the hint (or number `assembly` of
        assemblies(angle))."""
        angle = float(angle)
        if assembly is None and self.hint is not None:
            guess = self.state(self.hint, angle)
            state = self._newton(guess)                  # quick from a close hint ...
            if state is not None:
                return state
            q, worst = self._least_squares(guess[:-1], angle)      # ... robust from a rough one
            if worst < ASSEMBLY_TOL:
                return np.append(q, angle)
        found, best = self._assemblies(angle)
        if not found:
            raise ValueError(self._not_assembled(angle, best[1]))
        if assembly is None:
            if self.hint is None:
                return found[0]
            guess = self.state(self.hint, angle)
            return min(found, key=lambda s: np.linalg.norm(s - guess))
        if not 0 <= assembly < len(found):
            raise ValueError(f"assembly must be in 0..{len(found) - 1} at input angle {angle:.6g} rad, "
                             f"got {assembly!r}")
        return found[assembly]

    def _newton(self, state):
        """Newton at the state's input angle (jitted); the solved state, or None."""
        y = np.array(state, dtype=float)
        status = kn.correct_configuration(y, self.ci, self.cf, self.fixed_xy, self.layout, self.newton_tol, NEWTON_ITER)
        return y if status == 0 and np.max(np.abs(y - state)) < HINT_REACH else None

    def _onto_curve(self, state, steps=4):
        """A traced state corrected onto F = 0 by minimum-norm Gauss-Newton steps (the input free, so a lock
        position stays one)."""
        y = np.array(state, dtype=float)
        args = (self.ci, self.cf, self.fixed_xy, len(self.cranks))
        for _ in range(steps):
            tangent = kn.linkage_rhs(0.0, y, *args, 1.0, 0.0)
            y -= tangent - kn.linkage_rhs(0.0, y, *args, 1.0, 1.0)       # J^+ F
        return y

    def _not_assembled(self, angle, q):
        names = [f"crank {c.name} ({c.pivot}-{c.pin})" for c in self.cranks for _ in (0, 1)]
        for lk in self.links:
            names.append(f"link {lk.name} ({lk.joints[0]}-{lk.joints[1]})")
            names += [f"link {lk.name} joint {j}" for j in lk.joints[2:] for _ in (0, 1)]
        f = self.residual(np.append(q, angle))[0] * self.mean_length
        worst = int(np.argmax(np.abs(f)))
        where = [a for a in np.linspace(0, self.period, SCAN_ANGLES, endpoint=False)
                 if self._assemblies(a, ASSEMBLY_STARTS // 10, first=True)[0]]
        also = (f"; it assembles at input angles such as {math.degrees(where[0]):.4g} deg: its motion is "
                f"limited by lock positions" if where else "; it assembles at none of "
                f"{SCAN_ANGLES} input angles over the period")
        return (f"the linkage cannot be assembled at input angle {math.degrees(angle):.6g} deg: the "
                f"closest configuration found misses {names[worst]} by {abs(f[worst]):.4g}{also}")

    # --- motion ----------------------------------------------------------------------------------
    def __repr__(self):
        links = ", ".join(f"{link.name}({'-'.join(link.joints)})" for link in self.links)
        cranks = ", ".join(f"{c.name}({c.pivot}-{c.pin}, ratio {c.ratio:g})" for c in self.cranks)
        return (f"Linkage(fixed {sorted(self.fixed)}, cranks [{cranks}], links [{links}], "
                f"moving joints {list(self.moving)})")

    def cycle(self, assembly=None):
        """The configuration curve through the chosen assembly at hint_angle (cached): see
        spatialkin.continuation.Cycle."""
        if assembly is not None:
            assembly = check_count("assembly", assembly, minimum=0)
        if assembly not in self._cycles:
            y0 = self.assemble(self.hint_angle, assembly)
            args = (self.ci, self.cf, self.fixed_xy, len(self.cranks))
            budget = LENGTH_BUDGET * self.period * len(y0)
            cycle = trace_cycle(linkage_kernels(), y0, args, self.period, budget, rtol=TRACE_RTOL)
            cycle.locks = [self._onto_curve(y) for y in cycle.locks]
            self._cycles[assembly] = cycle
        return self._cycles[assembly]

    def lock_positions(self, assembly=None):
        """Input angles (rad) where the driven group locks (the Jacobian in the joints is singular and the
        input reverses), in the order met from hint_angle; empty when the input turns fully."""
        return np.array([s[-1] for s in self.cycle(assembly).locks])

    def solve(self, crank_angles, omega=1.0, assembly=None):
        """Positions, velocities and accelerations at the given input angles, the input turning at omega.

        The configuration curve through the assembly is traced once (cached); each angle is solved exactly by
        Newton from its prediction, velocities and accelerations come analytically, and each crank's share of
        the velocity is -J_q^-1 dF/dtheta_k theta_k' (the velocities are linear in the crank rates at a fixed
        position, as the velocity plans of [1]_ use by stopping one crank at a time).

        Parameters
        ----------
        crank_angles : float or array_like, shape (N,)
            Input angles phi (radians; crank 1's angle), any real values.
        omega : float
            Input rate (rad per unit time), finite and non-zero; crank k turns at ratio_k * omega.
        assembly : int, optional
            Number of the assembly in assemblies(hint_angle); default the one nearest the hint.

        Returns
        -------
        LinkageMotion
            ``position(joint)``, ``velocity(joint, crank=None)``, ``acceleration(joint)`` (N, 2) each, in fixed
            axes; link angles, angular velocities and accelerations.

        Raises
        ------
        ValueError
            Naming `crank_angles` (not finite, empty) or `omega` (zero, not finite); a linkage that cannot be
            assembled at hint_angle; a bad `assembly` number.
        LockError
            When a requested angle lies beyond a lock position of the assembly (a subclass of ValueError).

        References
        ----------
        .. [1] S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine",
           Visnyk KNUTD (Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in
           Ukrainian).

        Examples
        --------
        The two cranks' shares of the six-link's velocities add up to the velocity:

        >>> import numpy as np
        >>> import planar
        >>> mech = planar.examples.fnf_sixbar()
        >>> sol = mech.solve(np.radians([0.0, 90.0, 180.0]), omega=1.0)
        >>> sol.position("K").shape
        (3, 2)
        >>> np.allclose(sol.velocity("K", crank=1) + sol.velocity("K", crank=2), sol.velocity("K"))
        True

        Beyond a lock position:

        >>> four = planar.Linkage(
        ...     fixed={"O": (0.0, 0.0), "P": (4.0, 0.0)}, cranks=[planar.Crank("1", "O", "A", 2.0)],
        ...     links=[planar.Link("2", ("A", "B"), length=3.0), planar.Link("3", ("P", "B"), length=1.5)],
        ...     hint={"A": (2.0, 0.0), "B": (4.69, 1.33)})
        >>> four.solve(np.radians([100.0]))
        Traceback (most recent call last):
        ...
        planar.linkage.motion.LockError: the linkage cannot reach input angle(s) 100 deg on this assembly: ...
        """
        angles = check_angles("crank_angles", crank_angles)
        omega = check_omega(omega)
        cycle = self.cycle(assembly)
        inputs, states = cycle.branch_samples()
        order = np.argsort(inputs)

        def locked(mask):
            return LockError(self.lock_positions(assembly), angles[mask])
        ys, d1, d2, parts = solve_at(angles, inputs[order], states[order], self._configurations, index=-1,
                                     period=cycle.period if cycle.full_turn else self.period,
                                     reach=None if cycle.full_turn else 0.0, outside=locked, wrapped=True)
        bad = np.isnan(ys[:, 0])
        if bad.any():
            raise locked(bad)
        ys[:, -1] = angles
        return LinkageMotion(self, ys, float(omega), d1, d2, parts)

    def _configurations(self, guess):
        """(states, y', y'', per-crank parts) by Newton at the fixed inputs of guess (m, n), sorted by input, each
        from the prediction or from the one solved before it within TAYLOR_REACH (solve_at's corrector); the
        rows where Newton fails or jumps to another assembly are NaN."""
        m, n = guess.shape
        ys, d1, d2 = np.empty((m, n)), np.empty((m, n)), np.empty((m, n))
        parts = np.empty((m, len(self.cranks), n - 1))
        status = np.empty(m, dtype=np.int64)
        kn.solve_configurations(guess, np.arange(m), TAYLOR_REACH, BRANCH_JUMP, self.ci, self.cf, self.fixed_xy,
                                self.layout, self.newton_tol, NEWTON_ITER, ys, d1, d2, parts, status)
        bad = (status != 0) | (np.max(np.abs(ys - guess), axis=1) > BRANCH_JUMP)
        ys[bad] = np.nan
        return ys, d1, d2, parts
