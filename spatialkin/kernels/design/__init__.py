"""Kernels of spatialkin.design: products of truncated Taylor jets (jet)."""
