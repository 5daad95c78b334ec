"""spatialkin: surface-surface intersection by arc length (Dragilev's method) and the kinematics of
spatial mechanisms of sewing and knitting machines."""
from .frame import Frame, rotation_about, rotation_to_z
from .surfaces import Cone, Cylinder, Plane, Sphere, Surface, Torus
from .tracing.result import Curve, TracingError
from .tracing.start import auxiliary_starts
from .tracing.trace import trace
from .tracing.intersect import intersect
from .tracing.batch import BatchError, intersect_many
from .tracing.placement import CoincidentSurfacesError
from .tracing.topology import TopologyError

__all__ = ["Frame", "rotation_about", "rotation_to_z", "Surface", "Torus", "Sphere", "Plane", "Cylinder",
           "Cone", "Curve", "TracingError", "trace", "intersect", "intersect_many", "BatchError", "auxiliary_starts", "CoincidentSurfacesError",
           "TopologyError"]
__version__ = "0.2.0"
