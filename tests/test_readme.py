"""The README's examples run as written: every ```python block in order in one namespace (as a reader pastes
them into one session), in a scratch folder; every ```toml block is a valid looper config; every picture it shows
is in the repository; it describes the product, not its history."""
import os
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"


def blocks(kind):
    return re.findall(rf"^```{kind}\n(.*?)^```", README.read_text(), flags=re.S | re.M)


def test_the_first_two_commands_are_the_install_and_the_job():
    first = blocks("bash")[0].splitlines()
    assert first[0].startswith("python3 -m pip install . && spatialkin looper --out")
    assert first[1].startswith('python3 -m pip install ".[test]" && python3 -m pytest -q')


def test_python_examples_run_as_written(tmp_path, monkeypatch):
    code = blocks("python")
    assert len(code) >= 5
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "readme"}
    for k, block in enumerate(code):
        try:
            exec(compile(block, f"README.md python block {k + 1}", "exec"), namespace)
        except Exception as err:        # name the block that failed
            pytest.fail(f"README python block {k + 1} failed: {type(err).__name__}: {err}\n{block}")
    assert os.path.getsize(tmp_path / "looper.png") > 1000 and os.path.getsize(tmp_path / "curves.png") > 1000


def test_toml_examples_are_valid_configs(tmp_path):
    import numpy as np

    from spatialkin.cli.looper_job import build, load_config
    from spatialkin.mechanisms import LooperDrive
    tomls = blocks("toml")
    assert tomls
    reference = LooperDrive.reference()
    for k, text in enumerate(tomls):
        path = tmp_path / f"block{k}.toml"
        path.write_text(text)
        drive = build(load_config(path))
        # the README says its example is the reference drive: the same frames to round-off
        for got, want in ((drive.crank_frame, reference.crank_frame), (drive.rocker_frame, reference.rocker_frame)):
            np.testing.assert_allclose(got.rotation, want.rotation, rtol=0, atol=1e-15)
            np.testing.assert_allclose(got.origin, want.origin, rtol=0, atol=0)


def test_pictures_are_in_the_repository():
    pictures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", README.read_text())
    assert len(pictures) >= 2
    for path in pictures:
        file = README.parent / path
        assert file.suffix == ".png" and file.is_file() and file.stat().st_size > 10_000, path


#: Words of development history that a user-facing README does not carry (see the no-history rule).
HISTORY = re.compile(r"seed[ -]?00\d|\.\./shared|this session|\bround\b of|farm-bench|\bissue \d+", re.I)


def test_no_history():
    assert not HISTORY.findall(README.read_text())
