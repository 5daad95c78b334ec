"""Kernels of spatialkin.mechanisms: the spatial four-link RSSR (rssr)."""
