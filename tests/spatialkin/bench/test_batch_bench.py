"""The bench's batch section (spatialkin.bench.batch) and the per-kind files (spatialkin.bench.kinds_report)."""
import csv
import time

import numpy as np
import pytest

from spatialkin.bench import batch
from spatialkin.bench.kinds_report import COLUMNS, plot_kinds, write_kinds_csv
from spatialkin.bench.sidebyside import KindRow
from spatialkin.kernels.march import curve as kc
from spatialkin._lib import stages


def test_sweep_is_the_looper_pair_with_radii_spread():
    from spatialkin.mechanisms.looper.reference import looper_pair
    torus, sphere = looper_pair()
    pairs = batch.looper_configs(5)
    radii = [s.radius for _, s in pairs]
    for t, s in pairs:
        assert (t.major_radius, t.minor_radius) == (torus.major_radius, torus.minor_radius)
        np.testing.assert_array_equal(t.frame.origin, torus.frame.origin)
        np.testing.assert_array_equal(s.frame.origin, sphere.frame.origin)
    np.testing.assert_allclose(radii, sphere.radius * np.linspace(1 - batch.SPREAD, 1 + batch.SPREAD, 5), rtol=1e-15)


def test_kernel_seconds_counts_only_kernel_time():
    torus, sphere = batch.looper_configs(1)[0]
    y = np.array([0.3, 0.2, 0.1, 0.4])
    kc.dragilev_rhs(0.0, y, torus.data, sphere.data, 1.0, 0.0)     # compiled before the measurement

    def work():
        time.sleep(0.05)                    # Python time: not counted
        for _ in range(200):
            kc.dragilev_rhs(0.0, y, torus.data, sphere.data, 1.0, 0.0)
        return 1

    seconds, out = batch.kernel_seconds(work)
    assert out == 1 and 0.0 < seconds < 0.05


def test_closed_form_rate_counts_points():
    torus, sphere = batch.looper_configs(1)[0]
    rate = batch.closed_form_rate(torus, sphere, angles=1000)
    assert np.isfinite(rate) and rate > 0


def fake_rows():
    prof = stages.StageProfile({s: 1e-4 for s in stages.STAGES}, 7e-4)
    return [KindRow("plane-plane", 2e-3, 2e-4, 3e-16, 4e-16, 1, 1, prof),
            KindRow("torus-torus", 1e-2, 2e-1, 8e-16, 5e-8, 1, 10, prof)]


def test_kinds_csv_and_png_written(tmp_path):
    rows = fake_rows()
    write_kinds_csv(rows, tmp_path / "k.csv")
    plot_kinds(rows, tmp_path / "k.png", "title")
    with open(tmp_path / "k.csv") as f:
        table = list(csv.reader(f))
    assert table[0] == COLUMNS and len(table) == 3
    assert float(table[1][3]) == pytest.approx(0.1) and float(table[2][3]) == pytest.approx(20.0)
    assert (tmp_path / "k.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k.csv", "k.png"]       # no temporary left


