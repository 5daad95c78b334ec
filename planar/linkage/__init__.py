"""planar.linkage: general planar linkages of revolute joints driven by geared cranks.

The model and its solution (``model``: Crank, Link, Linkage), the motion at the requested input angles
(``motion``: LinkageMotion, LockError), the jitted loop-closure kernels (``kernels``), ready-made linkages
(``examples``: fnf_sixbar), pictures (``figures``) and DXF drawings (``export``: write_dxf).

References
----------
S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian): the
double-crank six-link of the FNF warp-knitting machine.
"""
from . import examples
from .export import write_dxf
from .model import Crank, Link, Linkage
from .motion import LinkageMotion, LockError

__all__ = ["Crank", "Link", "Linkage", "LinkageMotion", "LockError", "examples", "write_dxf"]
