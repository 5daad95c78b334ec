"""The looper job as a designer runs it: units and machine speed, the JSON record, partial-turn drives,
rotation forms in the TOML, one-line errors, --help (every key, every file the job writes) and --version. Oracles: the closed form per crank angle
(tests/oracles/closed_forms.py), the scaling of velocities with the crank speed (v ~ omega,
a ~ omega^2), the blocked crank ranges' exact edges, and the reference rotation."""
import json
import os

import numpy as np
import pytest
from tests.oracles.closed_forms import looper_closed_form

import spatialkin as sk
from spatialkin.mechanisms.looper import reference
from spatialkin.cli import main
from spatialkin.plots.looper import angle_span
from spatialkin.cli.looper_job import DEFAULT_SPEED_RPM, KEYS, ROTATION_TOL, build, load_config, output_files
from spatialkin.mechanisms import LooperDrive

#: Positions against the closed form (mm), and relative agreement of machine-speed values with rescaled ones.
POSITION_TOL = 1e-9
SCALING_TOL = 1e-12
#: Dead positions against the exact edges of the blocked ranges (rad; the analysis locates u1' = 0 on loops).
DEAD_TOL = 1e-5
#: Same physical drive typed differently: angles agree to round-off (deg).
SAME_ANGLES_TOL = 1e-9


@pytest.fixture(scope="module")
def reference_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("job")
    assert main(["looper", "--out", str(out)]) == 0
    header = (out / "looper_motion.csv").read_text().splitlines()[0].split(",")
    table = np.loadtxt(out / "looper_motion.csv", delimiter=",", skiprows=1)
    return out, header, table, json.loads((out / "looper_run.json").read_text())


def test_table_has_units_degrees_and_machine_speed(reference_run):
    out, header, table, record = reference_run
    col = {name: k for k, name in enumerate(header)}
    assert all("_" in name for name in header)           # every column names its unit
    assert {"crank_angle_deg", "time_s", "ball_vx_mm_per_s", "ball_ax_mm_per_s2", "u2_deg", "u2_dot_deg_per_s",
            "tip_az_mm_per_s2"} <= set(header)
    omega = DEFAULT_SPEED_RPM * 2 * np.pi / 60
    u1 = np.radians(table[:, col["crank_angle_deg"]])
    np.testing.assert_allclose(table[:, col["time_s"]], u1 / omega, rtol=SCALING_TOL, atol=0)
    drive = LooperDrive.reference()
    assert np.max(np.abs(table[:, [col["ball_x_mm"], col["ball_y_mm"], col["ball_z_mm"]]] - looper_closed_form(drive, u1, 0)[1])) < POSITION_TOL
    # oracle: velocities scale with omega, accelerations with omega^2 (constant crank speed)
    unit = drive.solve(u1, omega=1.0)
    v = table[:, [col["ball_vx_mm_per_s"], col["ball_vy_mm_per_s"], col["ball_vz_mm_per_s"]]]
    a = table[:, [col["ball_ax_mm_per_s2"], col["ball_ay_mm_per_s2"], col["ball_az_mm_per_s2"]]]
    scale = np.max(np.abs(unit.ball_velocity)) * omega
    assert np.max(np.abs(v - omega * unit.ball_velocity)) < SCALING_TOL * scale
    assert np.max(np.abs(a - omega ** 2 * unit.ball_acceleration)) < SCALING_TOL * scale * omega
    u2 = np.degrees(unit.rocker_angles[:, 0])
    assert np.max(np.abs(table[:, col["u2_deg"]] - u2)) < SAME_ANGLES_TOL
    assert np.max(np.abs(table[:, col["u2_dot_deg_per_s"]] - omega * np.degrees(unit.rocker_rates[:, 0]))) \
        < SCALING_TOL * omega * np.max(np.abs(np.degrees(unit.rocker_rates[:, 0])))


