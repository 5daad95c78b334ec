"""Planar Frenet-trihedron module against its oracles: geometric constraints, closed forms (3), (4),
finite differences, the paper's boundary cases, the corrected derivatives (15), (16), two image tests.

Formula and figure numbers are those of S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic
characteristics of planar mechanisms' driven member using Frenet trihedron", 2017."""
import os

import numpy as np
import pytest

import planar
from planar.frenet import figures

BASELINE = os.path.join(os.path.dirname(__file__), "baseline")


def time_fd(link, s, rho, h=1e-3):
    """Velocity and acceleration by 5-point differences in time (s = V t)."""
    dt = h / link.speed
    p = [link.position(s + j * h, rho) for j in (-2, -1, 0, 1, 2)]
    v = (p[0] - 8 * p[1] + 8 * p[3] - p[4]) / (12 * dt)
    a = (-p[0] + 16 * p[1] - 30 * p[2] + 16 * p[3] - p[4]) / (12 * dt * dt)
    return v, a


LAWS = {
    "slider": lambda: planar.CrankSlider(0.5, 1.0, 4.0),
    "slider-other-side": lambda: planar.CrankSlider(0.5, 1.0, 4.0, side=-1, branch=1),
    "rocking-stone": lambda: planar.CrankRocker(0.5, 4.0),
    "rotating-stone": lambda: planar.CrankRocker(0.5, 1.0),
    "stone-on-circle": lambda: planar.CrankRocker(0.5, 2.0),
}


@pytest.mark.parametrize("name", LAWS)
def test_velocity_and_acceleration_against_differences(name):
    """Velocities and accelerations of points along the link against 5-point differences of positions
    (tolerance 1e-8 relative), at omega = 3."""
    link = planar.DrivenLink(LAWS[name](), omega=3.0)
    s = np.linspace(0.05, 12.5, 400)
    for rho in (0.0, 4.0, -4.0, 2.0):
        v_fd, a_fd = time_fd(link, s, rho)
        t = link.trajectory(s, rho)
        assert np.max(np.abs(t.velocity - v_fd)) < 1e-8 * np.max(np.abs(v_fd)) + 1e-12
        assert np.max(np.abs(t.acceleration - a_fd)) < 1e-7 * np.max(np.abs(a_fd)) + 1e-10


@pytest.mark.parametrize("name", LAWS)
def test_frame_components_are_the_papers_formulas(name):
    """(V_tau, V_n) and (W_tau, W_n) equal formulas (3) and (4) of the paper to 1e-12, and the link's
    angular velocity and acceleration are V (k + phi') and V^2 phi'' (differences of gamma, 1e-8)."""
    law = LAWS[name]()
    link = planar.DrivenLink(law, omega=2.0)
    s = np.linspace(0.0, 12.5, 300)
    k, V = law.k, link.speed
    phi, dphi, ddphi = law.evaluate(s)
    for rho in (4.0, -4.0):
        vt = V * (1 - rho * (k + dphi) * np.sin(phi))
        vn = V * rho * (k + dphi) * np.cos(phi)
        wt = -V ** 2 * rho * (ddphi * np.sin(phi) + (k + dphi) ** 2 * np.cos(phi))
        wn = V ** 2 * (k + rho * ddphi * np.cos(phi) - rho * (k + dphi) ** 2 * np.sin(phi))
        np.testing.assert_allclose(link.velocity_frame(s, rho), np.stack([vt, vn], -1), atol=1e-12)
        np.testing.assert_allclose(link.acceleration_frame(s, rho), np.stack([wt, wn], -1), atol=1e-12)
    h = 1e-4
    g = lambda x: np.unwrap(law.gamma(x))
    omega_fd = (g(s + h) - g(s - h)) / (2 * h) * V
    np.testing.assert_allclose(link.angular_velocity(s), omega_fd, atol=1e-8)
    eps_fd = (law.evaluate(s + h)[1] - law.evaluate(s - h)[1]) / (2 * h) * V ** 2
    np.testing.assert_allclose(link.angular_acceleration(s), eps_fd, atol=1e-6)


