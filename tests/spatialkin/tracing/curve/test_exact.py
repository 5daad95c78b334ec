"""The closed-form dense outputs' helpers (spatialkin.tracing.curve.exact and .conic) against the numpy calls they stand
for, bit for bit (tolerance 0: they promise numpy's own arithmetic), the closed forms' settings (Scene) against
make_settings (exactly equal, and the same errors for bad options), and their messages made on first access against
the status table's."""
import math

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing.closed.forms import closed_settings
from spatialkin.tracing.closed.conic import quarter_turn
from spatialkin.tracing.curve.exact import CircleSolution, SegmentSolution, counting, even
from spatialkin.tracing.march.trace import (DEFAULT_METHOD, DEFAULT_PULLBACK, DEFAULT_RTOL, DEFAULT_SINGULAR_TOL,
                                      make_settings)

#: Random (start, stop) pairs per count.
DRAWS = 200


@pytest.mark.parametrize("count", [2, 3, 17, 65, 257])
def test_even_is_linspace(count):
    """even(start, stop, count) is np.linspace(start, stop, count) bit for bit, over magnitudes from 1e-300 to
    1e300, either sign, and a zero step (start == stop)."""
    rng = np.random.default_rng(count)
    for _ in range(DRAWS):
        start, stop = (float(x) for x in rng.normal(size=2) * 10.0 ** rng.integers(-300, 300, 2))
        for lo, hi in ((start, stop), (0.0, abs(stop)), (start, start), (0.0, 5e-324)):
            assert np.array_equal(even(lo, hi, count), np.linspace(lo, hi, count))
            assert np.signbit(even(lo, hi, count)).tolist() == np.signbit(np.linspace(lo, hi, count)).tolist()
    assert np.array_equal(counting(count), np.arange(float(count)))
    assert not counting(count).flags.writeable


def test_quarter_turn_is_linspace():
    assert np.array_equal(quarter_turn(65), np.linspace(0.0, 0.5 * math.pi, 17))
    assert not quarter_turn(65).flags.writeable


def test_circle_and_segment():
    """The circle's frame as np.linalg.norm makes it, the same circle given as arrays or as floats, and points_at is
    at()[0] (circle and segment)."""
    rng = np.random.default_rng(3)
    sphere = sk.Sphere(1.0)
    for _ in range(DRAWS):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        sol = CircleSolution((sphere, sphere), rng.normal(size=3), axis, rng.uniform(0.1, 3.0))
        e1 = np.cross(axis, np.eye(3)[np.argmin(np.abs(axis))])
        assert np.array_equal(sol.e1, e1 / np.linalg.norm(e1))
        listed = CircleSolution((sphere, sphere), sol.centre.tolist(), axis.tolist(), sol.radius)    # (3 floats each)
        assert all(np.array_equal(x, y) for x, y in zip(listed.at(sol.knots), sol.at(sol.knots)))
        assert np.array_equal(sol.knots, np.linspace(0.0, sol.length, len(sol.knots)))
        assert np.array_equal(sol.points_at(sol.knots), sol.at(sol.knots)[0])
        seg = SegmentSolution((sphere, sphere), rng.normal(size=3), rng.normal(size=3))
        assert np.array_equal(seg.points_at(seg.knots), seg.at(seg.knots)[0])
        assert np.array_equal(seg.knots, np.linspace(0.0, seg.length, len(seg.knots)))


def options(**changes):
    out = dict(tol=1e-10, method=DEFAULT_METHOD, rtol=DEFAULT_RTOL, atol=None, max_length=None,
               singular_tol=DEFAULT_SINGULAR_TOL, pullback=DEFAULT_PULLBACK)
    out.update(changes)
    return out


@pytest.mark.parametrize("changes", [{}, {"tol": 1e-6}, {"max_length": 3.5}, {"singular_tol": 1e-5},
                                     {"atol": 1e-9, "rtol": 1e-8}])
