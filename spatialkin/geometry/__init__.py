"""Geometry: frames and placed surfaces (one module per kind, with their CAD-face trims), their traits and the
placement rules; what every layer above knows about a surface. It imports only the kernels and the library
helpers below it."""
from .frame import Frame, rotation_about
from .surfaces import Cone, Cylinder, Plane, Sphere, Surface, Torus

__all__ = ["Frame", "rotation_about", "Surface", "Torus", "Sphere", "Plane", "Cylinder", "Cone"]
