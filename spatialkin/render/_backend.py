"""The one place in spatialkin that imports pyvista, lazily: ``import spatialkin`` never needs it.

On Linux with no display (no DISPLAY or WAYLAND_DISPLAY) VTK would first try an X window, print a warning
and fall back; when libEGL is present we ask VTK for its EGL render window straight away, which renders
off-screen through Mesa (or a GPU driver) with no X server. A value the user set is kept.
"""
import ctypes.util
import os
import sys

#: VTK's switch for the OpenGL window class (VTK >= 9.4 chooses at run time, see its runtime settings).
WINDOW_ENV = "VTK_DEFAULT_OPENGL_WINDOW"
#: The EGL window class: off-screen without an X server.
EGL_WINDOW = "vtkEGLRenderWindow"


def headless():
    """True on Linux with no X or Wayland display to open a window on."""
    return (sys.platform.startswith("linux") and not os.environ.get("DISPLAY")
            and not os.environ.get("WAYLAND_DISPLAY"))


def pyvista():
    """The pyvista module, imported on first use (with VTK pointed at EGL when there is no display)."""
    if WINDOW_ENV not in os.environ and headless() and ctypes.util.find_library("EGL"):
        os.environ[WINDOW_ENV] = EGL_WINDOW
    import pyvista as pv
    return pv
