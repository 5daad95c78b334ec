"""The surface-traits registry (spatialkin.geometry.traits): lookups by class, instance, packed data and kind code;
typed errors for unknown kinds and bad registrations; the built-in kinds' declarations against the
parametrisations they describe."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.kernels.geometry import surfaces as ks
from spatialkin.geometry.traits import (ANGLE, LENGTH, SurfaceTraits, UnknownSurfaceKindError, check_surface,
                                       register, traits)

#: Parametrisations are compared with their declarations to this (round-off of the kernels' trigonometry).
ROUND_OFF = 1e-12

BUILT_IN = {
    "torus": lambda: sk.Torus(2.0, 0.7, sk.Frame((0.1, -0.2, 0.3), sk.rotation_about((1, 2, 3), 0.4))),
    "spindle": lambda: sk.Torus(0.5, 0.8),
    "sphere": lambda: sk.Sphere(1.3, sk.Frame((1.0, 0.0, 0.0))),
    "plane": lambda: sk.Plane(sk.Frame((0.0, 0.0, 1.0)), u_range=(-1.0, 2.0), v_range=(0.0, 3.0)),
    "cylinder": lambda: sk.Cylinder(0.6, v_range=(-1.0, 2.0)),
    "cone": lambda: sk.Cone(0.5, sk.Frame((0.0, 1.0, 0.0)), v_range=(-1.0, 2.0)),
}


@pytest.mark.parametrize("name", sorted(BUILT_IN))
def test_lookups_agree_and_built_in_codes_are_their_geometries(name):
    surface = BUILT_IN[name]()
    kind = traits(surface)
    assert traits(type(surface)) is kind and traits(surface.data) is kind and traits(surface.kind) is kind
    assert kind.code == kind.geometry == int(surface.data[ks.GEOMETRY]) == int(surface.data[ks.KIND])


@pytest.mark.parametrize("name", sorted(BUILT_IN))
def test_declared_periods_and_collapse_lines_hold_on_the_parametrisation(name):
    """Oracle, identities of the parametrisation: S(u + 2 pi, v) = S(u, v) along each periodic parameter (and not
    along a periodic-looking length); S_u = 0 all along each collapse line v (the chart collapses to one point), and
    S_u != 0 off them. (A sphere's latitude is not declared periodic, its chart covering half a turn.)"""
    surface = BUILT_IN[name]()
    kind = traits(surface)
    scale = surface.size
    u = np.linspace(-3.0, 3.0, 13)
    v = np.full_like(u, 0.37)
    for j, periodic in enumerate(kind.periodic):
        shifted = (u + 2 * math.pi, v) if j == 0 else (u, v + 2 * math.pi)
        same = np.max(np.abs(surface.point(*shifted) - surface.point(u, v))) <= ROUND_OFF * scale
        assert same or not periodic
        if kind.units[j] == LENGTH:
            assert not same
    for line in kind.collapse_lines(surface):
        speeds = [np.linalg.norm(surface.derivatives(x, line)[ks.DU]) for x in u]
        assert max(speeds) <= ROUND_OFF * scale
    assert min(np.linalg.norm(surface.derivatives(x, 0.37)[ks.DU]) for x in u) > 1e-3 * scale


@pytest.mark.parametrize("name", sorted(BUILT_IN))
def test_bounding_ball_holds_the_trimmed_surface(name):
    """Oracle: every point of a grid over the natural domain lies in the declared ball."""
    surface = BUILT_IN[name]()
    kind = traits(surface)
    centre, radius = kind.bounding_ball(surface)
    (u0, u1), (v0, v1) = kind.natural_domain(surface)
    uu, vv = np.meshgrid(np.linspace(u0, u1, 41), np.linspace(v0, v1, 41))
    reach = np.linalg.norm(surface.point(uu, vv) - centre, axis=-1)
    assert np.max(reach) <= radius * (1 + ROUND_OFF)
    assert kind.extent(surface) >= radius


def test_units_set_the_tolerance_scale_per_parameter():
    kinds = {name: traits(make()) for name, make in BUILT_IN.items()}
    assert kinds["plane"].units == (LENGTH, LENGTH) and kinds["torus"].units == (ANGLE, ANGLE)
    assert kinds["cone"].parameter_units(5.0).tolist() == [1.0, 5.0]


class Unregistered(sk.Surface):
    def __init__(self):
        super().__init__(None)


def test_unknown_kinds_raise_a_typed_error():
    """An unregistered class, or data whose kind code no kind declares, never falls into another kind's defaults."""
    with pytest.raises(UnknownSurfaceKindError, match="Unregistered"):
        Unregistered()
    data = sk.Sphere(1.0).data.copy()
    data[ks.KIND] = 77.0
    with pytest.raises(UnknownSurfaceKindError, match="77"):
        traits(data)
    with pytest.raises(TypeError, match="a must be a spatialkin surface"):
        check_surface("a", object())
    with pytest.raises(TypeError, match="spatialkin surface"):
        sk.intersect(object(), sk.Sphere(1.0))


def test_registration_is_checked():
    class Half(SurfaceTraits):
        code, geometry, name = 101, ks.SPHERE, "half"

    with pytest.raises(ValueError, match="undeclared"):
        register(Unregistered, Half())

    class NewGeometry(SurfaceTraits):
        code, geometry, name, rank = 102, 99, "new", 0
        units, periodic, parameter_axes = (ANGLE, ANGLE), (True, True), (None, None)
        compact = recharts = area_watch = has_parallels = False

    with pytest.raises(ValueError, match="geometry"):
        register(Unregistered, NewGeometry())
    taken = NewGeometry()
    taken.code, taken.geometry = ks.SPHERE, ks.SPHERE
    with pytest.raises(ValueError, match="registered already"):
        register(Unregistered, taken)
    with pytest.raises(UnknownSurfaceKindError):
        traits(Unregistered)                   # nothing was filed by the refused registrations
