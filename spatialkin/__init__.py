"""spatialkin: surface-surface intersection by arc length (Dragilev's method) and the kinematics of
spatial mechanisms of sewing and knitting machines.

The intersection line of two surfaces is parametrised by its arc length and found as the solution of a Cauchy
problem (Dragilev's method); the looper drive of blind-stitch sewing machines, a spatial five-link crank-rocker,
moves its ball centre along such a line, torus ∩ sphere ([Looper]).

- ``Frame``, ``rotation_about``, ``rotation_to_z``: placements (global = origin + rotation @ local);
- ``Torus``, ``Sphere``, ``Plane``, ``Cylinder``, ``Cone``: placed surfaces (``point``, ``distance``);
- ``trace`` (one component from a start), ``intersect`` (every component; ``certify=True`` for a proof),
  ``intersect_many`` (many pairs): ``Curve`` objects, parametrised by arc length;
- ``TracingError``, ``TopologyError``, ``CoincidentSurfacesError``, ``BatchError``, ``CertificationError``: what
  they raise;
- ``spatialkin.mechanisms.LooperDrive`` (the looper drive's motion) and ``spatialkin.design`` (sensitivities,
  fits and sweeps of its geometry).

Angles are in radians, lengths in the user's unit, arrays have the point index first.

References
----------
[Looper] "Investigation of the trajectories of characteristic points of spatial mechanisms of technological
machines of the light industry" (Дослідження траєкторій характерних точок просторових механізмів технологічних
машин галузей легкої промисловості; in Ukrainian).
"""
from ._lib.version import __version__  # noqa: F401  (the package version)

# (before the kernels are imported: a cold cache runs them as plain Python while they compile in the background)
from ._lib import warm as _warm

_warm.decide()

from .geometry.frame import Frame, rotation_about, rotation_to_z  # noqa: E402
from .geometry.surfaces import Cone, Cylinder, Plane, Sphere, Surface, Torus  # noqa: E402
from .tracing.curve.result import Curve, TracingError  # noqa: E402
from .tracing.march.start import auxiliary_starts  # noqa: E402
from .tracing.single import trace  # noqa: E402
from .tracing.components import intersect  # noqa: E402
from .tracing.batch import BatchError, intersect_many  # noqa: E402
from .geometry.placement import CoincidentSurfacesError  # noqa: E402
from .tracing.search.topology import TopologyError  # noqa: E402
from .tracing.certify.certificate import CertificationError  # noqa: E402

__all__ = ["Frame", "rotation_about", "rotation_to_z", "Surface", "Torus", "Sphere", "Plane", "Cylinder",
           "Cone", "Curve", "TracingError", "trace", "intersect", "intersect_many", "BatchError", "auxiliary_starts", "CoincidentSurfacesError",
           "TopologyError", "CertificationError"]
