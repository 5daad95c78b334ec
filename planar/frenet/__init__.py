"""planar.frenet: a crank mechanism's driven link described in the moving Frenet trihedron.

Laws phi(s) of the driven link relative to the trihedron on the crank pin (``laws``: CrankSlider,
CrankRocker, LawFromFunctions, LawFromGamma; their jitted kernels in ``kernels``), the link's kinematics on
spatialkin's trajectory pipeline (``link``: DrivenLink) and the paper's pictures (``figures``).

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven
member using Frenet trihedron", 2017.
"""
from .laws import CrankRocker, CrankSlider, Law, LawFromFunctions, LawFromGamma
from .link import DrivenLink

__all__ = ["Law", "CrankSlider", "CrankRocker", "LawFromFunctions", "LawFromGamma", "DrivenLink"]
