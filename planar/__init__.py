"""planar: kinematics of planar mechanisms of technological machines.

The Frenet-trihedron module (seed 000): laws phi(s) of a crank mechanism's driven link and the link's
kinematics, on spatialkin's trajectory pipeline. General planar linkages of revolute joints with geared
driving cranks (seed 001's double-crank six-link with a class III group): planar.Linkage,
planar.examples.fnf_sixbar().
"""
from . import examples
from .laws import CrankRocker, CrankSlider, Law, LawFromFunctions, LawFromGamma
from .link import DrivenLink
from .linkage import Crank, Link, Linkage
from .linkage_motion import LinkageMotion, LockError

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink", "Crank", "Link", "Linkage",
           "LinkageMotion", "LockError", "examples"]
