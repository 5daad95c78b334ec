"""The arc-length Cauchy problem of an intersection curve (Dragilev's method): marching along a component
(``march``), the topology search for every component (``search``), the pairs solved in closed form (``closed``),
the curve record and ``Curve`` (``curve``), what certify=True proves (``certify``); ``intersect`` (``components``)
and ``intersect_many`` (``batch``) on top."""
from .curve.result import Curve, TracingError
from .single import trace
from .components import intersect
from .batch import BatchError, intersect_many
from .search.topology import TopologyError
from .certify.certificate import CertificationError

__all__ = ["Curve", "TracingError", "trace", "intersect", "intersect_many", "BatchError", "TopologyError",
           "CertificationError"]
