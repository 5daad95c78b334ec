"""Imported only by the sweep's forkserver: evaluates the reference geometry once so that every worker forked
from the server inherits the jitted kernels already loaded from numba's cache (a fresh worker would spend a
second or more loading them)."""
from .looper import LooperDesign
from .sweep import evaluate

evaluate(LooperDesign.reference(), ("swing", "min_transmission", "assembly_margin"))
