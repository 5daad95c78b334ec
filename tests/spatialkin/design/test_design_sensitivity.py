"""Exact sensitivities (implicit function theorem in Taylor arithmetic) against central differences, and the
outputs against the LooperDrive's own solver and analysis."""
import numpy as np
import pytest

from spatialkin.design import PARAMETERS, LooperDesign
from spatialkin.design.jet import Jet, atan2
from spatialkin.mechanisms import LooperDrive

#: Central-difference step (relative to each parameter's scale: lengths in mm, angles in rad).
FD_STEP = 1e-6
#: Agreement of exact and central-difference derivatives, relative to the largest derivative of that
#: output: FD truncation (h^2 f''') plus round-off (eps |f| / h with Newton at 1e-14 x size) is below 1e-7.
FD_TOL = 1e-6
#: Crank angles of the tests (1 deg steps over a full turn).
ANGLES = np.linspace(0.0, 2 * np.pi, 361)


@pytest.fixture(scope="module")
def design():
    """The reference drive moved out of its mirror symmetry (so turning points and minima are simple)."""
    return LooperDesign.reference().replace(rocker_y=2.0, rocker_rz=0.05, rocker_ry=0.03)


@pytest.fixture(scope="module")
def exact(design):
    return design.sensitivities(ANGLES, omega=2.0)


@pytest.fixture(scope="module")
def central(design):
    """Central differences of every output, one parameter at a time: {name: (P, ...)}."""
    out = {}
    for name in PARAMETERS:
        plus = design.replace(**{name: design.values[name] + FD_STEP}).sensitivities(ANGLES, omega=2.0)
        minus = design.replace(**{name: design.values[name] - FD_STEP}).sensitivities(ANGLES, omega=2.0)
        for field in ("ball_center", "ball_velocity", "ball_acceleration", "tip", "tip_velocity",
                      "tip_acceleration", "rocker_angles", "rocker_rates", "rocker_accelerations",
                      "transmission_angle", "min_transmission", "swing", "turning_points", "turning_u2",
                      "assembly_margin"):
            diff = np.asarray(getattr(plus, field)) - np.asarray(getattr(minus, field))
            if field == "turning_points":
                diff = np.mod(diff + np.pi, 2 * np.pi) - np.pi
            out.setdefault(field, []).append(diff / (2 * FD_STEP))
    return {k: np.moveaxis(np.array(v), 0, -1) for k, v in out.items()}


def test_outputs_match_the_drive(design, exact):
    """Values from the jets equal the drive's own motion (1e-12 relative) and analysis."""
    motion = design.drive().solve(ANGLES, omega=2.0)
    tip = motion.looper_tip
    for ours, theirs in ((exact.ball_center, motion.ball_center), (exact.ball_velocity, motion.ball_velocity),
                         (exact.ball_acceleration, motion.ball_acceleration), (exact.tip, tip.position),
                         (exact.tip_velocity, tip.velocity), (exact.tip_acceleration, tip.acceleration),
                         (exact.rocker_rates, motion.rocker_rates),
                         (exact.rocker_accelerations, motion.rocker_accelerations)):
        assert np.max(np.abs(ours - theirs)) <= 1e-12 * np.max(np.abs(theirs))
    analysis = design.drive().analyse(samples=361)
    assert abs(exact.min_transmission - analysis.min_transmission[0]) < 1e-12
    assert np.allclose(exact.transmission_angle, analysis.transmission_angle, atol=1e-12)
    u2_lo, u2_hi = analysis.u2_range               # sampled at 1 deg: the refined swing is at least as wide
    assert 0 <= exact.swing - (u2_hi - u2_lo) < 1e-4
    assert exact.assembly_margin > 0


@pytest.mark.parametrize("field", ["ball_center", "ball_velocity", "ball_acceleration", "tip", "tip_velocity",
                                   "tip_acceleration", "rocker_angles", "rocker_rates", "rocker_accelerations",
                                   "transmission_angle", "min_transmission", "swing", "turning_points",
                                   "turning_u2", "assembly_margin"])
def test_sensitivities_match_central_differences(exact, central, field):
    ours, fd = exact.jacobian(field), central[field]
    assert ours.shape == fd.shape
    if field == "transmission_angle":   # |.| in the angle: not differentiable where it is 90 deg
        keep = exact.transmission_angle < np.radians(89.0)
        ours, fd = ours[keep], fd[keep]
    scale = max(np.max(np.abs(fd)), 1e-300)
    assert np.max(np.abs(ours - fd)) <= FD_TOL * scale


def test_subset_of_free_parameters(design, exact):
    sub = design.sensitivities(ANGLES, omega=2.0, free=("rocker_length", "tip_z"), turning=False)
    cols = [PARAMETERS.index("rocker_length"), PARAMETERS.index("tip_z")]
    assert sub.free == ("rocker_length", "tip_z")
    assert np.allclose(sub.d_tip_acceleration, exact.d_tip_acceleration[..., cols], rtol=0, atol=1e-12)


def test_jet_functions_against_closed_forms():
    """sin, sqrt, 1/x and atan2 of a jet: value, d/dt, d2/dt2 and d/deps against closed forms (1e-13)."""
    x = Jet.variable(np.array([0.3, 1.7]), 3, 1, param=1, t=True)      # x = x0 + t + eps
    x0 = x.value
    for jet, f, f1, f2 in ((x.sin(), np.sin(x0), np.cos(x0), -np.sin(x0)),
                           (x.sqrt(), np.sqrt(x0), 0.5 / np.sqrt(x0), -0.25 * x0 ** -1.5),
                           (1.0 / x, 1 / x0, -1 / x0 ** 2, 2 / x0 ** 3),
                           (atan2(x, 2.0 + 0 * x), np.arctan2(x0, 2), 2 / (4 + x0 ** 2), -4 * x0 / (4 + x0 ** 2) ** 2)):
        assert np.allclose([jet.d_du(0), jet.d_du(1), jet.d_du(2), jet.d_dp(0)[:, 0], jet.d_dp(1)[:, 0]],
                           [f, f1, f2, f1, f2], rtol=1e-13, atol=1e-13)


