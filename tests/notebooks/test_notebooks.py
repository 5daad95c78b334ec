"""Every notebook in notebooks/ runs top to bottom in a fresh kernel (nbclient), using only the public API;
a cell that raises fails the test. Cells' own prints carry the measured checks. The layout is checked without
running them: stored without outputs, an opening markdown cell, a closing "What to try next", a gallery picture
(notebooks/figures/<name>.png, from the cell tagged "gallery") shown in notebooks/README.md, and no development
history."""
import pathlib
import re

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

FOLDER = pathlib.Path(__file__).parents[2] / "notebooks"
NOTEBOOKS = sorted(FOLDER.glob("*.ipynb"))
#: Per-cell time limit (s): generous for a cold numba cache on a fresh machine.
CELL_TIMEOUT = 600


def test_there_are_notebooks():
    assert {p.name[0] for p in NOTEBOOKS} >= {"a", "b", "c", "d", "e", "f"}


#: Words of development history that tutorials do not carry (cite the papers instead).
HISTORY = re.compile(r"seed[ -]?00\d|the seed\b|\.\./shared|this session|farm-bench|\bissue \d+", re.I)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_layout(path):
    nb = nbformat.read(path, as_version=4)
    assert nb.cells[0].cell_type == "markdown" and "What this shows" in nb.cells[0].source
    assert nb.cells[-1].cell_type == "markdown" and nb.cells[-1].source.startswith("## What to try next")
    assert all(not cell.get("outputs") for cell in nb.cells if cell.cell_type == "code"), "stored without outputs"
    assert sum("gallery" in cell.metadata.get("tags", []) for cell in nb.cells) == 1
    assert (FOLDER / "figures" / f"{path.stem}.png").is_file()
    assert f"figures/{path.stem}.png" in (FOLDER / "README.md").read_text()
    assert not HISTORY.findall("\n".join(cell.source for cell in nb.cells))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, tmp_path):
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    images = sum("image/png" in out.get("data", {}) for cell in nb.cells if cell.cell_type == "code"
                 for out in cell.outputs)
    assert images >= 2, "a notebook shows its figures"
