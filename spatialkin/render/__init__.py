"""Pictures of spatialkin's results with pyvista (the presentation layer's only pyvista user).

pyvista is imported when a scene first makes a dataset, never by ``import spatialkin`` or by importing this
package. Rendering is off-screen by default.

    from spatialkin.render import Scene, looper_scene
"""
from .looper import looper_scene
from .scene import Scene

__all__ = ["Scene", "looper_scene"]
