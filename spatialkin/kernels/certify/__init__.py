"""Compiled kernels of the certified path."""
