"""Kernels of spatialkin.continuation: following F(y) = 0 by arc length (implicit), and a continuation curve as a
system of the engine (follow)."""