def test_record_holds_geometry_speed_versions_errors(reference_run):
    out, _, table, record = reference_run
    g = record["geometry"]
    assert (g["crank_radius"], g["coupler_length"], g["rocker_length"]) == (
        reference.CRANK_RADIUS, reference.COUPLER_LENGTH, reference.ROCKER_LENGTH)
    np.testing.assert_allclose(g["rocker_frame"]["origin"], reference.ROCKER_CENTRE)
    assert record["speed"]["rpm"] == DEFAULT_SPEED_RPM and record["branch"] == 0 and record["length_unit"] == "mm"
    assert set(record["versions"]) >= {"spatialkin", "numpy", "scipy", "numba", "python"}
    assert max(record["measured_error"][k] for k in ("C_to_torus", "C_to_sphere", "coupler_vs_rocker_chain")) < 1e-12
    a = record["analysis"]
    assert a["turns_fully"] and a["dead_positions_deg"] == [] and a["blocked_ranges_deg"] == []
    # the rocker's swing on the reference geometry, from an independent script (u2 77.805..114.962 deg, v2 +-18.348)
    np.testing.assert_allclose(a["u2_range_deg"], [77.805, 114.962], atol=5e-4)
    np.testing.assert_allclose(a["v2_range_deg"], [-18.348, 18.348], atol=5e-4)
    peak = record["peaks_at_machine_speed"]["ball_v_m_per_s"]
    omega = DEFAULT_SPEED_RPM * 2 * np.pi / 60
    speed = np.linalg.norm(LooperDrive.reference().solve(np.radians(table[:, 0])).ball_velocity, axis=1)
    assert abs(peak[0] - 1e-3 * omega * speed.max()) < SCALING_TOL * peak[0]
    for name in record["files"]:
        assert (out / name).stat().st_size > 1000


def test_summary_states_units(tmp_path):
    lines = []
    from spatialkin.cli.looper_job import run
    run(tmp_path, echo=lines.append)
    text = "\n".join(lines)
    for needle in ("rpm", "rocker swing: u2 77.805..114.962 deg", "timing:", "m/s (crank", "m/s^2", " g (crank",
                   "deg/s", "measured error"):
        assert needle in text, needle


def test_partial_turn_drive_is_analysed_over_its_reachable_ranges(tmp_path, capsys, blocked_drive):
    cfg = tmp_path / "rocking.toml"
    cfg.write_text("rocker_frame = { origin = [40.0, 0.0, 60.0], rotation = [[1, 0, 0], [0, 1, 0], [0, 0, 1]] }\n"
                   "step_deg = 0.5\n")                                                     # blocked_drive typed
    out = tmp_path / "out"
    assert main(["looper", "--out", str(out), "--config", str(cfg)]) == 0
    assert "dead positions at crank angles" in capsys.readouterr().out
    record = json.loads((out / "looper_run.json").read_text())
    drive = blocked_drive
    edges = np.degrees(sorted(x for rng in drive.blocked_ranges for x in rng))
    assert not record["analysis"]["turns_fully"]
    np.testing.assert_allclose(record["analysis"]["dead_positions_deg"], edges, atol=np.degrees(DEAD_TOL))
    table = np.loadtxt(out / "looper_motion.csv", delimiter=",", skiprows=1)
    u1 = np.radians(table[:, 0])
    assert np.all(drive.assembly_margin(u1) > 0)            # rows only where the drive assembles
    assert np.max(np.abs(table[:, 2:5] - looper_closed_form(drive, u1, 0)[1])) < POSITION_TOL
    assert len(record["crank_ranges_deg"]) == 2            # [318.6, 41.4] through 0, and [154.6, 205.4]
    for name in record["files"]:
        assert (out / name).stat().st_size > 1000


