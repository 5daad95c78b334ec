import os

os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
