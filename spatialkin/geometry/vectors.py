"""Small 3-vectors: numpy's cross costs about 50 us a call on two 3-vectors (numpy 2.x), far more than its six
products; ``cross`` computes the same products in the same order (bit for bit np.cross's). ``cross_list`` holds
those products, as a list, and ``dot_list`` is the dot product, for scalar code on lists of floats
(spatialkin.tracing.closed), where building an array and computing on its numpy scalars costs more than the
arithmetic itself (a third of a plane-plane intersection's time, measured)."""
import numpy as np


def dot_list(x, y):
    """x . y, a float, of two 3-vectors (sequences or arrays (3,)): the products summed left to right."""
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]


def cross_list(x, y):
    """x x y as a list of 3 floats, of two 3-vectors (sequences or arrays (3,))."""
    return [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]


def cross(x, y):
    """x x y (3,) of two 3-vectors."""
    return np.array(cross_list(x, y))
