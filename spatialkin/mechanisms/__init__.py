"""Layer 4: mechanisms built on the tracer and the trajectory pipeline."""
from .looper import LooperDrive, LooperMotion, PointMotion

__all__ = ["LooperDrive", "LooperMotion", "PointMotion"]
