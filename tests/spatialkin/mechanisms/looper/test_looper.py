"""The looper drive against the closed form per crank angle (A cos v1 + B sin v1 + C = 0), its finite
differences, and the rigid-chain identities.

The reference geometry is assumed (the paper, "Investigation of the trajectories of characteristic points of spatial
mechanisms of technological machines of the light industry" (in Ukrainian; [Looper]), gives no dimensions); its swing
and branches were measured by an independent script.
"""
import os

import numpy as np
import pytest
from tests.oracles.closed_forms import looper_closed_form

import spatialkin as sk
from spatialkin.mechanisms.looper import reference
from spatialkin.mechanisms import LooperDrive


def five_point(f, x, h):
    """First and second derivatives by the 5-point stencils (errors O(h^4))."""
    fm2, fm1, fp1, fp2 = f(x - 2 * h), f(x - h), f(x + h), f(x + 2 * h)
    f0 = f(x)
    d1 = (fm2 - 8 * fm1 + 8 * fp1 - fp2) / (12 * h)
    d2 = (-fm2 + 16 * fm1 - 30 * f0 + 16 * fp1 - fp2) / (12 * h * h)
    return d1, d2


@pytest.fixture(scope="module")
def drive():
    return LooperDrive.reference()


@pytest.mark.parametrize("branch", [0, 1])
def test_full_turn_matches_closed_form(drive, branch):
    """Done-criterion: over a full turn, positions to 1e-9 mm, velocities and accelerations to 1e-8
    (relative to their largest magnitude) against the closed form and its 5-point differences."""
    omega = 3.0
    u1 = np.linspace(0.0, 2 * np.pi, 721)
    m = drive.solve(u1, omega=omega, branch=branch)
    np.testing.assert_array_equal(m.crank_angle, u1)
    v1, c = looper_closed_form(drive, u1, branch)
    assert np.max(np.abs(m.ball_center - c)) < 1e-9
    assert np.max(np.abs(np.angle(np.exp(1j * (m.coupler_angle - v1))))) < 1e-11
    # time derivatives: d/dt = omega d/du1
    d1, d2 = five_point(lambda x: looper_closed_form(drive, x, branch)[1], u1, 3e-3)   # FD error ~1e-9 relative
    vel, acc = omega * d1, omega ** 2 * d2
    assert np.max(np.abs(m.ball_velocity - vel)) < 1e-8 * np.max(np.abs(vel))
    assert np.max(np.abs(m.ball_acceleration - acc)) < 1e-8 * np.max(np.abs(acc))


def test_reference_drive_is_built_on_the_reference_pair(drive):
    """Identity oracle: LooperDrive.reference() places exactly the surfaces of spatialkin.mechanisms.looper.reference
    (the one definition of the reference geometry), and its rocker frame turns local z onto +y."""
    torus, sphere = reference.looper_pair()
    np.testing.assert_array_equal(drive.torus.data, torus.data)
    np.testing.assert_array_equal(drive.sphere.data, sphere.data)
    np.testing.assert_allclose(drive.rocker_frame.rotation[:, 2], (0.0, 1.0, 0.0), atol=1e-15)
    np.testing.assert_array_equal(drive.looper_tip, reference.LOOPER_TIP)


def test_reference_branches_and_swing(drive):
    """The reference geometry (independent script): branch 0 has v1 in about 107-114 deg, u2 in 77.8-115 deg,
    v2 within +-18.3 deg; branch 1 near v1 = 76 deg."""
    u1 = np.radians(np.arange(0, 360, 0.5))
    m0, m1 = drive.solve(u1, branch=0), drive.solve(u1, branch=1)
    v1 = np.degrees(m0.coupler_angle)
    assert 106.5 < v1.min() and v1.max() < 114.5
    u2, v2 = np.degrees(m0.rocker_angles.T)
    assert abs(u2.min() - 77.8) < 0.1 and abs(u2.max() - 115.0) < 0.1 and abs(np.abs(v2).max() - 18.35) < 0.05
    assert abs(np.degrees(m1.coupler_angle).min() - 76.0) < 0.1


