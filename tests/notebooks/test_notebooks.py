"""Every notebook in notebooks/ runs top to bottom in a fresh kernel (nbclient), using only the public API;
a cell that raises fails the test. Cells' own prints carry the measured checks."""
import pathlib

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

NOTEBOOKS = sorted((pathlib.Path(__file__).parents[2] / "notebooks").glob("*.ipynb"))
#: Per-cell time limit (s): generous for a cold numba cache on a fresh machine.
CELL_TIMEOUT = 600


def test_there_are_notebooks():
    assert {p.name[0] for p in NOTEBOOKS} >= {"a", "b", "c", "d"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, tmp_path):
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    images = sum("image/png" in out.get("data", {}) for cell in nb.cells if cell.cell_type == "code"
                 for out in cell.outputs)
    assert images >= 2, "a notebook shows its figures"
