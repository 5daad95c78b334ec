"""The planar bench's oracles and peers agree with independent computations (no timing asserted)."""
import numpy as np
import pytest

from planar import bench


def test_slider_closed_form_matches_finite_differences():
    k, e, L = 0.5, 1.0, 4.0
    phi = np.linspace(0.0, 2 * np.pi, 50)
    h = 1e-4
    (pin, pin_v, pin_a), (sl, sl_v, sl_a) = bench.slider_closed_form(k, e, L, phi, omega=2.0)
    shift = {d: bench.slider_closed_form(k, e, L, phi + d * h, omega=2.0) for d in (-1, 1)}
    for j, (p, v, a) in enumerate(((pin, pin_v, pin_a), (sl, sl_v, sl_a))):
        fd_v = 2.0 * (shift[1][j][0] - shift[-1][j][0]) / (2 * h)
        fd_a = 2.0 * (shift[1][j][1] - shift[-1][j][1]) / (2 * h)
        assert np.max(np.abs(v - fd_v)) < 1e-6 and np.max(np.abs(a - fd_a)) < 1e-6
    assert np.allclose(np.linalg.norm(sl - pin, axis=1), L) and np.allclose(sl[:, 1], e)


def test_slider_case_reports_agreeing_implementations():
    rows, diff = bench.slider_case(n=360, repeats=1)
    assert rows[0][2] < 1e-13                          # Frenet module vs the closed form (relative)
    if diff is not None:                               # pylinkage installed: both agree, ~1e-13
        assert diff < 1e-9 and rows[1][2] < 1e-9


def test_sixbar_case_root_solve_agrees():
    rows, diff = bench.sixbar_case(n=73, repeats=1)
    assert diff[0] < 1e-9 and diff[1] < 1e-10 and diff[2] < 1e-10
    assert [r[0] for r in rows][-1].startswith("per-angle")


@pytest.mark.parametrize("n", [1, 7])
def test_pylinkage_adapter_or_absent(n):
    run = bench.pylinkage_slider(max(n, 8))
    if run is None:
        pytest.skip("pylinkage not installed")
    out = run()
    phi = 2 * np.pi * np.arange(max(n, 8)) / max(n, 8)
    ref = bench.slider_closed_form(0.5, 1.0, 4.0, phi)
    assert np.allclose(out["slider"][0], ref[1][0], atol=1e-9)