def test_rocker_rates_and_link_points(drive):
    """Rocker angle rates against 5-point differences of the solved angles, and the chain identities:
    C as a point of the coupler and of the rocker arm agrees in position, velocity and acceleration."""
    omega = 2.0
    u1 = np.linspace(0.1, 6.0, 50)
    h = 1e-3
    m = drive.solve(u1, omega=omega)
    angles = lambda x: drive.solve(x, omega=omega).rocker_angles
    d1, d2 = five_point(angles, u1, h)
    np.testing.assert_allclose(m.rocker_rates, omega * d1, atol=1e-9)
    np.testing.assert_allclose(m.rocker_accelerations, omega ** 2 * d2, atol=1e-7)
    by_coupler = m.point("coupler", (drive.coupler_length, 0, 0))
    by_rocker = m.point("rocker_arm", (drive.rocker_length, 0, 0))
    for field in ("position", "velocity", "acceleration"):
        np.testing.assert_allclose(getattr(by_coupler, field), getattr(m, f"ball_{field if field != 'position' else 'center'}"), atol=1e-11)
        np.testing.assert_allclose(getattr(by_rocker, field), getattr(by_coupler, field), atol=1e-11)
    # the looper tip against differences of its position (a point off the arm, on the rocker arm's frame)
    tip = m.looper_tip
    tip_pos = lambda x: drive.solve(x, omega=omega).looper_tip.position
    t1, t2 = five_point(tip_pos, u1, h)
    np.testing.assert_allclose(tip.velocity, omega * t1, atol=1e-8 * np.abs(omega * t1).max())
    np.testing.assert_allclose(tip.acceleration, omega ** 2 * t2, atol=1e-7 * np.abs(omega ** 2 * t2).max())
    # the crank turns uniformly: its angular velocity is omega along the shaft
    np.testing.assert_allclose(m.angular_velocity("crank"), np.tile([0, 0, omega], (50, 1)), atol=1e-15)


def test_mechanism_that_cannot_be_assembled(blocked_drive):
    with pytest.raises(ValueError, match="cannot be assembled at any crank angle"):
        LooperDrive(8.0, 50.0, 5.0, rocker_frame=sk.Frame((6.0, 0.0, 200.0)))
    # assembled for part of the turn only: the error names the crank angles
    d = blocked_drive
    assert d.blocked_ranges
    lo, hi = d.blocked_ranges[0]
    with pytest.raises(ValueError, match="cannot be assembled at .* crank angles in"):
        d.solve([0.5 * (lo + hi)])


@pytest.mark.parametrize("branch", [0, 1])
def test_assembled_next_to_a_dead_position(branch):
    """Crank angles 1e-2 to 1e-10 rad inside either edge of a blocked range (where the coupler's circle touches the
    rocker sphere and the two crossings meet): each branch assembles, its ball centre within 1e-8 mm of the closed
    form's root of that branch (ill-conditioned as one over the square root of the margin), on both surfaces to
    1e-12 mm, and of the branch asked for."""
    base = LooperDrive.reference()
    d = LooperDrive(25.0, 50.0, 30.0, rocker_frame=base.rocker_frame)
    lo, hi = d.blocked_ranges[0]
    eps = np.array([1e-2, 1e-4, 1e-6, 1e-8, 1e-10])
    for angles in (lo - eps, hi + eps):
        assert np.all(d.assembly_margin(angles) > 0)
        states = np.array([d.solve([u], branch=branch).states[0] for u in angles])
        _, truth = looper_closed_form(d, np.mod(angles, 2 * np.pi), branch)
        ball = d.torus.point(states[:, 0], states[:, 1])
        assert np.max(np.linalg.norm(ball - truth, axis=1)) < 1e-8
        assert max(np.max(d.torus.distance(ball)), np.max(d.sphere.distance(ball))) < 1e-12
        assert np.all(d.branch_of(states) == branch)


