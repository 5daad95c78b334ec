"""The six-link's pictures draw exactly the solved data (identity oracle)."""
import numpy as np
import pytest

import planar
from planar.linkage import figures as lf


@pytest.fixture(scope="module")
def sol():
    return planar.examples.fnf_sixbar().solve(np.linspace(0.0, 2 * np.pi, 73))


def test_paths_draw_the_joint_trajectories(sol):
    fig = lf.paths(sol, joints=("B", "C", "K"))
    lines = {ln.get_label(): ln.get_xydata() for ln in fig.axes[0].get_lines()}
    for j in "BCK":
        assert np.array_equal(lines[f"path of {j}"], sol.position(j))


def test_velocity_plans_show_each_share_and_their_sum(sol):
    fig = lf.velocity_plans(sol, 10)
    assert len(fig.axes) == 3
    for ax, crank in zip(fig.axes, (1, 2, None)):
        tips = {t.get_text(): np.array(t.xy) for t in ax.texts if t.get_text() in "abckd" and t.get_text()}
        for j in "ABCKD":
            assert np.allclose(tips[j.lower()], sol.velocity(j, crank)[10], atol=1e-12)
    dashed = [ln.get_xydata() for ln in fig.axes[2].get_lines() if ln.get_linestyle() == "--"]
    for j in "ABCKD":                                        # share chains end at the full velocity
        assert any(np.allclose(d[-1], sol.velocity(j)[10], atol=1e-12) for d in dashed)


def test_mechanism_draws_every_link(sol):
    fig = lf.mechanism(sol, (0, 36))
    ax = fig.axes[0]
    assert len(ax.patches) == 2                         # the ternary link at both positions
    k = sol.position("K")[0]
    assert any(np.allclose(t.xy, k) for t in ax.texts if t.get_text() == "K")


def test_mechanism_names_every_position_it_draws():
    """Six positions: the title lists the six input angles, and each light one carries its angle beside the first
    crank's pin; past TITLE_ANGLES the title counts the rest."""
    sol = planar.examples.fnf_sixbar().solve(np.linspace(0.0, 2 * np.pi, 361))
    fig = lf.mechanism(sol, range(0, 360, 60))
    ax = fig.axes[0]
    assert ax.get_title() == "mechanism at input angles 0, 60, 120, 180, 240, 300 deg (the first dark)"
    pin = sol.linkage.cranks[0].pin
    marks = {t.get_text(): np.array(t.xy) for t in ax.texts if t.get_text().endswith("°")}
    assert sorted(marks) == sorted(f"{a}°" for a in (60, 120, 180, 240, 300))
    for i in range(60, 360, 60):
        assert np.allclose(marks[f"{i}°"], sol.position(pin)[i], atol=1e-12)
    many = lf.mechanism(sol, range(0, 360, 30)).axes[0].get_title()
    assert many.endswith(" and 4 more deg (the first dark)") and many.count(",") == lf.TITLE_ANGLES - 1


def test_velocity_plans_share_one_scale_and_name_the_shares(sol):
    fig = lf.velocity_plans(sol, 10)
    limits = {(ax.get_xlim(), ax.get_ylim()) for ax in fig.axes[:3]}
    assert len(limits) == 1
    assert [t.get_text() for t in fig.axes[2].get_legend().get_texts()] == ["crank 1's share", "crank 2's share"]
    assert fig.axes[0].get_xlabel() == "v_x (length unit / s)" and fig.axes[0].get_ylabel() == "v_y (length unit / s)"


def test_figures_label_their_axes_in_the_unit_given(sol):
    """unit="mm" puts the unit on every axis (velocities per second); without it the axes say "length unit"."""
    for fig in (lf.mechanism(sol, unit="mm"), lf.paths(sol, unit="mm")):
        assert (fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel()) == ("x [mm]", "y [mm]")
    plans = lf.velocity_plans(sol, 10, unit="mm")
    assert {ax.get_xlabel() for ax in plans.axes} == {"v_x [mm/s]"} and plans.axes[0].get_ylabel() == "v_y [mm/s]"
    assert lf.paths(sol).axes[0].get_xlabel() == "x (length unit)"