def test_closed_settings_match_make_settings(changes):
    """The Scene's fields equal make_settings' (exactly), for placements far from the origin (the round-off floor
    of the tolerance) and near it, and make_settings from the Scene's checked options gives the same settings."""
    rng = np.random.default_rng(5)
    for offset in (0.0, 1e9):
        a = sk.Sphere(0.8, sk.Frame(rng.normal(size=3) + offset))
        b = sk.Plane(sk.Frame(rng.normal(size=3)), (-1.0, 2.0), (-3.0, 1.0))
        for x, y in ((a, b), (b, a)):
            scene = closed_settings(x, y, **options(**changes))
            anchor = np.concatenate([x.frame.origin, y.frame.origin])
            full = make_settings(x, y, *options(**changes).values(), True, anchor)
            for name in scene._fields[:-1]:
                assert getattr(scene, name) == getattr(full, name) and type(getattr(scene, name)) is type(
                    getattr(full, name)), name
            again = make_settings(x, y, *options(**changes).values(), True, anchor, scene.checked)
            for name in ("scale", "tolerance", "gap_tol", "max_length", "singular_tol", "pullback", "rtol"):
                assert getattr(again, name) == getattr(full, name), name
            np.testing.assert_array_equal(again.atol, full.atol)


@pytest.mark.parametrize("changes", [{"tol": -1.0}, {"tol": "x"}, {"method": "Euler"}, {"rtol": 0.0},
                                     {"atol": -1.0}, {"max_length": math.inf}, {"singular_tol": math.nan},
                                     {"pullback": -1.0}])
def test_bad_options_same_errors(changes):
    """sk.intersect on a closed-form pair raises what make_settings raises for a bad option."""
    a, b = sk.Sphere(1.0), sk.Plane(sk.Frame((0.0, 0.0, 0.3)))
    anchor = np.concatenate([a.frame.origin, b.frame.origin])
    with pytest.raises((TypeError, ValueError)) as theirs:
        make_settings(a, b, *options(**changes).values(), True, anchor)
    with pytest.raises((TypeError, ValueError)) as ours:
        sk.intersect(a, b, **options(**changes))
    assert type(ours.value) is type(theirs.value) and str(ours.value) == str(theirs.value)


def pairs():
    """The closed-form pairs of the bench (spatialkin.bench.kinds), both orders, and a plane-cone hyperbola, a
    plane-cylinder pair of lines and an open ellipse arc (a trimmed plane across a cylinder)."""
    from spatialkin.bench.kinds import pair_kind_cases
    closed = ("plane-plane", "plane-sphere", "plane-cylinder", "plane-cone", "sphere-sphere")
    out = [(a, b) for kind, a, b in pair_kind_cases() if kind in closed]
    cone = sk.Cone(0.5, sk.Frame((0.0, 0.0, 0.0), np.eye(3)), (-2.0, 2.5))
    steep = sk.Plane(sk.Frame((0.3, 0.0, 0.0), sk.rotation_about((0.0, 1.0, 0.0), math.pi / 2 - 0.2)))
    cyl = sk.Cylinder(0.8, sk.Frame((0.1, 0.0, 0.0)), (-2.0, 2.0))
    along = sk.Plane(sk.Frame((0.3, 0.0, 0.0), sk.rotation_about((0.0, 1.0, 0.0), math.pi / 2)), (-3, 3),
                     (-3, 3))
    across = sk.Plane(sk.Frame((0.0, 0.0, 0.2), sk.rotation_about((1.0, 0.0, 0.0), 0.3)), (-0.5, 0.5),
                      (-3, 3))
    out += [(steep, cone), (along, cyl), (across, cyl)]
    return out + [(b, a) for a, b in out]


def fingerprint(curve, first):
    """The stored and dense values of a curve, its dense output read first (first='dense') or its stored samples
    first (first='stored')."""
    s = np.linspace(0.0, curve.length, 7)
    out = {}
    order = (("dense", "stored") if first == "dense" else ("stored", "dense"))
    for what in order:
        if what == "dense":
            out["at"], out["dense_params"] = curve(s), curve.parameters(s)
        else:
            out["points"], out["s"], out["params"] = curve.points, curve.s, curve.params
    return out


def test_samples_made_on_first_use():
    """A closed form's stored points, arc lengths and parameters (made on first access) are the same arrays, to the
    bit, whether they or the dense output are read first, and after pickling; the result's repr and
    dataclasses.replace see them."""
    import dataclasses
    import pickle
    handled = 0
    for a, b in pairs():
        first, second = sk.intersect(a, b), sk.intersect(a, b)
        assert len(first) == len(second)
        for c, d in zip(first, second):
            handled += c.topology.mode == "closed_form"
            x, y = fingerprint(c, "dense"), fingerprint(d, "stored")
            unpickled = pickle.loads(pickle.dumps(sk.intersect(a, b)))[first.index(c)]
            z = fingerprint(unpickled, "stored")
            for key in x:
                assert np.array_equal(x[key], y[key]) and np.array_equal(x[key], z[key]), key
            e = sk.Curve(dataclasses.replace(sk.intersect(a, b)[first.index(c)].result, certificate=None))
            assert np.array_equal(e.points, y["points"]) and np.array_equal(e.params, y["params"])
            assert "points=array" in repr(c.result)
    assert handled >= 12


