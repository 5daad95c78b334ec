"""The planar bench's oracles and peers agree with independent computations (no timing asserted)."""
import functools

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


def test_report_prints_the_measurement_rows(monkeypatch):
    """report prints, per case, its header and one row per solver with every measured column (rate or time,
    error, ratio), and the peers' differences; it returns the ratios printed in those rows (oracle: the rows of
    slider_case and sixbar_case, recorded as they are made). No timing is asserted."""
    made = {}

    def record(name, func):
        def wrapped(*args, **kwargs):
            made[name] = func(*args, **kwargs)
            return made[name]
        return wrapped
    monkeypatch.setattr(bench, "slider_case", record("slider", functools.partial(bench.slider_case, n=360)))
    monkeypatch.setattr(bench, "sixbar_case", record("sixbar", functools.partial(bench.sixbar_case, n=73)))
    lines = []
    ratios = bench.report(quick=True, echo=lines.append)
    text = "\n".join(lines)
    assert "goal" not in text.lower() and "reached" not in text
    slider_rows, diff = made["slider"]
    at = lines.index(next(line for line in lines if line.startswith("planar (a): ")))
    assert lines[at + 1].split() == ["solver", "positions/s", "max", "rel.", "error", "ratio"]
    for line, (name, rate, err, ratio) in zip(lines[at + 2:], slider_rows):
        assert line.startswith(name)
        cells = line[len(name):].split()
        assert float(cells[0]) == pytest.approx(rate, rel=1e-3) and float(cells[1]) == pytest.approx(err, rel=0.01)
        assert (len(cells) == 2) if ratio is None else (cells[2] == f"{ratio:.1f}x")
    assert (diff is None) == any(line.startswith("pylinkage: not installed") for line in lines)
    sixbar_rows, (dq, dv, da) = made["sixbar"]
    at = lines.index(next(line for line in lines if line.startswith("planar (b): ")))
    assert lines[at + 1].split() == ["solver", "time", "[ms]", "speed-up"]
    for line, (name, seconds, ratio) in zip(lines[at + 2:], sixbar_rows):
        assert line.startswith(name)
        cells = line[len(name):].split()
        assert float(cells[0]) == pytest.approx(1e3 * seconds, abs=0.01) and cells[1] == f"{ratio:.1f}x"
    assert lines[at + 2 + len(sixbar_rows)] == (f"max difference pipeline vs root solve: positions {dq:.1e} mm, "
                                                f"velocities {dv:.1e}, accelerations {da:.1e} (relative)")
    assert ratios == {"Frenet module vs pylinkage": slider_rows[1][3] if len(slider_rows) > 1 else None,
                      "six-link full turn vs per-angle root solve": sixbar_rows[0][2]}
