"""Kernels of spatialkin.tracing.curve: a traced curve's stored points corrected span by span (stored), and
distances of points from its dense output (near)."""
