"""Where two unbounded surfaces can meet: a ball that holds their whole intersection, read from the directions in
which each one runs to infinity (SurfaceTraits.asymptote).

Seen from its origin o, a point x of a cylinder lies within asin(r / |x - o|) of the directions +-w of its axis,
a point of a cone on its own cone of directions, a point of a plane in the plane of directions normal to it. When
the two surfaces' sets of directions are an angle delta apart, a point x on both, at rho = |x - o_a| from a's
origin and so at least rho - d from b's (d = |o_a - o_b|), obeys

    delta <= asin(c_a / rho) + asin(d / rho) + asin(c_b / (rho - d))

(the middle term: the angle at x between the directions to the two origins, by the law of sines). With
asin z <= pi z / 2 on [0, 1], no common point lies farther than d + pi (c_a + c_b + d) / (2 delta) from o_a.
The surfaces are cut to a ball MARGIN times that radius: the round-off of reading it (relative 1e-12 at the least
gap allowed) cannot bring a common point near the cut, so what is proven of the cut pair (certify=True) holds of
the pair as given.
"""
import math

from .vectors import cross_list, dot_list

#: The least angle between the two surfaces' directions to infinity for which intersect cuts them to a ball (the
#: ball's radius is then at most d + 1571 (c_a + c_b + d)); below it, the pair may meet arbitrarily far out (or
#: does, along common directions), and intersect asks for trims.
MIN_GAP = 1e-3
#: The surfaces are cut to a ball this many times the bound's radius, so that no curve comes near the cut.
MARGIN = 2.0


def direction_gap(wa, angle_a, wb, angle_b):
    """The least angle between two sets of unit vectors, each the double cone at an angle in [0, pi/2] from +-w
    (w unit, (3,)): a circle of directions round w with the antipodal one, a point pair for angle 0, a great circle
    for pi/2. Two circles on the unit sphere, of angular radii r1 and r2 with centres theta apart, are
    max(0, theta - r1 - r2, |r1 - r2| - theta, r1 + r2 + theta - 2 pi) apart; the antipodal circle round w is the
    circle of radius pi - angle round it."""
    theta = math.atan2(math.hypot(*cross_list(wa, wb)), dot_list(wa, wb))
    gap = math.pi
    for ra in (angle_a, math.pi - angle_a):
        for rb in (angle_b, math.pi - angle_b):
            gap = min(gap, max(0.0, theta - ra - rb, abs(ra - rb) - theta, ra + rb + theta - 2.0 * math.pi))
    return gap


def intersection_ball(a, b):
    """(centre (3,), radius) of a ball holding every common point of two unbounded surfaces (their trims ignored),
    MARGIN times the bound of the module's docstring; None where their directions to infinity come within MIN_GAP
    of each other (unbounded_message says so)."""
    (wa, angle_a, ca, oa), (wb, angle_b, cb, ob) = asymptote(a), asymptote(b)
    gap = direction_gap([float(x) for x in wa], angle_a, [float(x) for x in wb], angle_b)
    if not gap >= MIN_GAP:
        return None
    d = math.dist(oa, ob)
    reach = d + 0.5 * math.pi * (ca + cb + d) / gap
    if reach > 0.0:
        return oa, MARGIN * reach
    # planes and cones through one point share it alone: no length but the coordinates' (any ball holds it)
    return oa, 2.0 ** -20 * max(abs(float(x)) for x in oa) or 1.0


def unbounded_message(a, b):
    """Why intersect refuses a pair of unbounded surfaces that intersection_ball cannot bound."""
    (wa, angle_a, _, _), (wb, angle_b, _, _) = asymptote(a), asymptote(b)
    gap = direction_gap([float(x) for x in wa], angle_a, [float(x) for x in wb], angle_b)
    near = ("share a direction to infinity" if gap == 0.0 else
            f"run to infinity in directions only {gap:.3g} rad apart (at least {MIN_GAP} rad needed)")
    return (f"intersect needs a bounded pair: {type(a).__name__} and {type(b).__name__} are both unbounded and "
            f"{near}, so they may meet arbitrarily far out (give a Plane u_range and v_range, a Cylinder or Cone a "
            "v_range)")


def cut_to_ball(surface, centre, radius):
    """A copy of the surface trimmed, along each parameter that is a length (a plane's u and v, a cylinder's or
    cone's axial v), to the ball's extent; a trim of the user's that lies beyond the ball keeps a piece of the same
    width at its edge (no common point lies there either)."""
    local = surface.frame.local_of(centre)
    bounds = []
    for (lo, hi), axis in zip(surface.bounds, surface.traits.parameter_axes):
        if axis is not None:
            c = float(local[axis])
            lo_cut, hi_cut = max(lo, c - radius), min(hi, c + radius)
            if not lo_cut < hi_cut:
                lo_cut, hi_cut = (lo, lo + 2.0 * radius) if math.isfinite(lo) else (hi - 2.0 * radius, hi)
            lo, hi = lo_cut, hi_cut
        bounds.append((lo, hi))
    return surface.with_bounds(bounds)


def asymptote(surface):
    """The surface's SurfaceTraits.asymptote, read once (kept in its memo)."""
    return surface.memo("asymptote", surface.traits.asymptote)


def bounded_pair(a, b):
    """(a, b) as they are when either is bounded, or where no ball holds their whole intersection (the search then
    refuses them: unbounded_message); else both cut to the ball of intersection_ball."""
    if asymptote(a) is None or asymptote(b) is None:
        return a, b
    ball = intersection_ball(a, b)
    if ball is None:
        return a, b
    return cut_to_ball(a, *ball), cut_to_ball(b, *ball)