def test_sampled_result_init_is_curve_result_init():
    """SampledResult writes what CurveResult's generated init writes (every field, the defaults, the checks of
    __post_init__), given all fields or all but the sampled ones; a missing field or a bad status raises."""
    from spatialkin.tracing.curve.exact import SampledResult
    from spatialkin.tracing.curve.result import CurveResult
    import dataclasses
    a = sk.Sphere(1.0)
    sol = CircleSolution((a, a), np.zeros(3), np.array([0.0, 0.0, 1.0]), 1.0)
    fields = dict(closed=1, length=np.float64(2.0), status="closed", message="m", tolerance=1e-10, sol=sol, nfev=3.0)
    points, params = sol.samples()
    ours, theirs = SampledResult(**fields), CurveResult(points=points, s=sol.knots, params=params, **fields)
    given = SampledResult(points=points, s=sol.knots, params=params, **fields)
    for f in dataclasses.fields(CurveResult):
        for x in (ours, given):
            value, expected = getattr(x, f.name), getattr(theirs, f.name)
            assert type(value) is type(expected), f.name
            assert (np.array_equal(value, expected) if isinstance(value, np.ndarray) else value == expected), f.name
    assert set(ours.__dict__) == set(theirs.__dict__) and set(given.__dict__) == set(theirs.__dict__)
    with pytest.raises(ValueError):
        SampledResult(**dict(fields, status="nonsense"))
    with pytest.raises(TypeError):
        SampledResult(**{k: v for k, v in fields.items() if k != "sol"})
    with pytest.raises(TypeError):
        SampledResult(**fields, colour="red")


def test_conic_arithmetic_is_numpy():
    """A Conic's |P|^2 and |Q|^2 (the floats written out) are float(P @ P) and float(Q @ Q) to 2 ulp (a margin for a
    build whose dot product sums in another order), its centre, P and Q (arrays made on first use) np.array of the
    floats given, and a closed ellipse's quarter turn the last of quarter_turn: bit for bit, over random vectors of
    magnitudes 1e-3 to 1e3."""
    from spatialkin.tracing.closed.conic import ELLIPSE, QUARTER, Conic
    rng = np.random.default_rng(11)
    for _ in range(DRAWS):
        rows = [list(rng.normal(size=3) * 10.0 ** rng.uniform(-3, 3, 3)) for _ in range(3)]
        conic = Conic(ELLIPSE, *rows)
        P, Q = np.array(rows[1]), np.array(rows[2])
        # (numpy's @ may sum three products in another order or with FMA on another CPU: 2 ulp)
        assert abs(conic.p2 - float(P @ P)) <= 4.5e-16 * conic.p2
        assert abs(conic.q2 - float(Q @ Q)) <= 4.5e-16 * conic.q2
        for got, given in zip((conic.centre, conic.P, conic.Q), rows):
            assert np.array_equal(got, np.array(given)) and got.dtype == float
    for samples in (5, 17, 65, 129):
        assert quarter_turn(samples)[-1] == QUARTER


def test_conic_arc_one_by_one():
    """A line's and an ellipse's arc length at one float is their arc length at an array of it, bit for bit (the
    ends of an open arc are measured one by one)."""
    from spatialkin.tracing.closed.conic import ELLIPSE, LINE, Conic
    rng = np.random.default_rng(12)
    for shape in (LINE, ELLIPSE):
        for _ in range(DRAWS):
            P, Q = rng.normal(size=3), rng.normal(size=3)
            if P @ P > Q @ Q:
                P, Q = Q, P
            conic = Conic(shape, [0.0] * 3, P.tolist(), Q.tolist())
            t = rng.uniform(-7.0, 7.0, 2)
            for k in range(2):
                assert conic.arc(float(t[k])) == conic.arc(t)[k]


