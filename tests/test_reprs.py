"""Every public object prints as something a user can read (its class, its defining numbers), never as
'<... object at 0x...>'; solve() on empty or scalar input behaves as documented."""
import numpy as np
import pytest

import planar
import spatialkin as sk
from spatialkin.mechanisms import LooperDrive
from spatialkin.mechanisms.rssr import RSSR
from spatialkin.render import Scene


@pytest.fixture(scope="module")
def objects():
    drive = LooperDrive.reference()
    motion = drive.solve(np.radians(np.arange(0.0, 360.0, 10.0)))
    rssr = RSSR(8.0, 50.0, 30.0, rocker_frame=sk.Frame((20.0, 0.0, 40.0)))
    mech = planar.examples.fnf_sixbar()
    law = planar.CrankSlider(k=0.5, e=1.0, L=4.0)
    from spatialkin.design import LooperDesign, Targets
    design = LooperDesign.reference(free=("rocker_length",))
    fitted = design.fit(Targets(swing=design.sensitivities(np.linspace(0.0, 2 * np.pi, 91)).swing + 0.01))
    return {"FitResult": fitted, "ToleranceResult": design.tolerance({"crank_radius": 0.01}, samples=20),
            "LooperDrive": drive, "LooperMotion": motion, "LooperAnalysis": drive.analyse(samples=361),
            "PointMotion": motion.looper_tip, "Trajectory": motion.ball, "LinkState": motion.links()["crank"],
            "RSSR": rssr, "RSSRMotion": rssr.solve(np.linspace(0.0, 1.0, 5)), "CrankSlider": law,
            "CrankRocker": planar.CrankRocker(1.0, 2.0), "DrivenLink": planar.DrivenLink(law, omega=2.0),
            "Linkage": mech, "LinkageMotion": mech.solve(np.linspace(0.0, 2 * np.pi, 37)), "Scene": Scene(),
            "Frame": sk.Frame(), "Torus": sk.Torus(8.0, 50.0)}


@pytest.mark.parametrize("name", ["FitResult", "ToleranceResult",
                                  "LooperDrive", "LooperMotion", "LooperAnalysis", "PointMotion", "Trajectory",
                                  "LinkState", "RSSR", "RSSRMotion", "CrankSlider", "CrankRocker", "DrivenLink",
                                  "Linkage", "LinkageMotion", "Scene", "Frame", "Torus"])
def test_repr_is_readable(objects, name):
    text = repr(objects[name])
    assert text.startswith(name) and "object at 0x" not in text and len(text) < 600, text
    assert "\n" not in text and "array(" not in text, text


def test_reprs_carry_the_defining_numbers(objects):
    assert "crank_radius=8" in repr(objects["LooperDrive"]) and "rocker_length=30" in repr(objects["LooperDrive"])
    assert "36 crank angles" in repr(objects["LooperMotion"]) and "branch 0" in repr(objects["LooperMotion"])
    assert repr(objects["DrivenLink"]) == "DrivenLink(CrankSlider(k=0.5, e=1.0, L=4.0, side=1, branch=0), omega=2)"


def test_solve_on_scalar_empty_and_bad_input():
    drive = LooperDrive.reference()
    one, many = drive.solve(0.5), drive.solve([0.5, 1.0])
    assert one.ball_center.shape == (1, 3)
    np.testing.assert_array_equal(one.ball_center[0], many.ball_center[0])     # the same angle, the same numbers
    for bad in ([], np.zeros((0,)), [[0.1, 0.2]]):
        with pytest.raises(ValueError, match="crank_angles"):
            drive.solve(bad)
    for bad in ("x", "1", ["1"]):
        with pytest.raises(TypeError, match="crank_angles must be an array of real numbers"):
            drive.solve(bad)
    for omega, error in (("x", TypeError), (None, TypeError), (0.0, ValueError), (np.nan, ValueError)):
        with pytest.raises(error, match="omega"):
            drive.solve([0.1], omega=omega)
        with pytest.raises(error, match="omega"):
            planar.DrivenLink(planar.CrankRocker(1.0, 2.0), omega=omega)
        with pytest.raises(error, match="omega"):
            planar.examples.fnf_sixbar().solve([0.1], omega=omega)
    with pytest.raises(ValueError, match="crank_angles"):
        planar.examples.fnf_sixbar().solve([])
    link = planar.DrivenLink(planar.CrankSlider(k=0.5, e=1.0, L=4.0))
    assert link.position([], -4.0).shape == (0, 2) and link.position(1.0, -4.0).shape == (2,)   # as numpy
