"""spatialkin design --targets FILE.toml writes a config the main job accepts, whose drive meets the targets; the
example in its --help runs as copied."""
import math
import textwrap

import numpy as np

import pytest

from spatialkin.cli import main
from spatialkin.design import LooperDesign
from spatialkin.cli.looper_job import build, load_config

TARGETS = """
[design]
free = ["crank_radius", "rocker_length", "rocker_y", "rocker_rz"]
[design.bounds]
crank_radius = [5.0, 12.0]

[rocker]
swing_deg = 40.0
u2_max_at_deg = 5.0
u2_min_at_deg = 185.0

[limits]
min_transmission_deg = 60.0
"""


def test_design_command_writes_a_config_the_main_job_accepts(tmp_path, capsys):
    path = tmp_path / "targets.toml"
    path.write_text(TARGETS)
    out = tmp_path / "fitted.toml"
    assert main(["design", "--targets", str(path), "--out", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    config = load_config(str(out))
    design = LooperDesign.from_drive(build(config))
    turn = design.sensitivities(np.linspace(0, 2 * np.pi, 721), turning=True)
    assert abs(math.degrees(turn.swing) - 40.0) < 1e-8
    u2 = turn.turning_u2
    assert abs(math.remainder(math.degrees(turn.turning_points[np.argmax(u2)]) - 5.0, 360)) < 1e-8
    assert abs(math.remainder(math.degrees(turn.turning_points[np.argmin(u2)]) - 185.0, 360)) < 1e-8
    assert math.degrees(turn.min_transmission) > 60.0 - 0.05
    assert not list(tmp_path.glob(".tmp-*"))              # written atomically


def test_bad_targets_file_is_an_error_naming_it(tmp_path, capsys):
    path = tmp_path / "targets.toml"
    path.write_text('[design]\nfree = ["crank"]\n[rocker]\nswing_deg = 30.0\n')
    assert main(["design", "--targets", str(path)]) == 2
    assert "free" in capsys.readouterr().err
    assert not (tmp_path / "targets_fitted.toml").exists()


BAD_WEIGHTS = '[design]\nfree = ["crank_radius"]\n[rocker]\nswing_deg = 30.0\n[weights]\nswing = '


@pytest.mark.parametrize("text, words", [(BAD_WEIGHTS + '"x"\n', "weight swing must be a real number"),
                                         (BAD_WEIGHTS + "nan\n", "weight swing must be a finite number")])
def test_bad_weights_are_one_line_and_exit_2(tmp_path, capsys, text, words):
    path = tmp_path / "targets.toml"
    path.write_text(text)
    assert main(["design", "--targets", str(path)]) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err, err


def test_design_without_targets_is_one_line(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["design"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "--targets" in err and len(err.strip().splitlines()) == 1, err


def test_start_from_a_config_and_fit_tip_points(tmp_path):
    """The start is a looper config with a wrong crank radius; tip points of the reference drive bring it
    back (1e-8)."""
    reference = LooperDesign.reference()
    angles = np.radians([0.0, 90.0, 180.0, 270.0])
    tips = reference.sensitivities(angles, turning=False).tip
    (tmp_path / "start.toml").write_text("crank_radius = 8.6\nstep_deg = 0.5\n")
    text = '[design]\nfree = ["crank_radius"]\nstart = "start.toml"\n'
    for a, p in zip(np.degrees(angles), tips):
        text += f"[[tip]]\ncrank_angle_deg = {float(a)!r}\npoint = {[float(x) for x in p]!r}\n"
    (tmp_path / "t.toml").write_text(text)
    assert main(["design", "--targets", str(tmp_path / "t.toml")]) == 0
    config = load_config(str(tmp_path / "t_fitted.toml"))
    assert abs(config["crank_radius"] - 8.0) < 1e-8
    assert config["step_deg"] == 0.5                     # the start's job settings carry over


def test_the_help_example_meets_every_target_as_copied(tmp_path, capsys):
    """The targets file shown by --help, copied as it stands: exit status 0, every target met (the report's own
    verdict, within the example's tolerances), and the fitted config builds a drive."""
    with pytest.raises(SystemExit) as ex:
        main(["design", "--help"])
    assert ex.value.code == 0
    text = capsys.readouterr().out
    example = text.split("lengths in the drive's unit):\n", 1)[1].split("\nParameter names", 1)[0]
    path = tmp_path / "targets.toml"
    path.write_text(textwrap.dedent(example))
    assert main(["design", "--targets", str(path)]) == 0
    report = capsys.readouterr().out
    verdicts = [line for line in report.splitlines() if line.rstrip().endswith((": met", ": MISSED"))]
    assert len(verdicts) == 6 and all(line.endswith(": met") for line in verdicts), report
    drive = build(load_config(str(tmp_path / "targets_fitted.toml")))
    assert drive.analyse().turns_fully


def test_out_in_a_missing_folder_is_made_and_a_bad_out_is_refused_before_the_fit(tmp_path, capsys, monkeypatch):
    """--out in a folder that does not exist yet: the folder is made and the config written there; --out naming a
    folder, or below a file, is one line and exit 2 before any fit runs (a fit that would run says so)."""
    path = tmp_path / "targets.toml"
    path.write_text('[design]\nfree = ["crank_radius"]\n[rocker]\nswing_deg = 37.0\n')
    out = tmp_path / "new" / "deeper" / "fit.toml"
    assert main(["design", "--targets", str(path), "--out", str(out)]) in (0, 1)
    assert load_config(str(out))["crank_radius"] > 0
    capsys.readouterr()
    from spatialkin.design import looper as design_looper
    monkeypatch.setattr(design_looper.LooperDesign, "fit", lambda *a, **k: pytest.fail("the fit ran"))
    (tmp_path / "plain").write_text("x")
    for bad, words in ((tmp_path, "a folder of that name exists"), (tmp_path / "plain" / "fit.toml", "is a file")):
        assert main(["design", "--targets", str(path), "--out", str(bad)]) == 2
        err = capsys.readouterr().err
        assert words in err and len(err.strip().splitlines()) == 1, err
