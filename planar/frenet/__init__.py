"""planar.frenet: a crank mechanism's driven link described in the moving Frenet trihedron (seed 000).

Laws phi(s) of the driven link relative to the trihedron on the crank pin (``laws``: CrankSlider,
CrankRocker, LawFromFunctions, LawFromGamma; their jitted kernels in ``kernels``), the link's kinematics on
spatialkin's trajectory pipeline (``link``: DrivenLink) and the seed's pictures (``figures``).
"""
from .laws import CrankRocker, CrankSlider, Law, LawFromFunctions, LawFromGamma
from .link import DrivenLink

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink"]
