"""Tolerance analysis: how manufacturing errors in the design parameters move the looper tip's path and the
drive's figures of merit, linear (from the exact sensitivities) and Monte-Carlo, side by side.

Errors are independent, each either normal with the given standard deviation or uniform within +- the given
half-width (standard deviation half-width / sqrt(3)). Linear: the tip's covariance at every crank angle is
J diag(sigma^2) J^T with J = d tip / d p (3 x P), so its RMS deviation is sqrt(trace); a scalar output's
standard deviation is |dY/dp * sigma|. Monte-Carlo: the same errors drawn, each drive solved exactly.
"""
import math
from dataclasses import dataclass, field

import numpy as np

from .._lib.validation import check_choice, check_count, check_positive
from .params import ANGLES, check_names

#: Monte-Carlo samples by default.
MC_SAMPLES = 200
#: Crank angles over the turn by default (1 deg steps, both ends).
TOLERANCE_SAMPLES = 361
#: Scalar outputs compared.
SCALARS = ("swing", "min_transmission", "assembly_margin")
DISTRIBUTIONS = ("normal", "uniform")


@dataclass
class ToleranceResult:
    """Linear and Monte-Carlo tolerance analysis of one design (angles in rad, lengths in the drive's unit).

    Attributes
    ----------
    names : tuple of str (P,)            toleranced parameters
    sigma : (P,)                         their standard deviations
    crank_angles : (N,)
    tip : (N, 3)                         the nominal tip path
    tip_covariance : (N, 3, 3)           linear covariance of the tip at each crank angle
    tip_rms_linear, tip_rms_mc : (N,)    RMS distance of the tip from its nominal position
    tip_rms_by_parameter : (N, P)        the linear RMS from each parameter alone
    draws : (M0, P)                      the Monte-Carlo parameter errors
    mc_ok : (M0,) bool                   which draws could be assembled over the turn
    mc_tips : (M, N, 3)                  the Monte-Carlo tip paths of the draws that could (M = mc_ok.sum())
    scalars : dict                       {output: (nominal, linear std, MC std, linear std by parameter (P,))}
    failed : int                         Monte-Carlo samples that could not be assembled over the turn
    """
    names: tuple
    sigma: np.ndarray
    distribution: str
    crank_angles: np.ndarray
    tip: np.ndarray
    tip_covariance: np.ndarray
    tip_rms_linear: np.ndarray
    tip_rms_mc: np.ndarray
    tip_rms_by_parameter: np.ndarray
    draws: np.ndarray = field(repr=False)
    mc_ok: np.ndarray = field(repr=False)
    mc_tips: np.ndarray = field(repr=False)
    scalars: dict = field(default_factory=dict)
    failed: int = 0

    def __repr__(self):
        runs = f"{len(self.mc_tips)} Monte-Carlo runs" + (f" ({self.failed} not assembled)" if self.failed else "")
        return (f"ToleranceResult({self.distribution}, parameters {list(self.names)}, {len(self.crank_angles)} crank "
                f"angles, {runs}; tip RMS max linear {self.tip_rms_linear.max():.4g}, Monte-Carlo "
                f"{self.tip_rms_mc.max():.4g}; table() for the whole)")

    def table(self):
        """A plain-text table: per parameter the linear contributions, then linear against Monte-Carlo.
        Angles in degrees (marked), lengths in the drive's unit."""
        unit = {"swing": math.degrees(1), "min_transmission": math.degrees(1), "assembly_margin": 1.0}
        label = {"swing": "swing std [deg]", "min_transmission": "min transm. std [deg]",
                 "assembly_margin": "assembly margin std"}
        head = f"{'parameter':<17}{'sigma':>12}{'tip RMS max':>13}" + "".join(f"{label[s]:>23}" for s in SCALARS)
        lines = [head, "-" * len(head)]
        for k, name in enumerate(self.names):
            sigma = f"{math.degrees(self.sigma[k]):.4g} deg" if name in ANGLES else f"{self.sigma[k]:.4g}"
            row = f"{name:<17}{sigma:>12}{self.tip_rms_by_parameter[:, k].max():>13.4g}"
            row += "".join(f"{unit[s] * self.scalars[s][3][k]:>23.4g}" for s in SCALARS)
            lines.append(row)
        lines.append("-" * len(head))
        lin = f"{'all, linear':<17}{'':>12}{self.tip_rms_linear.max():>13.4g}"
        lin += "".join(f"{unit[s] * self.scalars[s][1]:>23.4g}" for s in SCALARS)
        mc = f"{'all, Monte-Carlo':<17}{f'{len(self.mc_tips)} runs':>12}{self.tip_rms_mc.max():>13.4g}"
        mc += "".join(f"{unit[s] * self.scalars[s][2]:>23.4g}" for s in SCALARS)
        lines += [lin, mc]
        if self.failed:
            lines.append(f"{self.failed} Monte-Carlo samples could not be assembled over the turn (left out)")
        return "\n".join(lines)


