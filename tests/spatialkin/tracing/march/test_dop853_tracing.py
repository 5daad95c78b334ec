"""The tracer on the compiled DOP853 engine (the default 'compiled'): lengths against closed forms where DOP853's
optimistic error estimate on long steps would show without the step cap (spatialkin.tracing.march.trace.MAX_STEP), the
hand-over to the same compiled engine, and an apex passed beside without re-firing its event at every restart."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.march import ivp

from tests.oracles.ssi_cases import all_cases

#: A loop's length against its closed form (relative to the scene scale): tol is 1e-10.
LENGTH_TOL = 1e-10


def case(name):
    return next(c for c in all_cases() if c.name == name)


@pytest.mark.parametrize("method", ["compiled", "compiled-rk45"])
def test_circle_of_a_plane_across_a_torus_axis_has_its_length(method):
    """aligned/plane-torus/0: the plane normal to the torus's axis at distance d cuts it in two circles, the inner
    of radius R - sqrt(r^2 - d^2) (closed form). Uncapped, DOP853 accepts steps of 0.75 there (a circle of radius
    0.93) with 40 times the tolerance's local error, and the loop's length is 2.8e-8 off; with steps capped at
    0.2 x scale it is within LENGTH_TOL x scale, both methods."""
    c = case("aligned/plane-torus/0")
    plane, torus = c.a, c.b
    axis = torus.frame.rotation[:, 2]
    d = abs(float((plane.frame.origin - torus.frame.origin) @ axis))
    assert abs(abs(float(plane.frame.rotation[:, 2] @ axis)) - 1.0) < 1e-15      # (the plane is normal to the axis)
    inner = 2 * math.pi * (torus.major_radius - math.sqrt(torus.minor_radius ** 2 - d * d))
    for a, b in ((plane, torus), (torus, plane)):
        loops = [curve for curve in sk.intersect(a, b, method=method) if curve.closed]
        assert len(loops) == 1
        assert abs(loops[0].length - inner) <= LENGTH_TOL * max(1.0, inner)


def test_apex_beside_the_curve_is_passed_once(monkeypatch):
    """aligned/cone-cone/0: the curve passes 1.3e-3 from an apex that the topology stage proved off it. Watched at
    every segment start, its apex event would fire again at the start of each following segment (up to MAX_SEGMENTS
    empty segments); the branch goes round it with the apex unwatched until clear of it: a handful of integrations
    (at most 20), all by the compiled engine (the hand-over too), and the same curves as with RK45's steps."""
    c = case("aligned/cone-cone/0")
    methods = []
    original = ivp.integrate

    def counted(system, span, y0, method, *args, **kwargs):
        methods.append(method)
        return original(system, span, y0, method, *args, **kwargs)

    monkeypatch.setattr(ivp, "integrate", counted)
    ours = sk.intersect(c.b, c.a)
    assert 0 < len(methods) <= 20 and set(methods) == {"compiled"}
    monkeypatch.setattr(ivp, "integrate", original)
    theirs = sk.intersect(c.b, c.a, method="compiled-rk45")
    assert [x.status for x in ours] == [x.status for x in theirs] == ["boundary"] * 3
    np.testing.assert_allclose([x.length for x in ours], [x.length for x in theirs], rtol=0, atol=1e-8)
