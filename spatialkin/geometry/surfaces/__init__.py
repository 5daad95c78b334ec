"""Placed surfaces: torus (ring, horn, spindle), sphere, plane, cylinder and cone, one module per kind.

Each surface is a thin object over a packed float array (``surface.data``) that the jitted kernels of
``spatialkin.kernels.geometry.surfaces`` read; see that module for the local parametrisations. Each kind's module also
declares the kind's traits (spatialkin.geometry.traits) and registers them: a new kind is its own module plus that
registration (over one of the kernels' geometries; see spatialkin.geometry.traits for the limit).
"""
from .base import Surface, check_positive, check_range, check_surface  # noqa: F401  (the checks, re-exported)
from .torus import Torus
from .sphere import Sphere
from .plane import Plane
from .cylinder import Cylinder
from .cone import Cone

__all__ = ["Surface", "Torus", "Sphere", "Plane", "Cylinder", "Cone"]
