"""The ball that holds the whole intersection of two unbounded surfaces (spatialkin.geometry.asymptotic).

Oracles: the least angle between two sets of directions by brute force over sampled directions; points of one
surface sampled beyond the ball's bound, off the other surface (its exact distance function)."""
import math

import numpy as np
import pytest
from tests.oracles.closed_forms import random_rotation
from tests.oracles.unbounded import unbounded_pair

import spatialkin as sk
from spatialkin.geometry.asymptotic import MARGIN, MIN_GAP, cut_to_ball, direction_gap, intersection_ball


def cone_directions(w, angle, n=4000):
    """n unit vectors on the circle at `angle` from w, and their opposites (the double cone of directions)."""
    w = np.asarray(w, float)
    e = np.cross(w, [1.0, 0.0, 0.0] if abs(w[0]) < 0.9 else [0.0, 1.0, 0.0])
    e /= np.linalg.norm(e)
    f = np.cross(w, e)
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)[:, None]
    d = math.cos(angle) * w + math.sin(angle) * (np.cos(t) * e + np.sin(t) * f)
    return np.vstack([d, -d])


@pytest.mark.parametrize("seed", range(40))
def test_direction_gap_is_the_least_angle_between_the_sampled_sets(seed):
    """Two random double cones of directions (angles 0, pi/2 or between): the gap never exceeds the least sampled
    angle, and lies within the sampling's resolution (2 pi / 4000 on each circle) of it."""
    rng = np.random.default_rng(seed)
    angles = [0.0, 0.5 * math.pi, *rng.uniform(0.0, 0.5 * math.pi, 2)]
    wa, wb = random_rotation(rng)[:, 0], random_rotation(rng)[:, 0]
    aa, ab = angles[seed % 4], angles[(seed // 4) % 4]
    gap = direction_gap(list(wa), aa, list(wb), ab)
    da, db = cone_directions(wa, aa), cone_directions(wb, ab)
    brute = float(np.arccos(np.clip(np.max(da @ db.T), -1.0, 1.0)))
    assert gap <= brute + 1e-12
    assert brute - gap <= 2 * math.pi / 4000 * 1.01 + 1e-7


def test_direction_gap_in_closed_form():
    """An axis and a plane's normal theta apart: pi/2 - theta; a cone's circle and an axis theta apart:
    |theta - a|; two great circles always meet."""
    z = [0.0, 0.0, 1.0]
    for theta in (0.0, 0.3, 1.0, math.pi / 2):
        w = [math.sin(theta), 0.0, math.cos(theta)]
        assert direction_gap(z, 0.0, w, math.pi / 2) == pytest.approx(math.pi / 2 - theta, abs=1e-15)
        assert direction_gap(z, 0.4, w, 0.0) == pytest.approx(min(abs(theta - 0.4), abs(math.pi - theta - 0.4)),
                                                              abs=1e-15)
        assert direction_gap(z, math.pi / 2, w, math.pi / 2) == 0.0


def unbounded_pairs(seed):
    """A random unbounded pair, origins within 2 of each other, sizes about 1."""
    return unbounded_pair(seed, 1.0, (0.2, 1.5), (0.1, 1.3))


def far_points(surface, centre, rho, n=400):
    """Points of the untrimmed surface at distances rho[k] (a list) from centre, n per distance and sheet."""
    out = []
    kind = type(surface).__name__
    rot, origin = surface.frame.rotation, surface.frame.origin
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    for r in rho:
        for sign in (1.0, -1.0):
            if kind == "Plane":             # a circle of the plane about the foot of centre, radius r
                foot = centre - ((centre - origin) @ rot[:, 2]) * rot[:, 2]
                pts = foot + r * (np.cos(t)[:, None] * rot[:, 0] + np.sin(t)[:, None] * rot[:, 1])
                if sign < 0:
                    continue
            else:                           # the parallel at height v = sign r (local)
                v = sign * r + float(surface.frame.to_local(centre)[2])
                rad = surface.radius if kind == "Cylinder" else abs(v) * math.tan(surface.half_angle)
                pts = origin + v * rot[:, 2] + rad * (np.cos(t)[:, None] * rot[:, 0] + np.sin(t)[:, None] * rot[:, 1])
            out.append(pts[np.linalg.norm(pts - centre, axis=1) >= r])
    return np.vstack(out)


@pytest.mark.parametrize("seed", range(27))
def test_no_common_point_lies_beyond_the_bound(seed):
    """Points of either surface sampled beyond the bound (the ball's radius over MARGIN) up to 1000 times it lie
    off the other surface: their distance to it is positive, and grows with the distance from the centre."""
    a, b = unbounded_pairs(seed)
    ball = intersection_ball(a, b)
    if ball is None:
        assert direction_gap(list(a.traits.asymptote(a)[0]), a.traits.asymptote(a)[1],
                             list(b.traits.asymptote(b)[0]), b.traits.asymptote(b)[1]) < MIN_GAP
        return
    centre, radius = ball
    bound = radius / MARGIN
    for p, q in ((a, b), (b, a)):
        pts = far_points(p, np.asarray(centre), list(bound * np.geomspace(1.0, 1e3, 25)))
        assert len(pts) and float(np.min(q.distance(pts))) > 0.0


def test_a_cut_keeps_the_angular_trims_and_shows_the_cut():
    """cut_to_ball trims the lengths (a cylinder's v, a plane's u and v) to the ball about a point, keeps an
    angular range, and keeps a piece as wide as the ball where the user's half-infinite trim lies beyond it."""
    cyl = sk.Cylinder(1.0, sk.Frame((0.0, 0.0, 5.0)), u_range=(0.0, 1.0))
    cut = cut_to_ball(cyl, np.zeros(3), 2.0)
    assert cut.v_range == (-7.0, -3.0) and cut.u_range == cyl.u_range and cut.region == cyl.region
    assert cyl.v_range == (-math.inf, math.inf)               # the given surface is unchanged
    plane = cut_to_ball(sk.Plane(sk.Frame((1.0, 2.0, 3.0))), np.zeros(3), 1.0)
    assert plane.u_range == (-2.0, 0.0) and plane.v_range == (-3.0, -1.0)
    beyond = cut_to_ball(sk.Cylinder(1.0, v_range=(10.0, math.inf)), np.zeros(3), 1.0)
    assert beyond.v_range == (10.0, 12.0)
