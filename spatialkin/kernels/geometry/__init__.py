"""Kernels of spatialkin.geometry: placed surfaces' points, derivatives, implicit values, distances and inverse maps
(surfaces), and their interval enclosures with outward rounding (interval)."""