def test_kinds_files_without_opencascade_hold_no_nan(tmp_path):
    """OpenCascade not installed (its times and errors NaN): the CSV leaves those cells empty, the PNG says so."""
    prof = stages.StageProfile({s: 1e-4 for s in stages.STAGES}, 7e-4)
    rows = [KindRow("torus-torus", 1e-2, float("nan"), 8e-16, float("nan"), 1, 0, prof)]
    write_kinds_csv(rows, tmp_path / "k.csv")
    plot_kinds(rows, tmp_path / "k.png", "title")
    text = (tmp_path / "k.csv").read_text()
    assert "nan" not in text.lower()
    row = list(csv.reader(text.splitlines()))[1]
    assert row[2] == row[3] == row[5] == "" and float(row[1]) == 1e-2
    assert (tmp_path / "k.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_kinds_bars_start_at_parity():
    """Each ratio bar runs from parity (1) to the ratio: OCC/ours = 0.1 to the left of 1 (red), 20 to its right
    (green); the axis holds both with their labels and no more than RATIO_MARGIN past them; the numbers are
    readable (at least NUMBER_SIZE points) and both times in ms are written."""
    from matplotlib.colors import to_rgba
    from spatialkin.bench.kinds_report import (FASTER_COLOR, NUMBER_SIZE, RATIO_MARGIN, SLOWER_COLOR,
                                               kinds_figure)
    fig = kinds_figure(fake_rows(), "title")
    bars, middle, errors = fig.axes
    spans = sorted((p.get_x(), p.get_x() + p.get_width(), p.get_facecolor()) for p in bars.patches
                   if p.get_height() < 1 and p.get_width() != 0)
    (lo0, hi0, c0), (lo1, hi1, c1) = spans
    assert min(lo0, hi0) == pytest.approx(0.1) and max(lo0, hi0) == pytest.approx(1.0) and c0 == to_rgba(SLOWER_COLOR)
    assert min(lo1, hi1) == pytest.approx(1.0) and max(lo1, hi1) == pytest.approx(20.0) and c1 == to_rgba(FASTER_COLOR)
    assert bars.get_xscale() == "log"
    np.testing.assert_allclose(bars.get_xlim(), (0.1 / RATIO_MARGIN, 20.0 * RATIO_MARGIN), rtol=1e-12)
    labels = [t.get_text() for t in bars.texts]
    assert labels == ["0.1\u00d7", "20\u00d7"]
    assert [t.get_text() for t in middle.texts] == ["2 / 0.2", "10 / 200"]
    assert min(t.get_fontsize() for t in bars.texts + middle.texts) >= NUMBER_SIZE >= 9
    assert min(t.get_fontsize() for t in bars.get_yticklabels()) >= 9


def test_kinds_errors_do_not_hide_each_other():
    """Equal errors of both on one row: ours and OpenCascade's markers at different heights, told apart by a
    legend."""
    from spatialkin.bench.kinds_report import kinds_figure
    prof = stages.StageProfile({s: 1e-4 for s in stages.STAGES}, 7e-4)
    rows = [KindRow("plane-sphere", 3e-5, 3e-5, 4e-16, 4e-16, 1, 1, prof)]
    errors = kinds_figure(rows, "title").axes[2]
    ours, occ = errors.get_lines()
    assert ours.get_xdata()[0] == occ.get_xdata()[0] and abs(ours.get_ydata()[0] - occ.get_ydata()[0]) >= 0.3
    assert [t.get_text() for t in errors.get_legend().get_texts()][1].startswith("GeomAPI_IntSS")


def test_kinds_cold_and_loop_ratios_marked_beside_the_warm_bar(tmp_path):
    """Where the cold and loop times are measured, each row has a mark at OCC cold / ours cold (here 0.5 and 5) and
    a hollow diamond at OCC loop / ours loop (here 0.25 and 40), inside the axis, told apart by legend entries; the
    CSV carries the cold and loop times and their ratios."""
    from spatialkin.bench.kinds_report import kinds_figure
    prof = stages.StageProfile({s: 1e-4 for s in stages.STAGES}, 7e-4)
    rows = [KindRow("plane-plane", 2e-3, 2e-4, 3e-16, 4e-16, 1, 1, prof, ours_cold=4e-3, occ_cold=2e-3,
                    ours_loop=1e-3, occ_loop=2.5e-4),
            KindRow("torus-torus", 1e-2, 2e-1, 8e-16, 5e-8, 1, 10, prof, ours_cold=4e-2, occ_cold=2e-1,
                    ours_loop=5e-3, occ_loop=2e-1)]
    bars = kinds_figure(rows, "title").axes[0]
    mark, = [line for line in bars.get_lines() if line.get_marker() == "|"]
    np.testing.assert_allclose(mark.get_xdata(), [0.5, 5.0], rtol=1e-12)
    np.testing.assert_allclose(mark.get_ydata(), [0, 1])
    diamond, = [line for line in bars.get_lines() if line.get_marker() == "D"]
    np.testing.assert_allclose(diamond.get_xdata(), [0.25, 40.0], rtol=1e-12)
    np.testing.assert_allclose(diamond.get_ydata(), [0, 1])
    lo, hi = bars.get_xlim()
    assert lo < 0.25 and hi > 40.0
    legend = [t.get_text() for t in bars.get_legend().get_texts()]
    assert any(t.startswith("cold") for t in legend) and any(t.startswith("loop") for t in legend)
    write_kinds_csv(rows, tmp_path / "k.csv")
    with open(tmp_path / "k.csv") as f:
        table = list(csv.reader(f))
    assert table[0][-6:] == ["ours cold s", "OCC cold s", "OCC/ours cold", "ours loop s", "OCC loop s",
                             "OCC/ours loop"]
    assert [float(x) for x in table[2][-6:]] == pytest.approx([4e-2, 2e-1, 5.0, 5e-3, 2e-1, 40.0])
