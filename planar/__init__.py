"""planar: kinematics of planar mechanisms (Frenet-trihedron laws, multi-input linkages).

Built on spatialkin's trajectory pipeline; the modules arrive with their issues.
"""
