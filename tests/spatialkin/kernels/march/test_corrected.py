"""kernels.curve.corrected_many (the stored states of a traced segment projected in one call) against
project_many and the surfaces' own evaluation, on a torus ∩ sphere loop with states pushed off the curve."""
import numpy as np

import spatialkin as sk
from spatialkin.kernels.march import curve as kc
from spatialkin.kernels.geometry import surfaces as ks
from spatialkin.tracing.march.segments import NEWTON_MAX_ITER

GAP_TOL = 1e-12


def states():
    """Torus and sphere data and (N, 4) states near their intersection (the traced points' parameters, each
    pushed by up to 1e-6)."""
    torus = sk.Torus(1.2, 0.5, sk.Frame((0.1, -0.2, 0.3)))
    sphere = sk.Sphere(1.0, sk.Frame((0.9, 0.1, 0.2)))
    curve = sk.trace(torus, sphere, (1.2, 0.5, 0.5))
    y = np.ascontiguousarray(curve.params[:-1]) + np.random.default_rng(3).uniform(-1e-6, 1e-6,
                                                                                    (len(curve.params) - 1, 4))
    return torus.data, sphere.data, y


def test_corrected_many_is_project_many_with_the_gaps_before_projection():
    a, b, y = states()
    for normal in (np.zeros(3), np.array([0.3, -0.2, 0.9])):
        ours, points, gaps = y.copy(), np.empty((len(y), 3)), np.empty(len(y))
        kc.corrected_many(ours, a, b, normal, GAP_TOL, NEWTON_MAX_ITER, points, gaps)
        theirs, p, t, st = y.copy(), np.empty((len(y), 3)), np.empty((len(y), 3)), np.empty(len(y), dtype=np.int64)
        kc.project_many(theirs, a, b, normal, GAP_TOL, NEWTON_MAX_ITER, p, t, st)
        assert np.array_equal(ours, theirs) and np.array_equal(points, p)
        on_a, on_b = np.empty((len(y), 3)), np.empty((len(y), 3))
        ks.evaluate(a, np.ascontiguousarray(y[:, :2]), on_a)
        ks.evaluate(b, np.ascontiguousarray(y[:, 2:]), on_b)
        assert np.allclose(gaps, np.linalg.norm(on_a - on_b, axis=1), rtol=1e-12, atol=1e-18)
        assert gaps.max() > 1e-7                                        # the states were off the curve ...
        assert np.all(st >= 0)                                          # ... and every projection converged
        ks.evaluate(b, np.ascontiguousarray(ours[:, 2:]), on_b)
        assert np.max(np.linalg.norm(points - on_b, axis=1)) <= GAP_TOL  # onto both surfaces


def test_project_many_is_curve_frame_project_to_curve_and_frame_along():
    """project_many evaluates each surface once where its three steps evaluate it at the same parameters (the frames
    handed on): oracle the three kernels called one by one, as project_many called them before, to the bit (the
    rows, points, tangents and Newton's iterations), with and without a fixed plane normal, also where Newton
    fails (max_iter 1) or ends with a step (the frames then made again)."""
    a, b, y = states()
    for normal in (np.zeros(3), np.array([0.3, -0.2, 0.9])):
        fixed = bool(normal @ normal > 0)
        for max_iter in (1, 2, NEWTON_MAX_ITER):
            ours, p, t, st = y.copy(), np.empty((len(y), 3)), np.empty((len(y), 3)), np.empty(len(y), dtype=np.int64)
            kc.project_many(ours, a, b, normal, GAP_TOL, max_iter, p, t, st)
            for k in range(len(y)):
                row, q, tangent, point, along = y[k].copy(), np.empty(3), np.empty(3), np.empty(3), np.empty(3)
                kc.curve_frame(row, a, b, q, tangent)
                status = kc.project_to_curve(row, a, b, q, normal if fixed else tangent, GAP_TOL, max_iter)
                kc.frame_along(row, a, b, normal, fixed, point, along)
                assert status == st[k]
                assert np.array_equal(row, ours[k]) and np.array_equal(point, p[k]) and np.array_equal(along, t[k])
            if max_iter == 1:
                assert np.any(st < 0)