@pytest.mark.parametrize("side, branch", [(1, 0), (1, 1), (-1, 0), (-1, 1)])
def test_slider_stays_on_its_guide(side, branch):
    law = planar.CrankSlider(0.5, 1.0, 4.0, side=side, branch=branch)
    link = planar.DrivenLink(law)
    s = np.linspace(0, 4 * np.pi, 1001)
    slider = link.position(s, law.L)
    np.testing.assert_allclose(slider[:, 1], side * 1.0, atol=1e-12)
    np.testing.assert_allclose(link.velocity(s, law.L)[:, 1], 0.0, atol=1e-12)
    np.testing.assert_allclose(link.acceleration(s, law.L)[:, 1], 0.0, atol=1e-11)
    # the rod length is L: the pin is at distance L from the slider
    np.testing.assert_allclose(np.linalg.norm(slider - link.position(s, 0.0), axis=1), law.L, atol=1e-12)


@pytest.mark.parametrize("d", [4.0, 2.0, 1.0])
def test_link_passes_through_the_stone(d):
    law = planar.CrankRocker(0.5, d)
    link = planar.DrivenLink(law)
    s = np.linspace(0, 4 * np.pi, 1001)
    pin, ahead = link.position(s, 0.0), link.position(s, 1.0)
    u, w = ahead - pin, law.stone - pin
    np.testing.assert_allclose(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0], 0.0, atol=1e-12)
    # direction continuous along s, also where the pin passes the stone (d = r)
    assert np.min(np.sum(u[1:] * u[:-1], axis=1)) > 0.9


@pytest.mark.parametrize("k, d, s", [(0.5, 2.0000001, np.pi - 2.1e-8), (0.5, 2.0000001, np.pi),
                                     (0.5, 2.00000001, np.pi), (0.5, 2.0 + 4.0 * np.finfo(float).eps, np.pi),
                                     (0.5, 2.0 - 4.0 * np.finfo(float).eps, np.pi), (0.5, 1.9999, np.pi + 1e-3),
                                     (0.3, 1.0 / 0.3 + 1e-8, 0.5 * np.pi / 0.3), (0.7, 1.0 / 0.7 - 3e-9, 2.2439)])
def test_derivatives_where_the_pin_passes_near_the_stone(k, d, s):
    """d near 1/k, the pin passing within 1e-16 to 1e-4 of the stone: phi' and phi'' against the law's formulas in
    50-digit arithmetic (mpmath, from the same doubles k, d, s), to 1e-12 relative; finite everywhere."""
    import mpmath as mp
    _, dphi, ddphi = planar.CrankRocker(k, d).evaluate(np.array([s]))
    with mp.workdps(50):
        K, D, S = mp.mpf(k), mp.mpf(d), mp.mpf(s)
        sn, c = mp.sin(K * S), mp.cos(K * S)
        big_d = 1 + K * K * D * D - 2 * K * D * sn
        true1 = -K * K * D * (K * D - sn) / big_d
        true2 = -D * K ** 3 * (K * K * D * D - 1) * c / big_d ** 2
    for got, true in ((dphi[0], true1), (ddphi[0], true2)):
        assert np.isfinite(got)
        assert abs(got - float(true)) <= 1e-12 * abs(float(true))


