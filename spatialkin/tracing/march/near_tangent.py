"""Steps beside a near tangency: where the surfaces nearly touch at a point, two branches of the curve may pass each
other there a gap apart, on either side of a saddle of the level. A step longer than that gap may cross from one branch
to the other with no error the solver can see (the direction field is smooth along either branch, and the points
between them lie within round-off of both surfaces). So a segment that starts where the normals' sine is below
CAP_BELOW takes steps of at most STEP_PER_SINE of the distance over which the sine would fall to zero at its present
rate (the sine over its slope: on the way in, about the distance to that point), and at most GROWTH times the previous
segment's cap (at the branches' closest approach, where the slope vanishes, the cap of the way in holds); it ends where
the sine leaves the band [sine / BAND_RATIO, sine * BAND_RATIO]. Where the sine stays small along a stretch (surfaces
nearly touching along a ruling, whose branches run side by side) its slope is small and the steps are left long; near
a node the search proved (within NODE_CLEAR of the scale), the march passes by a jump, uncapped.
"""
import math

from ...kernels.march import curve as kc

#: Steps at most this share of the distance over which the sine would vanish at the segment start's slope ...
STEP_PER_SINE = 0.25
#: ... where the sine is below this (an uncapped segment ends where it falls below this over BAND_RATIO) ...
CAP_BELOW = 1e-2
#: ... and at most this many times the previous segment's cap.
GROWTH = 2.0
#: A capped segment ends where the sine falls below, or rises above, this factor of its start's.
BAND_RATIO = 2.0
#: No cap within this distance (relative to the scale) of a node the search proved.
NODE_CLEAR = 1e-2


def step_cap(y, a, b, sign, slope_step, previous, clearance, scale):
    """(largest step, band (lo, hi) of the sine) for a segment starting at the state y (4,) in the charts a, b
    (travelling the way sign says; slope_step: the arc-length step of the sine's slope, kernels.march.curve
    .degeneracy_slope), after a segment whose cap was previous (inf where none): at or above CAP_BELOW, no cap (inf)
    until the sine falls below CAP_BELOW / BAND_RATIO; None (no cap, no band) where the nearest node the search
    proved (clearance away; inf where none) lies within NODE_CLEAR times the scale, or twice the distance over which
    the sine would vanish (the march passes a node by a jump)."""
    sine = kc.degeneracy(y, a, b, 0.0, 0.0)
    if not sine < CAP_BELOW:
        return math.inf, (CAP_BELOW / BAND_RATIO, math.inf)
    slope = abs(kc.degeneracy_slope(y, a, b, float(sign), float(slope_step)))
    reach = sine / slope if slope > 0.0 else math.inf
    if math.isfinite(clearance) and clearance <= max(2.0 * reach, NODE_CLEAR * scale):
        return None
    return min(STEP_PER_SINE * reach, GROWTH * previous), (sine / BAND_RATIO, sine * BAND_RATIO)
