"""Length units the looper job and its pictures know, for figures at machine speed in SI."""

#: Metres per length unit (the unit a drive's lengths are given in).
METRES_PER_UNIT = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}
#: Standard gravity (m/s^2), to state accelerations in g.
STANDARD_GRAVITY = 9.80665
