"""Layer 4: mechanisms built on the tracer and the trajectory pipeline."""
from .common import PointMotion
from .looper import LooperDrive, LooperMotion
from .rssr import RSSR, RSSRMotion

__all__ = ["LooperDrive", "LooperMotion", "PointMotion", "RSSR", "RSSRMotion"]
