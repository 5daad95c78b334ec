"""Synthesis: recover a known geometry from its own outputs, from a perturbed start; bounds hold."""
import math

import numpy as np
import pytest

from spatialkin.design import LooperDesign
from spatialkin.design.fit import Targets

#: A recovered parameter lies this close (length units, rad) to the known geometry's.
RECOVERY_TOL = 1e-8


@pytest.fixture(scope="module")
def true():
    return LooperDesign.reference().replace(rocker_y=2.0, rocker_rz=0.05, rocker_ry=0.03)


def test_recover_geometry_from_tip_points(true):
    angles = np.radians(np.arange(0.0, 360.0, 45.0))
    tips = true.sensitivities(angles, turning=False).tip
    free = ("crank_radius", "coupler_length", "rocker_length", "rocker_x", "rocker_z", "tip_x", "tip_z")
    start = true.replace(crank_radius=8.4, coupler_length=49.0, rocker_length=31.0, rocker_x=6.5, rocker_z=74.0,
                         tip_x=38.0, tip_z=13.0)
    fitted = start.fit(Targets(angles, tips), free=free)
    assert fitted.success
    for name in free:
        assert abs(fitted.design.values[name] - true.values[name]) < RECOVERY_TOL, name
    assert fitted.achieved["tip_miss"] < 1e-9


def test_recover_swing_and_timing(true):
    turn = true.sensitivities(np.linspace(0, 2 * np.pi, 721))
    u2 = turn.turning_u2
    timing = turn.turning_points[[np.argmax(u2), np.argmin(u2)]]
    start = true.replace(crank_radius=8.5, rocker_y=0.5, rocker_rz=0.0)
    fitted = start.fit({"rocker": {"swing_deg": math.degrees(turn.swing), "u2_max_at_deg": math.degrees(timing[0]),
                                   "u2_min_at_deg": math.degrees(timing[1])},
                        "limits": {"min_transmission_deg": 60.0}}, free=("crank_radius", "rocker_y", "rocker_rz"))
    for name in ("crank_radius", "rocker_y", "rocker_rz"):
        assert abs(fitted.design.values[name] - true.values[name]) < RECOVERY_TOL, name
    assert abs(fitted.achieved["swing"] - turn.swing) < 1e-10


def test_bounds_on_transmission_and_assembly_hold(true):
    """A wider swing is wanted while the transmission angle stays above 68 deg and the assembly margin above
    3.0: the fit trades the swing for the bounds (quadratic penalties: violated by at most 0.05 deg / 0.01)."""
    base = true.sensitivities(np.linspace(0, 2 * np.pi, 721))
    fitted = true.fit(Targets(swing=base.swing + math.radians(15), min_transmission=math.radians(68.0),
                              min_margin=3.0), free=("crank_radius", "rocker_length"))
    assert fitted.achieved["min_transmission"] > math.radians(68.0 - 0.05)
    assert fitted.achieved["assembly_margin"] > 3.0 - 0.01
    assert fitted.achieved["swing"] > base.swing          # it moved towards the target
    fitted.design.drive().solve(np.linspace(0, 2 * np.pi, 361))      # and still turns fully


@pytest.mark.parametrize("targets, word", [({}, "targets"), ({"tip": [{"point": [1, 2, 3]}]}, "tip"),
                                           ({"rocker": {"swing_deg": 30, "u2_max_at_deg": 3}}, "u2_min_at_deg"),
                                           ({"rocker": {"swings": 3}}, "rocker"),
                                           ({"rocker": {"swing_deg": -3}}, "swing")])
def test_bad_targets_name_the_argument(true, targets, word):
    with pytest.raises(ValueError, match=word):
        true.fit(targets, free=("crank_radius",))


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(swing="0.5"), TypeError, "targets: swing must be a real number"),
    (dict(swing=0.5, min_transmission="1.2"), TypeError, "targets: min_transmission must be a real number"),
    (dict(swing=0.5, weights={"swing": "x"}), TypeError, "targets: weight swing must be a real number"),
    (dict(swing=0.5, weights={"swing": None}), TypeError, "targets: weight swing must be a real number"),
    (dict(swing=0.5, weights={"swing": math.nan}), ValueError, "targets: weight swing must be a finite number"),
    (dict(tip_angles=[0.0], tip_points=[[1.0, 2.0]]), ValueError, r"tip_points must have shape \(K, 3\)"),
])
def test_targets_check_their_values_when_made(kwargs, error, words):
    """A target, weight or tolerance of no real type, or not finite, is refused when the Targets are made, naming
    it (they were stored raw and failed inside the fit); valid numbers are kept as floats."""
    with pytest.raises(error, match=words):
        Targets(**kwargs)
    kept = Targets(swing=np.float32(0.5), weights={"swing": 2})
    assert type(kept.swing) is float and kept.weights == {"swing": 2.0}


@pytest.mark.parametrize("min_margin", [None, 0.0])
def test_fit_never_ends_on_a_drive_that_stops_turning(min_margin):
    """A 5 deg swing asks for a rocker so short that the crank could not turn fully (below about 26.3 mm):
    the fit stops at the edge, on a drive that still assembles at every crank angle: with the default margin
    bound (1 % of the size = 0.88, held to 0.05), or else no closer than the fit's CLEARANCE."""
    from spatialkin.design.fit import CLEARANCE
    design = LooperDesign.reference()
    fitted = design.fit(Targets(swing=math.radians(5.0), min_margin=min_margin), free=("rocker_length",))
    assert fitted.design.drive().blocked_ranges == []
    size = fitted.design.drive().size
    assert fitted.achieved["assembly_margin"] >= (CLEARANCE * size if min_margin == 0.0 else 0.88 - 0.05)
    assert fitted.achieved["swing"] < math.radians(37.0)