def test_messages_made_on_first_access():
    """A closed form's status and message (made on first access, by spatialkin.tracing.closed.forms.arc_message or
    exact.event_message) are those the status table gives for its ends or its event (outcome and open_outcome, the
    oracle kept here), read first or after pickling; a SampledResult takes a message or its maker, not both."""
    import pickle
    from spatialkin.tracing.closed.forms import arc_message
    from spatialkin.tracing.march.segments import EDGE_NAMES as EDGES
    from spatialkin.tracing.curve.exact import SampledResult, event_message
    from spatialkin.tracing.curve.status import BOUNDARY, open_outcome, outcome
    seen = set()
    for a, b in pairs():
        for c in sk.intersect(a, b):
            r = c.result
            assert c.topology.mode == "closed_form" and "message" not in r.__dict__
            maker = r._message_of
            if maker.func is event_message:                 # a circle about a common axis (exact_curve)
                assert maker.args == ("axis_circle", "circle")
                expected = outcome("axis_circle", shape="circle")
            elif maker.args[0] is None:                     # a closed conic (closed.arc_message)
                assert maker.func is arc_message
                expected = outcome("closed", s=c.length)
            else:                                           # an arc from one edge to another
                assert maker.func is arc_message
                (k0, j0), (k1, j1) = maker.args[0]
                expected = open_outcome(
                    BOUNDARY, outcome("edge", edge=EDGES[j0], surface="ab"[k0], s=0.0)[1],
                    BOUNDARY, outcome("edge", edge=EDGES[j1], surface="ab"[k1], s=c.length)[1])
            unpickled = pickle.loads(pickle.dumps(c))
            assert (c.status, c.message) == expected == (unpickled.status, unpickled.message)
            seen.add((c.status, maker.func))
    assert seen == {("closed", arc_message), ("boundary", arc_message), ("closed", event_message)}
    sphere = sk.Sphere(1.0)
    sol = CircleSolution((sphere, sphere), np.zeros(3), np.array([0.0, 0.0, 1.0]), 1.0)
    fields = dict(closed=True, length=sol.length, status="closed", tolerance=1e-10, sol=sol)
    calls = []
    lazy = SampledResult(**fields, message_of=lambda: calls.append(1) or "said")
    assert "message" not in lazy.__dict__ and lazy.message == "said" and lazy.message == "said" and calls == [1]
    with pytest.raises(TypeError):
        SampledResult(**fields, message="m", message_of=lambda: "said")
    with pytest.raises(TypeError):
        SampledResult(**fields)


def test_elliptic_e_scalar_is_ufunc():
    """E(t | m) at one float (scipy.special.cython_special) is scipy.special.ellipeinc's, bit for bit, over t in
    [-7, 7] (beyond a turn) and m in [0, 1); an array goes to the ufunc itself."""
    from scipy.special import ellipeinc
    from spatialkin.tracing.closed.conic import QUARTER, elliptic_e
    rng = np.random.default_rng(13)
    t, m = rng.uniform(-7.0, 7.0, DRAWS * 20), rng.uniform(0.0, 1.0, DRAWS * 20)
    ours = [elliptic_e(float(x), float(y)) for x, y in zip(t, m)] + [elliptic_e(QUARTER, float(y)) for y in m]
    assert np.array_equal(ours, np.concatenate([ellipeinc(t, m), ellipeinc(QUARTER, m)]))
    assert type(ours[0]) is float and np.array_equal(elliptic_e(t, m[0]), ellipeinc(t, m[0]))


def test_exact_circles_params_continuous():
    """A circle in closed form (two spheres; a sphere about a cylinder's axis, exact_curve) stores its periodic u
    unwrapped along the curve, as a conic and a traced curve do: neighbouring stored params differ by less than
    pi, and every stored u is the surface's own (Surface.parameters, wrapped) plus whole turns, to 1e-12."""
    frame = sk.Frame((0.1, -0.2, 0.3), np.linalg.qr(np.arange(9.0).reshape(3, 3) + np.eye(3))[0])
    pairs = [(sk.Sphere(1.0, frame), sk.Sphere(0.8, sk.Frame((0.6, 0.4, -0.2)))),
             (sk.Sphere(1.0), sk.Cylinder(0.6, sk.Frame(), (-2.0, 2.0)))]
    wrapped_any = False
    for a, b in pairs:
        for first, second in ((a, b), (b, a)):
            for c in sk.intersect(first, second):
                params = c.params
                assert np.all(np.abs(np.diff(params, axis=0)) < math.pi)
                for k, surf in enumerate((first, second)):
                    own = surf.parameters(c.points)[:, 0]
                    turns = (params[:, 2 * k] - own) / (2 * math.pi)
                    assert np.all(np.abs(turns - np.rint(turns)) <= 1e-12)
                    wrapped_any = wrapped_any or bool(np.any(np.abs(np.diff(own)) > math.pi))
    assert wrapped_any          # some circle does cross u = pi, where the wrapped parameters jump
