"""planar: kinematics of planar mechanisms of technological machines.

Two families, one subpackage each:

* ``planar.frenet``: laws phi(s) of a crank mechanism's driven link relative to the Frenet trihedron on the
  crank pin and the link's kinematics, on spatialkin's trajectory pipeline (CrankSlider, CrankRocker,
  DrivenLink);
* ``planar.linkage``: general planar linkages of revolute joints with geared driving cranks, such as the
  double-crank six-link with a class III group of a warp-knitting machine (``planar.examples.fnf_sixbar()``).

Their public names are re-exported here. Angles in radians, lengths in the user's unit, arrays with the point
index first.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven
member using Frenet trihedron", 2017.
S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian).
"""
import sys

from spatialkin._lib import warm as _warm

# (before planar's kernels are imported: a cold cache runs them as plain Python while they compile in the background)
_warm.register("planar.warmup")

from . import frenet  # noqa: E402
from . import linkage  # noqa: E402
from .frenet import CrankRocker, CrankSlider, DrivenLink, Law, LawFromFunctions, LawFromGamma  # noqa: E402
from .linkage import Crank, Link, Linkage, LinkageMotion, LockError, examples  # noqa: E402

# ``import planar.examples`` (as the tutorials spell it) is the module planar.linkage.examples itself
sys.modules[__name__ + ".examples"] = examples

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink", "Crank", "Link", "Linkage",
           "LinkageMotion", "LockError", "examples", "frenet", "linkage"]
