"""planar: kinematics of planar mechanisms of technological machines.

The Frenet-trihedron module (seed 000): laws phi(s) of a crank mechanism's driven link and the link's
kinematics, on spatialkin's trajectory pipeline.
"""
from .laws import CrankRocker, CrankSlider, Law, LawFromFunctions, LawFromGamma
from .link import DrivenLink

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink"]
