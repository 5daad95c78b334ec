"""A point moving along a curve parametrised by arc length: its position, first and second derivatives, and the
map from s to time that gives velocity and acceleration (spatial and planar mechanisms both use it)."""
