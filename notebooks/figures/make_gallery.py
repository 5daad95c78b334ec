"""Make the gallery pictures: run every notebook in ../ (nbclient, a fresh kernel each) and write the picture of
its cell tagged "gallery" to <notebook name>.png here. bench_kinds.png comes from `spatialkin bench --out DIR`.

    python notebooks/figures/make_gallery.py [NAME ...]      # all notebooks, or those whose name starts so
"""
import base64
import pathlib
import sys
import tempfile

import nbclient
import nbformat

HERE = pathlib.Path(__file__).resolve().parent
TAG = "gallery"


def gallery_png(path):
    """PNG bytes of the first picture the notebook's cell tagged TAG shows."""
    nb = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory() as work:
        nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                resources={"metadata": {"path": work}}).execute()
    for cell in nb.cells:
        if TAG in cell.metadata.get("tags", []):
            for out in cell.get("outputs", []):
                if "image/png" in out.get("data", {}):
                    return base64.b64decode(out["data"]["image/png"])
    raise ValueError(f"{path.name}: no picture in a cell tagged {TAG!r}")


def main(prefixes):
    for path in sorted(HERE.parent.glob("*.ipynb")):
        if not prefixes or path.name.startswith(tuple(prefixes)):
            target = HERE / f"{path.stem}.png"
            target.write_bytes(gallery_png(path))
            print(f"wrote {target}")


if __name__ == "__main__":
    main(sys.argv[1:])
