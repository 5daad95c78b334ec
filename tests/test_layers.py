"""The layers hold: import-linter runs the contracts of pyproject.toml ([tool.importlinter]: each layer of
spatialkin (_lib, kernels, geometry, tracing and continuation, motion, mechanisms and design, then the presentation:
export, render, plots, bench, cli) imports none above it, pyvista only in render, matplotlib only in plots and the
bench's figures, spatialkin never imports planar), and a copy of the packages with one deliberate wrong import
breaks them."""
import pathlib
import shutil
import subprocess
import sys

import pytest

pytest.importorskip("importlinter")
ROOT = pathlib.Path(__file__).parents[1]
#: lint-imports: the command import-linter installs, beside this Python.
LINT = [sys.executable, "-c", "import sys; from importlinter.cli import lint_imports_command as c; sys.exit(c())"]


def lint(cwd, env=None):
    return subprocess.run(LINT, cwd=cwd, capture_output=True, text=True, env=env, timeout=300)


def test_the_import_contracts_hold():
    run = lint(ROOT)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    assert "12 kept, 0 broken" in run.stdout


def test_a_wrong_import_breaks_a_contract(tmp_path):
    """geometry importing tracing (a placed surface asking the tracer) is caught."""
    for package in ("spatialkin", "planar"):
        shutil.copytree(ROOT / package, tmp_path / package, ignore=shutil.ignore_patterns("__pycache__", "*.nbc",
                                                                                          "*.nbi"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    frame = tmp_path / "spatialkin" / "geometry" / "frame.py"
    frame.write_text(frame.read_text() + "\nfrom ..tracing import intersect  # noqa: E402,F401  (the breach)\n")
    run = lint(tmp_path, env={"PYTHONPATH": str(tmp_path), "PATH": ""})
    assert run.returncode != 0
    assert "geometry: no import of a layer above BROKEN" in run.stdout
    assert "spatialkin.geometry.frame -> spatialkin.tracing" in run.stdout