def tolerance(design, tolerances, distribution="normal", samples=MC_SAMPLES, crank_angles=None, seed=0):
    """Tolerance analysis of a LooperDesign, linear and Monte-Carlo.

    Parameters
    ----------
    design : LooperDesign
    tolerances : dict
        {parameter: standard deviation ('normal') or half-width ('uniform')} (length unit or rad).
    distribution : str
        'normal' or 'uniform'.
    samples : int
        Monte-Carlo samples (0: linear only).
    crank_angles : array_like (N,), optional
        Crank angles over a full turn (default 1 deg steps).
    seed : int
        Seed of the Monte-Carlo draws.

    Returns
    -------
    ToleranceResult
    """
    if not isinstance(tolerances, dict) or not tolerances:
        raise ValueError("tolerances must be a non-empty dict {parameter: tolerance}")
    names = check_names(tuple(tolerances), "tolerances")
    check_choice("distribution", distribution, DISTRIBUTIONS)
    width = np.array([check_positive(f"tolerances: {n}", tolerances[n]) for n in names])
    check_count("samples", samples, 0)
    sigma = width if distribution == "normal" else width / math.sqrt(3.0)
    angles = np.linspace(0.0, 2 * np.pi, TOLERANCE_SAMPLES) if crank_angles is None \
        else np.asarray(crank_angles, dtype=float)
    nominal = design.sensitivities(angles, free=names)
    jac = nominal.d_tip * sigma                                            # (N, 3, P)
    cov = np.einsum("nip,njp->nij", jac, jac)
    rms_linear = np.sqrt(np.trace(cov, axis1=1, axis2=2))
    rms_by = np.linalg.norm(jac, axis=1)                                   # (N, P)
    rng = np.random.default_rng(seed)
    draws = rng.normal(0.0, 1.0, (samples, len(names))) * sigma if distribution == "normal" \
        else rng.uniform(-1.0, 1.0, (samples, len(names))) * width
    tips, values, failed = [], {s: [] for s in SCALARS}, 0
    ok = np.ones(len(draws), dtype=bool)
    from .sensitivity import sensitivities
    for m, row in enumerate(draws):
        try:
            s = sensitivities(design.replace(**{n: design.values[n] + d for n, d in zip(names, row)}), angles,
                              free=())
        except ValueError:
            failed += 1
            ok[m] = False
            continue
        tips.append(s.tip)
        for name in SCALARS:
            values[name].append(getattr(s, name))
    mc_tips = np.array(tips).reshape(-1, len(angles), 3)
    rms_mc = np.sqrt(np.mean(np.sum((mc_tips - nominal.tip) ** 2, axis=2), axis=0)) if len(tips) \
        else np.full(len(angles), np.nan)
    scalars = {}
    for name in SCALARS:
        by = np.abs(getattr(nominal, "d_" + name) * sigma)
        mc = float(np.std(values[name], ddof=1)) if len(values[name]) > 1 else math.nan
        scalars[name] = (float(getattr(nominal, name)), float(np.linalg.norm(by)), mc, by)
    return ToleranceResult(names, sigma, distribution, angles, nominal.tip, cov, rms_linear, rms_mc, rms_by,
                           draws, ok, mc_tips, scalars, failed)
