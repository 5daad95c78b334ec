"""Tolerance analysis: each Monte-Carlo sample against its linear prediction from the exact sensitivities."""
import numpy as np
import pytest

from spatialkin.design import LooperDesign

TOLERANCES = {"crank_radius": 0.01, "coupler_length": 0.02, "rocker_length": 0.02, "rocker_x": 0.02,
              "rocker_z": 0.02, "rocker_rz": np.radians(0.05), "tip_z": 0.02}


@pytest.fixture(scope="module")
def result():
    design = LooperDesign.reference().replace(rocker_y=2.0, rocker_rz=0.05)
    return design, design.tolerance(TOLERANCES, samples=30, seed=3)


def test_each_sample_against_its_linear_prediction(result):
    """tip(p + d) - tip(p) = J d + O(|d|^2): with errors of 0.02 mm the second-order rest stays below 2 % of
    the first-order move (measured about 0.3 %)."""
    design, r = result
    sens = design.sensitivities(r.crank_angles, free=r.names, turning=False)
    linear = np.einsum("nip,mp->mni", sens.d_tip, r.draws[r.mc_ok])
    actual = r.mc_tips - r.tip
    assert r.failed == 0
    assert np.max(np.abs(actual - linear)) < 0.02 * np.max(np.abs(linear))


def test_linear_and_monte_carlo_side_by_side(result):
    """The RMS tip deviation from 30 samples agrees with the linear one to sampling accuracy (40 %)."""
    _, r = result
    ratio = r.tip_rms_mc.max() / r.tip_rms_linear.max()
    assert 0.6 < ratio < 1.4
    assert np.allclose(np.sqrt(np.sum(r.tip_rms_by_parameter ** 2, axis=1)), r.tip_rms_linear, rtol=1e-12)
    text = r.table()
    assert "all, linear" in text and "all, Monte-Carlo" in text and "crank_radius" in text


def test_uniform_half_width_is_sigma_times_root_three():
    design = LooperDesign.reference()
    r = design.tolerance({"tip_x": 0.03}, distribution="uniform", samples=0)
    # the tip moves along the arm's x: RMS = sigma exactly
    assert np.allclose(r.tip_rms_linear, 0.03 / np.sqrt(3), rtol=1e-12)


@pytest.mark.parametrize("kwargs, word", [(dict(tolerances={}), "tolerances"),
                                          (dict(tolerances={"crank_radius": -1}), "tolerances"),
                                          (dict(tolerances={"crank": 0.1}), "tolerances"),
                                          (dict(tolerances={"crank_radius": 0.1}, distribution="beta"),
                                           "distribution")])
def test_bad_input_names_the_argument(kwargs, word):
    with pytest.raises(ValueError, match=word):
        LooperDesign.reference().tolerance(**kwargs)


def test_exaggeration_is_a_round_factor_making_the_band_visible():
    from spatialkin.plots.design import VISIBLE, exaggeration
    assert exaggeration(0.24, 30.0) == 5          # 0.24 x 5 = 1.2 = VISIBLE x 30
    assert exaggeration(0.1, 30.0) == 20 and exaggeration(0.02, 30.0) == 100
    assert exaggeration(VISIBLE * 30.0, 30.0) == 1 and exaggeration(0.0, 30.0) == 1
    assert all(exaggeration(w, 1.0) * w >= VISIBLE for w in (1e-6, 3e-4, 0.007, 0.039))


def test_the_figure_draws_the_band_and_samples_at_its_stated_exaggeration(result):
    """Left panel: the band's half-width is k x 3 sigma normal to the path and each Monte-Carlo path is the
    nominal one plus k times its deviation (in the path's plane), k the factor the title states. Oracle: the
    result's arrays, projected by hand."""
    from spatialkin.plots.design import tolerance_figure
    _, r = result
    fig = tolerance_figure(r)
    ax = fig.axes[0]
    k = float(ax.get_title().rpartition("×")[2])
    lines = ax.get_lines()
    nominal = next(ln for ln in lines if ln.get_label() == "nominal tip path").get_xydata()
    band = next(ln for ln in lines if ln.get_label().startswith("linear ±3σ envelope, deviations ×")).get_xydata()
    widest = np.max(np.linalg.norm(band - nominal, axis=1))
    assert k > 1 and widest >= 0.04 * np.max(np.ptp(nominal, axis=0)) - 1e-12
    first_mc = lines[0].get_xydata()                 # the first Monte-Carlo path, drawn first
    moved = np.linalg.norm(first_mc - nominal, axis=1)
    true = np.linalg.norm(r.mc_tips[0] - r.tip, axis=1)
    assert np.all(moved <= k * true * (1 + 1e-9) + 1e-12) and np.max(moved) >= 0.3 * k * np.max(true)