def test_from_drive_round_trip():
    drive = LooperDrive.reference()
    design = LooperDesign.from_drive(drive)
    again = design.drive()
    assert np.allclose(again.rocker_frame.rotation, drive.rocker_frame.rotation, atol=1e-15)
    assert np.allclose(again.rocker_frame.origin, drive.rocker_frame.origin)


@pytest.mark.parametrize("kwargs, word", [(dict(free=("crank", )), "free"), (dict(free=()), "free"),
                                          (dict(bounds={"crank_radius": (3, 2)}), "bounds"),
                                          (dict(bounds={"crank_radius": (0, 10 ** 400)}),
                                           "bounds: crank_radius must be finite, got an integer too large"),
                                          (dict(bounds={"crank_radius": (20.0, 30.0)}),
                                           "crank_radius = 8 lies outside its bounds"),
                                          (dict(bounds={"crank_radius": (-1.0, 30.0)}),
                                           "crank_radius is a length: its low bound must be > 0"),
                                          (dict(branch=2), "branch"), (dict(branch=True), "branch")])
def test_bad_input_names_the_argument(kwargs, word):
    with pytest.raises(ValueError, match=word):
        LooperDesign(LooperDesign.reference().values, **kwargs)
    with pytest.raises(ValueError, match="values"):
        LooperDesign({**LooperDesign.reference().values, "crank_radius": -1.0})


def test_dead_positions_of_a_crank_that_cannot_turn_fully(design):
    """A rocker 25.5 long: the crank rocks between two dead positions; their derivatives against central
    differences (1e-6 relative) and against the drive's own blocked range (same angles, 1e-12)."""
    short = design.replace(rocker_length=25.5)
    angles, d_angles = short.dead_positions()
    (lo, hi), = short.drive().blocked_ranges
    assert np.allclose(angles, [lo, hi], atol=1e-12)
    assert design.dead_positions()[0].shape == (0,)
    for k, name in enumerate(PARAMETERS):
        plus = short.replace(**{name: short.values[name] + FD_STEP}).dead_positions()[0]
        minus = short.replace(**{name: short.values[name] - FD_STEP}).dead_positions()[0]
        fd = (plus - minus) / (2 * FD_STEP)
        assert np.max(np.abs(fd - d_angles[:, k])) <= FD_TOL * max(1.0, np.max(np.abs(d_angles)))


def test_tilted_crank_frame_and_shaft_link():
    """A crank frame turned and moved, the looper on the rocker shaft: values equal the drive's (1e-12
    relative) and one derivative equals its central difference (1e-6 relative)."""
    import spatialkin as sk
    crank = sk.Frame((1.0, -2.0, 0.5), sk.rotation_about((1, 1, 0), 0.2))
    drive = LooperDrive(8.0, 50.0, 30.0, crank, sk.Frame((6.0, 0.0, 75.0), sk.rotation_about((1, 0, 0), -1.5)),
                        looper_tip=(30.0, 5.0, 10.0), looper_link="rocker_shaft")
    design = LooperDesign.from_drive(drive, free=("rocker_rx", "tip_y"))
    s = design.sensitivities(ANGLES, turning=False)
    tip = drive.solve(ANGLES).looper_tip
    for ours, theirs in ((s.tip, tip.position), (s.tip_velocity, tip.velocity),
                         (s.tip_acceleration, tip.acceleration)):
        assert np.max(np.abs(ours - theirs)) <= 1e-12 * np.max(np.abs(theirs))
    rx = design.values["rocker_rx"]
    plus = design.replace(rocker_rx=rx + FD_STEP).sensitivities(ANGLES, turning=False)
    minus = design.replace(rocker_rx=rx - FD_STEP).sensitivities(ANGLES, turning=False)
    fd = (plus.tip_acceleration - minus.tip_acceleration) / (2 * FD_STEP)
    assert np.max(np.abs(fd - s.d_tip_acceleration[..., 0])) <= FD_TOL * np.max(np.abs(fd))


def test_turning_points_need_increasing_angles(design):
    with pytest.raises(ValueError, match="crank_angles"):
        design.sensitivities(ANGLES[::-1])
    design.sensitivities(ANGLES[::-1][:5], turning=False)


def test_turning_point_right_on_a_sample_is_found():
    """A fit to target timings puts a turning point exactly on a sampled crank angle (u2' = 0.0 there); the swing
    still comes from both turning points and matches an independent fine solve of the drive (1e-9 rad)."""
    import math
    from spatialkin.design import LooperDesign, Targets
    from spatialkin.design.sensitivity import sensitivities
    design = LooperDesign.reference(free=("crank_radius", "rocker_length", "rocker_y", "rocker_rz"))
    fitted = design.fit(Targets(swing=math.radians(40.0), timing=np.radians([5.0, 185.0])))
    d = fitted.design.replace(crank_radius=8.0, rocker_length=31.0)
    turn = sensitivities(d, np.linspace(0.0, 2 * np.pi, 361), free=(), turning=True)
    assert len(turn.turning_points) == 2
    motion = d.drive().solve(np.radians(np.arange(0.0, 360.0001, 0.01)))
    u2 = motion.rocker_angles[:, 0]
    assert abs(turn.swing - (u2.max() - u2.min())) < 1e-9
