"""Layer 2: the arc-length Cauchy problem of an intersection curve, its start points and its results."""
