"""Kernels of spatialkin.tracing.search: certified root isolation of the topology stage (topology)."""