@pytest.mark.parametrize("kwargs, name", [
    ({"crank_radius": 0}, "crank_radius"), ({"coupler_length": -1}, "coupler_length"),
    ({"rocker_length": np.nan}, "rocker_length"), ({"looper_link": "crank"}, "looper_link"),
    ({"crank_radius": 1e-40}, "crank_radius must lie within"), ({"coupler_length": 1e40}, "coupler_length must lie"),
    ({"rocker_length": 1e40}, "rocker_length must lie"),
])
def test_bad_arguments(kwargs, name):
    args = dict(crank_radius=reference.CRANK_RADIUS, coupler_length=reference.COUPLER_LENGTH,
                rocker_length=reference.ROCKER_LENGTH, rocker_frame=reference.rocker_frame())
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        LooperDrive(**args)


def test_bad_solve_arguments(drive):
    with pytest.raises(ValueError, match="branch"):
        drive.solve([0.0], branch=2)
    with pytest.raises(ValueError, match="branch must be 0 or 1, got True"):
        drive.solve([0.0], branch=True)
    assert drive.solve([0.0], branch=1.0).branch == 1 and isinstance(drive.solve([0.0], branch=1.0).branch, int)
    with pytest.raises(TypeError, match="omega must be a real number"):
        drive.solve([0.0], omega="3")
    with pytest.raises(TypeError, match="crank_radius must be a real number"):
        LooperDrive("8", reference.COUPLER_LENGTH, reference.ROCKER_LENGTH, rocker_frame=reference.rocker_frame())
    motion = drive.solve([0.0, 0.1])
    for method in (motion.angular_velocity, motion.angular_acceleration):
        with pytest.raises(ValueError, match="link must be one of"):
            method("foo")
    with pytest.raises(ValueError, match="omega"):
        drive.solve([0.0], omega=0.0)
    with pytest.raises(ValueError, match="crank_angles"):
        drive.solve([np.nan])


def test_looper_job_writes_what_it_promises(tmp_path):
    from spatialkin.cli import main
    out = tmp_path / "out"
    assert main(["looper", "--out", str(out)]) == 0
    table = np.loadtxt(out / "looper_motion.csv", delimiter=",", skiprows=1)
    header = (out / "looper_motion.csv").read_text().splitlines()[0].split(",")
    assert header[:5] == ["crank_angle_deg", "time_s", "ball_x_mm", "ball_y_mm", "ball_z_mm"]
    assert table.shape[0] >= 361 and table.shape[1] == len(header)
    drive = LooperDrive.reference()
    _, c = looper_closed_form(drive, np.radians(table[:, 0]), 0)
    assert np.max(np.abs(table[:, 2:5] - c)) < 1e-9
    for name in ("looper_speed.png", "looper_cyclogram.png", "looper_transmission.png"):
        assert (out / name).stat().st_size > 1000
    assert not [p for p in os.listdir(out) if p.startswith(".tmp-")]
    from PIL import Image

    from spatialkin.cli.looper_job import PICTURE_SIZE
    with Image.open(out / "looper_3d.png") as png:          # the 3-D picture: a PNG of the stated size
        assert png.format == "PNG" and png.size == PICTURE_SIZE
        pixels = np.asarray(png.convert("L"), dtype=float)
    # not blank: a white picture has variance 0; the links and paths give ~1000 (measured here)
    assert pixels.var() > 100.0
    assert (pixels < 128).mean() > 0.005        # dark pixels (the links: 2.8 % here) cover more than 0.5 %


