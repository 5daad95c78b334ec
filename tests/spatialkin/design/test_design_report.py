"""How a fit meets its targets (spatialkin.design.report) and what ``spatialkin design`` says and returns when a
target is missed.

Oracles: the reference drive is symmetric about the crank's x-z plane, so its rocker turns at crank angles 0 and
180 deg exactly and no parameter that keeps the symmetry moves them (a timing of 170/350 deg is missed by 170 deg
whatever the symmetric parameters do); a parameter named as reaching a target is checked by a fit of its own with
that parameter freed, and one left out by the same fit failing.
"""
import math

import numpy as np
import pytest

from spatialkin.cli import main
from spatialkin.design import LooperDesign
from spatialkin.design.fit import FIT_SAMPLES, Targets
from spatialkin.design.report import ANGLE_TOLERANCE, target_rows

GRID = np.linspace(0.0, 2 * np.pi, FIT_SAMPLES)
#: The reference drive's turning points (deg): 0 and 180 by its symmetry; agreement of the sampled, Newton-refined
#: turning points with them (deg).
SYMMETRY_TOL = 1e-9

UNREACHABLE = """
[design]
free = ["crank_radius", "rocker_length", "rocker_x", "rocker_z"]
[rocker]
u2_max_at_deg = 170.0
u2_min_at_deg = 350.0
"""


def test_a_timing_the_free_parameters_cannot_reach_is_reported_and_exits_1(tmp_path, capsys):
    path = tmp_path / "targets.toml"
    path.write_text(UNREACHABLE)
    out = tmp_path / "fitted.toml"
    assert main(["design", "--targets", str(path), "--out", str(out)]) == 1
    text = capsys.readouterr().out
    assert out.exists()                                           # the config is written all the same
    lines = {line.split()[0] + " " + line.split()[1]: line for line in text.splitlines() if "wanted" in line}
    for name, wanted, achieved in (("u2 max", 170.0, 0.0), ("u2 min", 350.0, 180.0)):
        line = lines[name]
        assert f"wanted {wanted:.4f} deg" in line and f"achieved {achieved:.4f} deg" in line
        assert "miss 170 deg" in line and line.endswith("MISSED")
    missed = [line for line in text.splitlines() if line.startswith("missed:")]
    assert len(missed) == 2
    for line in missed:        # only the parameters that break the symmetry move the turning points
        movers = line.split("; ")[-1]
        assert {"rocker_y", "rocker_rx", "rocker_rz"} <= set(movers.replace(",", " ").split())
        assert not {"crank_radius", "coupler_length", "rocker_ry", "tip_x"} & set(movers.replace(",", " ").split())


def test_the_reference_timing_by_symmetry():
    rows = target_rows(LooperDesign.reference(), Targets(timing=(math.radians(170), math.radians(350))), GRID,
                       confirm=False)
    assert [r.name for r in rows] == ["u2 max at", "u2 min at"]
    for row, achieved in zip(rows, (0.0, 180.0)):
        assert abs(math.remainder(row.achieved - achieved, 360.0)) < SYMMETRY_TOL
        assert abs(row.miss - 170.0) < SYMMETRY_TOL and not row.met


def test_parameters_named_as_reaching_a_missed_swing_do_reach_it():
    design = LooperDesign.reference(free=["tip_x"])               # the tip does not move the rocker
    targets = Targets(swing=math.radians(45.0))
    fitted = design.fit(targets).design
    row, = target_rows(fitted, targets, GRID)
    assert not row.met and abs(abs(row.achieved - 45.0) - row.miss) < 1e-9
    assert row.reach and set(row.reach) <= set(row.movers)
    assert not {"tip_x", "tip_y", "tip_z"} & set(row.movers)
    for name in row.movers:                                       # the oracle: a fit with it freed
        refit = fitted.fit(targets, free=("tip_x", name)).design
        met = abs(math.degrees(refit.sensitivities(GRID).swing) - 45.0) <= math.degrees(ANGLE_TOLERANCE)
        assert met == (name in row.reach), name


def test_targets_met_exit_0_and_say_so(tmp_path, capsys):
    path = tmp_path / "targets.toml"
    path.write_text('[design]\nfree = ["crank_radius"]\n[rocker]\nswing_deg = 42.0\n')
    assert main(["design", "--targets", str(path), "--out", str(tmp_path / "f.toml")]) == 0
    text = capsys.readouterr().out
    assert "swing" in text and text.count(": met") == 1 and "missed:" not in text


@pytest.mark.parametrize("bound", ["min_transmission_deg", "min_assembly_margin"])
def test_a_bound_that_holds_is_met_with_no_miss(bound):
    value = {"min_transmission_deg": 10.0, "min_assembly_margin": 0.1}[bound]
    targets = Targets.from_dict({"rocker": {"swing_deg": 37.0}, "limits": {bound: value}})
    rows = target_rows(LooperDesign.reference(), targets, GRID, confirm=False)
    assert rows[-1].miss == 0.0 and rows[-1].met


def test_tolerances_set_in_the_targets_file(tmp_path, capsys):
    """[tolerances] angle_deg = 5 with only the tip free (it does not move the rocker): the reference drive's own
    swing, 37.16 deg, meets a 40 deg target (2.84 deg off) and misses a 45 deg one (7.84 deg off)."""
    path = tmp_path / "targets.toml"
    for swing, status in ((40.0, 0), (45.0, 1)):
        path.write_text(f'[design]\nfree = ["tip_x"]\n[rocker]\nswing_deg = {swing}\n[tolerances]\nangle_deg = 5.0\n')
        assert main(["design", "--targets", str(path), "--out", str(tmp_path / "f.toml")]) == status
        assert "(tolerance 5 deg)" in capsys.readouterr().out
    with pytest.raises(ValueError, match="tolerances"):
        Targets.from_dict({"rocker": {"swing_deg": 40.0}, "tolerances": {"angle": 1.0}})
    with pytest.raises(ValueError, match="angle_deg"):
        Targets.from_dict({"rocker": {"swing_deg": 40.0}, "tolerances": {"angle_deg": -1.0}})
