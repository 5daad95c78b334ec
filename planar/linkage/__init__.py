"""planar.linkage: general planar linkages of revolute joints driven by geared cranks (seed 001).

The model and its solution (``model``: Crank, Link, Linkage), the motion at the requested input angles
(``motion``: LinkageMotion, LockError), the jitted loop-closure kernels (``kernels``), ready-made linkages
(``examples``: fnf_sixbar), pictures (``figures``) and DXF drawings (``export``: write_dxf).
"""
from . import examples
from .export import write_dxf
from .model import Crank, Link, Linkage
from .motion import LinkageMotion, LockError

__all__ = ["Crank", "Link", "Linkage", "LinkageMotion", "LockError", "examples", "write_dxf"]