def test_looper_job_config_errors_are_clear(tmp_path, capsys):
    from spatialkin.cli import main
    bad = tmp_path / "bad.toml"
    bad.write_text("crank_radius = -1\n")
    assert main(["looper", "--out", str(tmp_path / "o"), "--config", str(bad)]) == 2
    assert "crank_radius" in capsys.readouterr().err
    bad.write_text("crank_radiu = 3\n")
    assert main(["looper", "--out", str(tmp_path / "o"), "--config", str(bad)]) == 2
    assert "unknown keys" in capsys.readouterr().err
    assert not (tmp_path / "o" / "looper_motion.csv").exists()


def test_analysis_of_the_reference(drive):
    """The reference crank turns fully on both branches; swing ranges as measured independently; the
    transmission angle is 90 deg where C moves normal to the plane of the coupler line and the pin axis,
    as at crank angle 0 (C moves along the pin axis there by the symmetry of the reference)."""
    a = drive.analyse(branch=0)
    assert a.turns_fully and a.dead_positions == [] and a.blocked_ranges == [] and a.branch_points == []
    assert abs(np.degrees(a.u2_range[0]) - 77.8) < 0.05 and abs(np.degrees(a.v2_range[1]) - 18.35) < 0.05
    assert abs(np.degrees(a.transmission_angle[0]) - 90.0) < 1e-9
    assert 0 < a.min_transmission[0] < np.pi / 2


def test_dead_positions_are_the_edges_of_the_blocked_ranges(blocked_drive):
    """A crank that cannot turn fully: the dead positions found on the traced loops (u1' = 0) are the crank
    angles where the coupler circle just touches the rocker sphere (independent distance formula), to 1e-12 (they
    were interpolated between samples, 2e-6 off)."""
    d = blocked_drive
    a = d.analyse()
    assert not a.turns_fully
    edges = sorted(x for rng in d.blocked_ranges for x in rng)
    assert len(a.dead_positions) == len(edges) == 4
    np.testing.assert_allclose(a.dead_positions, edges, atol=1e-12)
    assert np.all(d.assembly_margin(a.crank_angles) > 0)
    for scale in (1.0, 1e-3):               # a crank of 25 rocking, at two scales: the same to the round-off
        ref = LooperDrive.reference()
        rocking = LooperDrive(25.0 * scale, 50.0 * scale, 30.0 * scale,
                              rocker_frame=sk.Frame(ref.rocker_frame.origin * scale, ref.rocker_frame.rotation))
        edges = np.ravel(rocking.blocked_ranges)
        np.testing.assert_allclose(rocking.analyse().dead_positions, edges, atol=1e-12)


def test_equator_start_and_assembly_agree_with_solve(drive):
    """The start of [Looper] (the sphere's equator cut by the torus) and assembly at any crank angle give the
    states that solve() returns at those crank angles, each on its branch."""
    for y in drive.seed_starts():
        branch = int(drive.branch_of(y))
        m = drive.solve([y[0]], branch=branch)
        np.testing.assert_allclose(np.angle(np.exp(1j * (m.states[0] - y))), 0.0, atol=1e-9)
    for branch in (0, 1):
        y = drive.assemble(1.234, branch)
        m = drive.solve([1.234], branch=branch)
        np.testing.assert_allclose(np.angle(np.exp(1j * (m.states[0] - y))), 0.0, atol=1e-9)


def test_branch_over_two_components_uses_every_component(blocked_drive):
    """A crank that cannot turn fully, asked at crank angles in both of its ranges: branch 0 lies on a
    different loop in each, so the component through the first assembly does not cover the request and
    solve traces every component; positions match the closed form to 1e-9 mm either way."""
    d = blocked_drive
    (a0, a1), (b0, b1) = d.blocked_ranges
    one_range = np.linspace(a1 + 0.05, b0 - 0.05, 50)
    both = np.concatenate([one_range, np.mod(np.linspace(b1 + 0.05, a0 + 2 * np.pi - 0.05, 50), 2 * np.pi)])
    for angles, every in ((one_range, False), (both, True)):
        d._loops = None
        for branch in (0, 1):
            m = d.solve(angles, branch=branch)
            assert np.max(np.abs(m.ball_center - looper_closed_form(d, angles, branch)[1])) < 1e-9
        assert (d._loops is not None) == every


