"""The looper drive of blind-stitch sewing machines: the drive and its motion (``drive``), its reference geometry
(``reference``) and what its analyses read off the motion (``analysis``: dead positions, transmission angles)."""
from .drive import LooperDrive, LooperMotion

__all__ = ["LooperDrive", "LooperMotion"]