def test_never_assembling_drive_exits_2_with_the_clear_message(tmp_path, capsys):
    cfg = tmp_path / "far.toml"
    cfg.write_text("rocker_frame = { origin = [600.0, 0.0, 75.0], z_axis = [0, 1, 0] }\n")
    assert main(["looper", "--out", str(tmp_path / "o"), "--config", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "cannot be assembled at any crank angle" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


REFERENCE_ROCKER = sk.rotation_about((1, 0, 0), -np.pi / 2)


@pytest.mark.parametrize("table", [
    {"origin": [6.0, 0.0, 75.0], "z_axis": [0, 1, 0]},
    {"origin": [6.0, 0.0, 75.0], "z_axis": [0, -1, 0]},                       # the same shaft, typed reversed
    {"origin": [6.0, 0.0, 75.0], "z_axis": [0, 2, 0], "x_hint": [1, 0.3, 0]},
    {"origin": [6.0, 0.0, 75.0], "axis_angle": {"axis": [1, 0, 0], "angle_deg": -90}},
    {"origin": [6.0, 0.0, 75.0], "rotation": [[1, 0, 0], [0, 0.000001, 1], [0, -1, 0.000001]]},   # 6 decimals
])
def test_rotation_forms_give_the_same_drive_and_angles(table):
    config = load_config()
    config["rocker_frame"] = table
    drive = build(config)
    np.testing.assert_allclose(drive.rocker_frame.rotation, REFERENCE_ROCKER, atol=2e-6)
    angles = np.radians(np.arange(0.0, 360.0, 10.0))
    got = np.degrees(drive.solve(angles).rocker_angles)
    want = np.degrees(LooperDrive.reference().solve(angles).rocker_angles)
    assert np.max(np.abs(got - want)) < (SAME_ANGLES_TOL if "rotation" not in table else 1e-3)


def test_crank_z_axis_alone_points_u1_zero_at_the_rocker():
    config = load_config()
    config["crank_frame"] = {"origin": [0.0, 0.0, 0.0], "z_axis": [0, 0, 1]}
    np.testing.assert_allclose(build(config).crank_frame.rotation, np.eye(3), atol=1e-15)


@pytest.mark.parametrize("text, needle", [
    ("crank_radius = -1\n", "crank_radius"),
    ("crank_radius = 'a'\n", "crank_radius must be a number"),
    ("crank_radius = \n", "not valid TOML"),
    ("omega = 3.0\n", "speed_rpm"),
    ("speed_rpm = 0\n", "speed_rpm"),
    ("length_unit = 'furlong'\n", "length_unit"),
    ("branch = 3\n", "branch"),
    ("looper_tip = [1, 2]\n", "looper_tip"),
    ("rocker_frame = { origin = [6, 0, 75], rotation = [[1, 0, 0], [0, 0, 1], [0, -1, 0.01]] }\n",
     "rocker_frame.rotation must be orthonormal"),
    ("rocker_frame = { origin = [6, 0, 75], rotation = [[-1, 0, 0], [0, 0, 1], [0, -1, 0]] }\n",
     "rocker_frame.rotation must be right-handed"),
    ("rocker_frame = { origin = [6, 0, 75], z_axis = [0, 1, 0], x_hint = [0, 3, 0] }\n", "parallel"),
    ("rocker_frame = { origin = [6, 0, 75], x_hint = [1, 0, 0] }\n", "x_hint goes with z_axis"),
    ("rocker_frame = { origin = [6, 0, 75], axis_angle = { axis = [0, 0, 0], angle_deg = 5 } }\n", "non-zero"),
    ("rocker_frame = { origin = [6, 0, 75], z_axis = [0, 1, 0], rotation = [[1, 0, 0], [0, 1, 0], [0, 0, 1]] }\n",
     "give one of"),
    ("rocker_frame = { origin = [6.0, 0.0, 75.0] }\n", "rocker_frame: origin alone does not place a frame"),
    ("crank_frame = { origin = [0.0, 0.0, 0.0] }\n", "crank_frame: origin alone does not place a frame"),
    ("rocker_frame = {}\n", "rocker_frame: origin alone does not place a frame"),
    ("links = { crank = { mass = -1.0 } }\n", "links.crank: mass"),
    ("links = { looper = { mass = 1.0 } }\n", "unknown link 'looper'"),
    ("links = { coupler = { mass = 1.0, inertia = [1.0, -2.0, 1.0] } }\n", "links.coupler: inertia"),
    ("links = { coupler = { mass = 1.0, density = 7.85 } }\n", "links.coupler: unknown keys"),
    ("gravity_m_per_s2 = [0, -9.8]\n", "gravity_m_per_s2"),
    ("step_deg = 1e-9\n", "step_deg must lie in [0.001, 1]"),
    ("cad_tolerance = 1e-30\n", "a B-spline within 1e-30 was not reached"),
])
def test_bad_config_is_one_line_and_exit_2(tmp_path, capsys, text, needle):
    """One line naming the key, exit 2, and no file written (a CAD tolerance out of reach is found before any)."""
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text)
    assert main(["looper", "--out", str(tmp_path / "o"), "--config", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("argv", [["demo", "--tol", "-1"], ["demo", "--tol", "x"], ["looper"], ["bogus"],
                                  ["looper", "--out", "o", "--config", "/nonexistent/x.toml"]])
def test_bad_command_lines_are_one_line_and_exit_2(capsys, argv):
    try:
        code = main(argv)
    except SystemExit as ex:          # argparse's errors
        code = ex.code
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, err


def test_out_that_is_a_file_is_one_line_naming_out(tmp_path, capsys):
    """--out naming an existing file, or a folder below one: exit 2 before any work, one line naming --out and
    the reason, the file untouched."""
    existing = tmp_path / "neg.toml"
    existing.write_text("crank_radius = 8.0\n")
    for command in (["looper"], ["bench", "--quick"]):
        for out, reason in ((existing, "a file of that name exists"), (existing / "sub", "is a file")):
            assert main(command + ["--out", str(out)]) == 2
            err = capsys.readouterr().err
            assert err.startswith(f"spatialkin {command[0]}: --out {out}: ") and reason in err, err
            assert len(err.strip().splitlines()) == 1 and "Errno" not in err, err
    assert existing.read_text() == "crank_radius = 8.0\n"


def test_help_lists_every_file_the_job_writes(reference_run, capsys):
    """Oracle: the files the reference run wrote (and the job's list of its outputs, which holds the STEP file
    the cad extra adds) are each named in --help."""
    out, _, _, record = reference_run
    written = set(os.listdir(out))
    assert written == set(record["files"]) | {"looper_run.json"}
    assert written <= set(output_files())
    with pytest.raises(SystemExit) as ex:
        main(["looper", "--help"])
    text = capsys.readouterr().out
    assert ex.value.code == 0
    for name in sorted(written | set(output_files())):
        assert name in text, name


def test_version_and_help_list_every_key(capsys):
    with pytest.raises(SystemExit) as ex:
        main(["--version"])
    assert ex.value.code == 0 and capsys.readouterr().out.strip() == f"spatialkin {sk.__version__}"
    with pytest.raises(SystemExit):
        main(["looper", "--help"])
    text = capsys.readouterr().out
    for key, (default, unit, _) in KEYS.items():
        assert key in text and f"[{unit}]" in text, key
    assert str(ROTATION_TOL) in text or f"{ROTATION_TOL:g}" in text


def test_angle_span_on_the_circle():
    """The shortest arc holding angles (deg): plain min/max, or through 180 deg (oracle: by hand)."""
    assert angle_span(np.array([77.8, 114.9, 90.0])) == (77.8, 114.9)
    lo, hi = angle_span(np.array([170.0, 179.0, -179.0, -170.0]))
    assert (lo, hi) == (170.0, 190.0)


def test_the_same_drive_in_metres_gives_the_same_si_figures(tmp_path):
    """Oracle: scale invariance. The reference drive typed in metres (and its rocker shaft reversed) reports
    the same peaks in m/s and m/s^2 and the same angles as in millimetres."""
    records = []
    for unit, k, frame in (("mm", 1.0, "z_axis = [0, 1, 0]"), ("m", 1e-3, "z_axis = [0, -1, 0]")):
        cfg = tmp_path / f"{unit}.toml"
        cfg.write_text(f'length_unit = "{unit}"\nstep_deg = 1.0\ncrank_radius = {8 * k}\ncoupler_length = {50 * k}\n'
                       f"rocker_length = {30 * k}\nlooper_tip = [{40 * k}, 0.0, {12 * k}]\n"
                       f"rocker_frame = {{ origin = [{6 * k}, 0.0, {75 * k}], {frame} }}\n")
        assert main(["looper", "--out", str(tmp_path / unit), "--config", str(cfg)]) == 0
        records.append(json.loads((tmp_path / unit / "looper_run.json").read_text()))
    mm, m = records
    for key, value in mm["peaks_at_machine_speed"].items():
        if key != "note":
            np.testing.assert_allclose(m["peaks_at_machine_speed"][key], value, rtol=1e-9, err_msg=key)
    np.testing.assert_allclose(m["analysis"]["u2_range_deg"], mm["analysis"]["u2_range_deg"], rtol=0, atol=1e-9)


def test_cad_paths_read_back(reference_run):
    """looper_paths.dxf holds the ball-centre and tip paths of the full turn as two degree-5 splines within
    cad_tolerance (1e-5 mm) of the table's exact positions (at 3601 crank angles, nearest point of a dense
    evaluation of the DXF spline, by ezdxf)."""
    ezdxf = pytest.importorskip("ezdxf")
    out, header, table, record = reference_run
    splines = list(ezdxf.readfile(out / "looper_paths.dxf").modelspace().query("SPLINE"))
    assert len(splines) == 2 and all(sp.dxf.degree == 5 for sp in splines)
    tip_cols = [header.index(f"tip_{c}_mm") for c in "xyz"]
    for sp, cols in zip(splines, ([header.index(f"ball_{c}_mm") for c in "xyz"], tip_cols)):
        tool = sp.construction_tool()
        knots = list(sp.knots)
        lo, hi = knots[5], np.nextafter(knots[-6], 0.0)              # ezdxf evaluates inside [lo, hi)
        theta = np.clip(np.radians(table[::10, 0]), lo, hi)
        exact = table[::10, cols]
        at = np.array([tuple(tool.point(t)) for t in theta])
        tangent = np.array([tuple(tool.derivative(t, 1)[1]) for t in theta])
        foot = np.clip(theta - np.einsum("ij,ij->i", at - exact, tangent) / np.einsum("ij,ij->i", tangent, tangent),
                       lo, hi)
        near = np.array([tuple(tool.point(t)) for t in foot])       # the spline point nearest each exact one
        assert np.max(np.linalg.norm(near - exact, axis=1)) < 1e-5
    if "looper_paths.step" not in record["files"] or not (out / "looper_paths.step").exists():
        pytest.skip("OpenCascade (the cad extra) not installed")


def test_forces_at_machine_speed_with_si_units(reference_run, tmp_path):
    """The default job (the example steel links) writes the forces: the CSV with an SI unit in every header, its
    torque the library's (the drive's loads at machine speed, mm -> m), its mean power zero over the turn (no
    gravity, no external load), the record's peaks the table's; `links = {}` turns them off."""
    from spatialkin.dynamics import Body
    out, _, motion_table, rec = reference_run
    header = (out / "looper_forces.csv").read_text().splitlines()[0].split(",")
    forces = np.loadtxt(out / "looper_forces.csv", delimiter=",", skiprows=1)
    assert all(name.endswith(("_deg", "_N", "_N_m", "_W")) for name in header)
    assert {"looper_forces.csv", "looper_torque.png", "looper_bearing_loads.png"} <= set(rec["files"])
    col = {name: k for k, name in enumerate(header)}
    omega = DEFAULT_SPEED_RPM * 2 * np.pi / 60
    bodies = {k: Body(v["mass"], v["com"], v["inertia"]) for k, v in reference.STEEL_LINKS.items()}
    want = LooperDrive.reference().loads(np.radians(forces[:, 0]), omega, bodies).crank_torque * 1e-6
    torque = forces[:, col["crank_torque_N_m"]]
    np.testing.assert_allclose(torque, want, rtol=0, atol=1e-12 * np.max(np.abs(want)))
    np.testing.assert_allclose(forces[:, col["power_W"]], torque * omega, rtol=1e-14)
    assert abs(np.mean(forces[:-1, col["power_W"]])) < 1e-9 * np.max(np.abs(forces[:, col["power_W"]]))
    assert rec["forces"]["crank_torque_N_m"][0] == pytest.approx(np.max(np.abs(torque)), rel=1e-12)
    assert rec["forces"]["peak_power_W"][0] == pytest.approx(np.max(np.abs(torque * omega)), rel=1e-12)
    from spatialkin.cli.looper_forces import summary
    line = summary(rec["forces"])[0]
    assert "mean power" in line and line.endswith("(frictionless joints: the links' energy is the same after a turn)")
    lossy = dict(rec["forces"], mean_power_W=0.01 * rec["forces"]["peak_power_W"][0])
    assert "frictionless" not in summary(lossy)[0]
    ball = np.linalg.norm(forces[:, [col["ball_Fx_N"], col["ball_Fy_N"], col["ball_Fz_N"]]], axis=1)
    np.testing.assert_allclose(forces[:, col["ball_F_N"]], ball, rtol=1e-12)
    off = tmp_path / "off.toml"
    off.write_text("links = {}\nstep_deg = 1.0\n")
    assert main(["looper", "--out", str(tmp_path / "o"), "--config", str(off)]) == 0
    assert not (tmp_path / "o" / "looper_forces.csv").exists()
    assert "forces" not in json.loads((tmp_path / "o" / "looper_run.json").read_text())


def test_demo_times_a_second_call():
    """spatialkin demo prints the components and, apart, the first call's time (its kernels included, spatialkin's
    import not) and a second call's, whose curves' times the table shows: no curve's time carries the first call's
    loading (each at most the second call's whole time)."""
    import re
    import subprocess
    import sys
    out = subprocess.run([sys.executable, "-m", "spatialkin.cli", "demo"], capture_output=True, text=True, check=True)
    rows = [line.split() for line in out.stdout.splitlines() if re.match(r"\s*\d+\s+closed", line)]
    assert len(rows) == 2
    again = float(re.search(r"a second call: ([\d.]+) ms", out.stdout).group(1))
    assert all(float(row[-1]) <= again for row in rows)