def test_coverage_of_crank_angles():
    """covers(): every angle within the gap of a key, circularly (the first key follows the last)."""
    from spatialkin.mechanisms.looper.drive import covers
    keys = np.array([0.01, 1.0, 1.02, 2 * np.pi - 0.01])
    assert covers(keys, np.array([0.0, 2 * np.pi - 0.005, 1.01]), 0.02)
    assert not covers(keys, np.array([0.5]), 0.02)
    assert covers(keys, np.array([0.5]), 0.5)


def test_solution_does_not_depend_on_the_order_or_company_of_the_angles(drive):
    """Angles are solved in increasing order by continuation: asking them shuffled, or one at a time, gives
    the same states, velocities and accelerations (to 1e-12 mm / relative), each from its own Newton."""
    u1 = np.linspace(0.0, 2 * np.pi, 361)
    ref = drive.solve(u1, omega=2.0)
    perm = np.random.default_rng(3).permutation(len(u1))
    shuffled = drive.solve(u1[perm], omega=2.0)
    np.testing.assert_allclose(shuffled.ball_center, ref.ball_center[perm], atol=1e-12)
    np.testing.assert_allclose(shuffled.ball_acceleration, ref.ball_acceleration[perm],
                               atol=1e-12 * np.abs(ref.ball_acceleration).max())
    for k in (0, 97, 360):
        one = drive.solve(u1[k:k + 1], omega=2.0)
        np.testing.assert_allclose(one.ball_center[0], ref.ball_center[k], atol=1e-12)
        np.testing.assert_allclose(one.ball_velocity[0], ref.ball_velocity[k],
                                   atol=1e-12 * np.abs(ref.ball_velocity).max())


@pytest.mark.parametrize("samples", [0, 1, 2, -1, 3.5, True, 10 ** 9])
def test_analyse_names_a_bad_count_of_samples(drive, samples):
    """A turn analysed over fewer than 3 crank angles (1 or 2 gave a degenerate range and a 90 deg minimum
    transmission angle), a count that is no integer, or one too large for memory, is refused naming it."""
    with pytest.raises(ValueError, match="samples must be an integer >= 3"):
        drive.analyse(samples=samples)


@pytest.mark.parametrize("offset", [(5000.0, 0.0, 0.0), (0.0, 0.0, 8000.0), (1e6, 2e6, -3e6)])
def test_a_drive_far_from_the_origin_moves_as_at_it(offset):
    """The reference drive moved by an offset (its Newton tolerance below the coordinates' round-off there made
    solve fail with a false 'dead position'): identity oracle, the motion at the origin translated: positions
    shifted by the offset, velocities and accelerations the same, to 64 ulps of the coordinates."""
    o = np.array(offset)
    ref = LooperDrive.reference()
    far = LooperDrive(reference.CRANK_RADIUS, reference.COUPLER_LENGTH, reference.ROCKER_LENGTH,
                      crank_frame=sk.Frame(o), rocker_frame=sk.Frame(ref.rocker_frame.origin + o,
                                                                     ref.rocker_frame.rotation),
                      looper_tip=ref.looper_tip)
    angles = np.radians(np.arange(0.0, 360.0, 2.0))
    near, moved = ref.solve(angles, omega=2.0), far.solve(angles, omega=2.0)
    tol = 64 * np.finfo(float).eps * (np.max(np.abs(o)) + ref.size)
    np.testing.assert_allclose(moved.ball_center - o, near.ball_center, rtol=0, atol=tol)
    np.testing.assert_allclose(moved.ball_velocity, near.ball_velocity, rtol=0, atol=4 * tol)
    np.testing.assert_allclose(moved.ball_acceleration, near.ball_acceleration, rtol=0, atol=16 * tol)
    assert far.analyse().turns_fully
