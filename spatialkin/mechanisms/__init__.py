"""Mechanisms built on the tracer and the trajectory pipeline: the looper drive of blind-stitch sewing machines
(``LooperDrive``, a spatial five-link crank-rocker whose ball centre runs on torus ∩ sphere) and the spatial
four-bar RSSR, with their motions (``LooperMotion``, ``RSSRMotion``, ``PointMotion``).

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]).
"""
from .common import PointMotion
from .looper.drive import LooperDrive, LooperMotion
from .rssr import RSSR, RSSRMotion

__all__ = ["LooperDrive", "LooperMotion", "PointMotion", "RSSR", "RSSRMotion"]