def test_corrected_derivatives_at_d_equal_r():
    """At d = r the link is a chord through a point of the circle and turns uniformly at omega/2: phi' = -k/2.
    The printed (15) has the wrong sign of the gamma term: phi'_printed = -k - (phi' + k) = -3k/2 here.
    Differences of phi itself side with the corrected form, at d = r and at d = 4."""
    k = 0.5
    for d in (2.0, 4.0, 1.0):
        law = planar.CrankRocker(k, d)
        s = np.linspace(0.1, 12.0, 200)
        h = 1e-5
        fd = (np.unwrap(law.evaluate(s + h)[0]) - np.unwrap(law.evaluate(s - h)[0])) / (2 * h)
        corrected = law.evaluate(s)[1]
        printed = -2 * k - corrected
        np.testing.assert_allclose(corrected, fd, atol=1e-8)
        assert np.max(np.abs(printed - fd)) > 0.1
    link = planar.DrivenLink(planar.CrankRocker(k, 2.0), omega=3.0)
    np.testing.assert_allclose(link.angular_velocity(np.linspace(0, 20, 50)), 1.5, atol=1e-14)
    np.testing.assert_allclose(link.angular_acceleration(np.linspace(0, 20, 50)), 0.0, atol=1e-14)


@pytest.mark.parametrize("e, L", [(2.0, 4.0), (1.0, 3.0)])
def test_boundary_cases_of_the_paper(e, L):
    """e + 1/k = L (Fig. 8-11): the rod lines up with the crank once a turn; positions exact, no NaN."""
    law = planar.CrankSlider(0.5, e, L)
    link = planar.DrivenLink(law)
    s = np.linspace(0, 4 * np.pi, 2001)
    t = link.trajectory(s, L)
    assert np.all(np.isfinite(t.position)) and np.all(np.isfinite(t.velocity)) and np.all(np.isfinite(t.acceleration))
    np.testing.assert_allclose(t.position[:, 1], e, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(t.position - link.position(s, 0.0), axis=1), L, atol=1e-12)


def test_feasibility_is_checked_up_front():
    with pytest.raises(ValueError, match=r"e \+ 1/k <= L.*= 4.5 > L = 4"):
        planar.CrankSlider(0.5, 2.5, 4.0)
    for kwargs, name in (({"k": 0}, "k"), ({"e": -1}, "e"), ({"L": np.nan}, "L"), ({"side": 2}, "side")):
        args = {"k": 0.5, "e": 1.0, "L": 4.0}
        args.update(kwargs)
        with pytest.raises(ValueError, match=name):
            planar.CrankSlider(**args)
    with pytest.raises(ValueError, match="d"):
        planar.CrankRocker(0.5, -1.0)
    for args, kwargs, error, words in (((0.5, 1.0, 1e155), {}, ValueError, "L must lie within"),
                                       ((1e154, 0.0, 4.0), {}, ValueError, "k must lie within"),
                                       (("0.5", 1.0, 4.0), {}, TypeError, "k must be a real number"),
                                       ((0.5, 1.0, 4.0), {"side": True}, ValueError, "side must be 1 or -1"),
                                       ((0.5, 1.0, 4.0), {"branch": True}, ValueError, "branch must be 0 or 1")):
        with pytest.raises(error, match=words):
            planar.CrankSlider(*args, **kwargs)
    with pytest.raises(ValueError, match="d must lie within"):
        planar.CrankRocker(0.5, 1e40)
    with pytest.raises(ValueError, match="omega"):
        planar.DrivenLink(planar.CrankRocker(0.5, 4.0), omega=0.0)
    with pytest.raises(TypeError, match="law"):
        planar.DrivenLink("law")
    with pytest.raises(TypeError, match="s must be an array of real numbers"):
        planar.DrivenLink(planar.CrankRocker(0.5, 4.0)).position("a", 1.0)
    arcsin_law = planar.LawFromFunctions(0.5, lambda s: np.arcsin(s), lambda s: 1 / np.sqrt(1 - s * s), lambda s: s)
    with pytest.raises(ValueError, match="non-finite"), np.errstate(invalid="ignore"):
        arcsin_law.evaluate(np.array([2.0]))


