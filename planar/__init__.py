"""planar: kinematics of planar mechanisms of technological machines.

Two families, one subpackage each:

* ``planar.frenet`` (seed 000): laws phi(s) of a crank mechanism's driven link relative to the Frenet
  trihedron on the crank pin and the link's kinematics, on spatialkin's trajectory pipeline;
* ``planar.linkage`` (seed 001): general planar linkages of revolute joints with geared driving cranks, such
  as the double-crank six-link with a class III group (``planar.examples.fnf_sixbar()``).

Their public names are re-exported here.
"""
from . import frenet, linkage
from .frenet import CrankRocker, CrankSlider, DrivenLink, Law, LawFromFunctions, LawFromGamma
from .linkage import Crank, Link, Linkage, LinkageMotion, LockError, examples

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink", "Crank", "Link", "Linkage",
           "LinkageMotion", "LockError", "examples", "frenet", "linkage"]
