"""Measured against the surfaces: the largest distance of curves' points to two surfaces (their exact distance
functions)."""
import numpy as np


def on_both(curves, a, b, samples=200):
    """Largest distance of the stored points and `samples` dense evaluations per curve to either surface."""
    worst = 0.0
    for c in curves:
        pts = c.points if c.length == 0 else np.vstack([c.points, c(np.linspace(0, c.length, samples))])
        worst = max(worst, float(np.max(a.distance(pts))), float(np.max(b.distance(pts))))
    return worst