def test_user_laws_reproduce_the_crank_rocker():
    """A law from user functions and one from gamma(s) (eq. (1)) give the crank-rocker's kinematics."""
    ref = planar.CrankRocker(0.5, 4.0)
    funcs = planar.LawFromFunctions(0.5, lambda s: ref.evaluate(s)[0], lambda s: ref.evaluate(s)[1],
                                    lambda s: ref.evaluate(s)[2])
    gam = planar.LawFromGamma(0.5, ref.gamma, lambda s: 0.5 + ref.evaluate(s)[1], lambda s: ref.evaluate(s)[2])
    s = np.linspace(0, 12, 100)
    for law in (funcs, gam):
        for method in ("position", "velocity", "acceleration"):
            np.testing.assert_allclose(getattr(planar.DrivenLink(law, 2.0), method)(s, 3.0),
                                       getattr(planar.DrivenLink(ref, 2.0), method)(s, 3.0), atol=1e-12)


def test_vectorised_over_s_and_rho():
    link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0))
    s = np.linspace(0, 10, 7)[:, None]
    rho = np.array([-4.0, 0.0, 2.0, 4.0])[None, :]
    assert link.velocity(s, rho).shape == (7, 4, 2)
    np.testing.assert_allclose(link.velocity(s, rho)[3, 2], link.velocity(s[3, 0], rho[0, 2]), atol=1e-15)


def compare_image(fig, name, tolerance=0.02):
    """Render at 50 dpi and compare with the stored baseline: same size, RMS difference below tolerance."""
    import matplotlib.image as mpimg
    path = os.path.join(BASELINE, name)
    out = os.path.join(os.path.dirname(path), "..", f"_actual_{name}")
    fig.savefig(out, dpi=50)
    actual = mpimg.imread(out)
    expected = mpimg.imread(path)
    assert actual.shape == expected.shape
    rms = float(np.sqrt(np.mean((actual - expected) ** 2)))
    assert rms < tolerance, f"{name}: RMS difference {rms:.4f} (actual image kept at {out})"
    os.remove(out)


def test_image_fig3_positions():
    import matplotlib
    matplotlib.rcdefaults()
    link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0))
    compare_image(figures.positions(link, [0.0, 4.0, -4.0, 2.0], title="Fig. 3"), "fig3_positions.png")


def test_image_fig4_velocity_vectors():
    import matplotlib
    matplotlib.rcdefaults()
    link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0))
    compare_image(figures.vectors(link, [-4.0, 2.0], "velocity", 0.5, title="Fig. 4"), "fig4_velocity.png")


def test_figure_arguments_are_checked():
    link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0))
    with pytest.raises(ValueError, match="kind"):
        figures.vectors(link, [1.0], "jerk")
    with pytest.raises(ValueError, match="scale"):
        figures.vectors(link, [1.0], "velocity", scale=-1)
    fig = figures.magnitudes(link, [4.0, -4.0], "acceleration")
    assert len(fig.axes[0].lines) == 2


def test_vectors_colour_each_point_and_keep_the_arrow_tips_in_view():
    """Each point's path and arrows share a colour, named in the legend; every arrow tip lies inside the axes
    (oracle: the trajectory's velocity times the scale, added to its positions)."""
    link = planar.DrivenLink(planar.CrankSlider(0.5, 1.0, 4.0))
    fig = figures.vectors(link, [-4.0, 2.0], "velocity", 0.5)
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["rho = -4", "rho = 2"]
    paths = [ln for ln in ax.get_lines() if ln.get_label().startswith("rho")]
    for line, arrows in zip(paths, ax.collections):
        assert np.allclose(arrows.get_facecolor()[0][:3], matplotlib_rgb(line.get_color()))
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    turn = 2 * np.pi / link.k
    for rho in (-4.0, 2.0):
        t = link.trajectory(np.arange(0.0, turn, turn / figures.VECTORS_PER_TURN), rho)
        tips = t.position + 0.5 * t.velocity
        assert np.all((tips[:, 0] >= x0) & (tips[:, 0] <= x1) & (tips[:, 1] >= y0) & (tips[:, 1] <= y1))
    assert ax.get_title() == "velocity vectors, drawn as m v with m = 0.5 s"


def matplotlib_rgb(colour):
    from matplotlib.colors import to_rgb
    return to_rgb(colour)
