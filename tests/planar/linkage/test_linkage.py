"""The general planar linkage and the double-crank six-link of the FNF warp-knitting machine (its reference geometry is
assumed: the paper gives no dimensions). Oracles: the constraint equations themselves, an independent solver of the
classical angle loop equations, finite differences, the paper's superposition identities.

S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian)."""
import math

import numpy as np
import pytest
from scipy.optimize import fsolve

import planar
from planar import Crank, Link, Linkage, LockError
from planar.linkage import kernels as kn

N = 3601
PHI = np.linspace(0.0, 2 * np.pi, N)
JOINTS = ("O1", "A", "B", "O2", "D", "C", "K", "E")
MOVING = ("A", "B", "D", "C", "K")
#: Tolerances (mm, or relative where stated).
CONSTRAINT_TOL = 1e-10
SOLVER_TOL = 1e-9
FD_STEP = 1e-3
VEL_TOL = 1e-8          # relative to the largest speed
ACC_TOL = 1e-6          # relative to the largest acceleration


@pytest.fixture(scope="module")
def mech():
    return planar.examples.fnf_sixbar()


@pytest.fixture(scope="module")
def sol(mech):
    return mech.solve(PHI, omega=1.0)


def dist(p, q):
    return np.linalg.norm(p - q, axis=1)


def sixbar(e_k=58.0, phase=4.73, omega_ratio=-2.0, hint=True):
    base = planar.examples.fnf_sixbar()
    return Linkage(base.fixed, [Crank("1", "O1", "A", 14.0), Crank("2", "O2", "D", 16.0, omega_ratio, phase)],
                   [Link("3", ("A", "B"), length=137.0), Link("5", ("D", "C"), length=107.0),
                    Link("4", ("B", "C", "K"), shape=((0, 0), (99, 0), (30, 45))),
                    Link("6", ("E", "K"), length=e_k)],
                   hint=base.hint if hint else None)


def test_constraints_hold_over_the_cycle(sol):
    p = {j: sol.position(j) for j in JOINTS}
    phi2 = 4.73 - 2 * PHI
    checks = {
        "A on crank 1": p["A"] - np.column_stack([14 * np.cos(PHI), 14 * np.sin(PHI)]),
        "D on crank 2": p["D"] - (81, 0) - np.column_stack([16 * np.cos(phi2), 16 * np.sin(phi2)]),
    }
    lengths = {("A", "B"): 137.0, ("D", "C"): 107.0, ("E", "K"): 58.0, ("B", "C"): 99.0,
               ("B", "K"): math.hypot(30, 45), ("C", "K"): math.hypot(69, 45)}
    for name, r in checks.items():
        assert np.max(np.abs(r)) < CONSTRAINT_TOL, name
    for (i, j), length in lengths.items():
        assert np.max(np.abs(dist(p[i], p[j]) - length)) < CONSTRAINT_TOL, (i, j)
    # link 4 keeps its orientation (K to the left of B->C): no flip to the mirror assembly
    bc, bk = p["C"] - p["B"], p["K"] - p["B"]
    assert np.all(bc[:, 0] * bk[:, 1] - bc[:, 1] * bk[:, 0] > 0)
    assert np.allclose(p["O1"], 0) and np.allclose(p["E"], (153, 155))


def angle_loop_solution(phi, guess, e_k=58.0):
    """Independent oracle: the classical loop equations in the link angles (t3, t4, t6, t5) of the two
    loops O1-A-B-K-E and O2-D-C-K-E, solved by fsolve."""
    phi2 = 4.73 - 2 * phi
    a = 14 * np.array([math.cos(phi), math.sin(phi)])
    d = np.array([81.0, 0.0]) + 16 * np.array([math.cos(phi2), math.sin(phi2)])
    e = np.array([153.0, 155.0])
    bk, beta = math.hypot(30, 45), math.atan2(45, 30)          # K from B in link 4's frame
    ck, gamma = math.hypot(69, 45), math.atan2(45, -69)        # K from C

    def u(t):
        return np.array([math.cos(t), math.sin(t)])

    def eqs(x):
        t3, t4, t6, t5 = x
        return np.concatenate([a + 137 * u(t3) + bk * u(t4 + beta) - e - e_k * u(t6),
                               d + 107 * u(t5) + ck * u(t4 + gamma) - e - e_k * u(t6)])
    x, info, *_ = fsolve(eqs, guess, xtol=1e-13, full_output=True)
    return e + e_k * u(x[2]), x, np.max(np.abs(info["fvec"]))


def test_triad_matches_an_independent_solver(sol):
    k = sol.position("K")
    b, c = sol.position("B"), sol.position("C")
    guess = None
    for i in range(0, N, 90):
        t3 = math.atan2(*(b[i] - sol.position("A")[i])[::-1])
        t4 = math.atan2(*(c[i] - b[i])[::-1])
        t6 = math.atan2(*(k[i] - (153, 155))[::-1])
        t5 = math.atan2(*(c[i] - sol.position("D")[i])[::-1])
        perturbed = np.array([t3, t4, t6, t5]) + 0.05 if guess is None else guess
        k_ref, guess, _ = angle_loop_solution(PHI[i], perturbed)
        assert np.linalg.norm(k_ref - k[i]) < SOLVER_TOL, PHI[i]


def test_continuity_and_period(sol):
    step = PHI[1] - PHI[0]
    for j in MOVING:
        p, v = sol.position(j), sol.velocity(j)
        jumps = np.linalg.norm(np.diff(p, axis=0), axis=1)
        bound = step * np.maximum(np.linalg.norm(v[:-1], axis=1), np.linalg.norm(v[1:], axis=1))
        assert np.all(jumps <= 1.01 * bound + 1e-9), j   # a chord never exceeds the arc (+ curvature)
        assert np.linalg.norm(p[-1] - p[0]) < CONSTRAINT_TOL, j   # back after one input turn


def test_superposition_and_velocity_plan_identities(sol):
    scale = max(np.max(np.linalg.norm(sol.velocity(j), axis=1)) for j in MOVING)
    for j in JOINTS:
        total = sol.velocity(j)
        assert np.max(np.abs(total - sol.velocity(j, crank=1) - sol.velocity(j, crank=2))) < 1e-12 * scale
    rk = sol.position("K") - (153, 155)
    for crank in (None, 1, 2):                  # V_K is perpendicular to EK, for each share too
        vk = sol.velocity("K", crank)
        assert np.max(np.abs(np.sum(vk * rk, axis=1))) / 58 < 1e-12 * scale
    # crank 1's share moves A as the crank alone; crank 2 stopped leaves D still, and conversely
    a = sol.position("A")
    assert np.allclose(sol.velocity("A", 1), np.column_stack([-a[:, 1], a[:, 0]]), atol=1e-12)
    assert np.max(np.abs(sol.velocity("A", 2))) < 1e-12 and np.max(np.abs(sol.velocity("D", 1))) < 1e-12
    d = sol.position("D") - (81, 0)
    assert np.allclose(sol.velocity("D", 2), -2 * np.column_stack([-d[:, 1], d[:, 0]]), atol=1e-12)
    assert np.allclose(sol.angular_velocity("2"), -2.0) and np.allclose(sol.angular_velocity("1"), 1.0)


def five_point(f, h):
    return (f(-2) - 8 * f(-1) + 8 * f(1) - f(2)) / (12 * h)


@pytest.mark.parametrize("omega", [1.0, -2.5])
def test_velocity_and_acceleration_match_finite_differences(mech, omega):
    phi = np.linspace(0.0, 2 * np.pi, 37)[:-1]
    h = FD_STEP
    shifted = {k: mech.solve(phi + k * h, omega) for k in (-2, -1, 1, 2)}
    sol = mech.solve(phi, omega)
    for j in MOVING:
        v_fd = omega * five_point(lambda k: shifted[k].position(j), h)
        a_fd = omega * five_point(lambda k: shifted[k].velocity(j), h)
        v, a = sol.velocity(j), sol.acceleration(j)
        assert np.max(np.abs(v - v_fd)) < VEL_TOL * np.max(np.abs(v)), j
        assert np.max(np.abs(a - a_fd)) < ACC_TOL * np.max(np.abs(a)), j
    for link in ("3", "4", "5", "6"):
        w_fd = omega * five_point(lambda k: shifted[k].link_angle(link), h)
        e_fd = omega * five_point(lambda k: shifted[k].angular_velocity(link), h)
        assert np.max(np.abs(sol.angular_velocity(link) - w_fd)) < VEL_TOL * abs(omega) * 10, link
        assert np.max(np.abs(sol.angular_acceleration(link) - e_fd)) < ACC_TOL * omega ** 2 * 10, link


def test_crank_shares_match_partial_differences(mech):
    """Independent oracle of the superposition: crank 2's share is dP/dphi2 * omega2, the position's
    difference quotient in crank 2's phase with crank 1 held."""
    phi = np.linspace(0.0, 2 * np.pi, 25)[:-1]
    h = FD_STEP
    sol = mech.solve(phi, 1.0)
    shifted = {k: sixbar(phase=4.73 + k * h).solve(phi) for k in (-2, -1, 1, 2)}
    for j in MOVING:
        share2 = -2.0 * five_point(lambda k: shifted[k].position(j), h)
        assert np.max(np.abs(sol.velocity(j, crank=2) - share2)) < VEL_TOL * 100, j


def test_rocker_swing_matches_the_reference(sol):
    swing = np.ptp(sol.link_angle("6"))
    assert abs(math.degrees(swing) - 28.5) < 0.05


def test_lock_positions_are_found_and_never_jumped():
    mech = sixbar(e_k=40.0, hint=False)
    locks = mech.lock_positions()
    assert len(locks) == 2
    for lock in mech.cycle().locks:                     # the Jacobian in the joints is singular there
        f, jac = mech.residual(lock)
        sv = np.linalg.svd(jac[:, :-1], compute_uv=False)
        assert sv[-1] / sv[0] < 1e-7 and np.max(np.abs(f)) < 1e-9
    lo, hi = min(locks), max(locks)
    inside = np.linspace(lo + 1e-3, hi - 1e-3, 721)
    sol = mech.solve(inside)
    k = sol.position("K")
    assert np.max(np.abs(dist(k, np.array([153.0, 155.0])) - 40.0)) < CONSTRAINT_TOL
    assert np.max(np.linalg.norm(np.diff(k, axis=0), axis=1)) < 5.0     # continuous on one assembly
    with pytest.raises(LockError, match="locks") as info:
        mech.solve([hi + 1e-3])
    assert np.allclose(np.sort(info.value.locks), np.sort(locks))
    # independent oracle of the lock angle: a warm-started fsolve of the angle loop equations marching
    # towards it converges up to just below the lock and has no solution nearby just beyond it
    near = mech.solve([hi - 0.05])
    p = {j: near.position(j)[0] for j in JOINTS}
    guess = np.array([math.atan2(*(p[q] - p[r])[::-1]) for r, q in
                      (("A", "B"), ("B", "C"), ("E", "K"), ("D", "C"))])
    for phi in np.linspace(hi - 0.05, hi - 1e-4, 50):
        _, guess, residual = angle_loop_solution(phi, guess, e_k=40.0)
        assert residual < 1e-9
    assert angle_loop_solution(hi + 1e-4, guess, e_k=40.0)[2] > 1e-6


def test_geometry_that_cannot_be_assembled():
    with pytest.raises(ValueError, match="cannot be assembled.*none of"):
        sixbar(e_k=5.0).solve(PHI[:10])


def test_bad_input_is_rejected(mech, sol):
    with pytest.raises(ValueError, match="joint"):
        sol.position("Z")
    with pytest.raises(ValueError, match="crank"):
        sol.velocity("K", crank=3)
    with pytest.raises(ValueError, match="crank_angles"):
        mech.solve([0.0, np.nan])
    with pytest.raises(ValueError, match="omega"):
        mech.solve([0.0], omega=0.0)
    with pytest.raises(ValueError, match="degree of freedom"):
        Linkage(mech.fixed, mech.cranks, mech.links[:-1])
    with pytest.raises(ValueError, match="gear ratio"):
        sixbar(omega_ratio=math.pi)
    with pytest.raises(ValueError, match="link 3"):
        Linkage(mech.fixed, mech.cranks, [Link("3", ("A", "B"), length=-1.0)] + mech.links[1:])
    size = 2 * len(mech.moving) + 1
    with pytest.raises(ValueError, match=rf"^state must have shape \({size},\)"):
        mech.positions([1.0, 2.0])
    with pytest.raises(ValueError, match="^state must be finite, got an integer too large for a float"):
        mech.positions([10 ** 400] * size)
    with pytest.raises(TypeError, match="^state must be an array of real numbers"):
        mech.positions("a")


def test_a_linkage_checks_its_parts_when_made(mech):
    """Fixed joints, hints and the parts are checked when the linkage is made, naming them (a NaN pivot or a
    partial hint failed later inside solve, with scipy's or a KeyError's message)."""
    fixed = dict(mech.fixed)
    first = next(iter(fixed))
    hint = dict(mech.hint)
    for bad, error, words in (
            (dict(fixed={**fixed, first: (np.nan, 0.0)}), ValueError, rf"fixed\['{first}'\] must be finite"),
            (dict(fixed={**fixed, first: (np.inf, 0.0)}), ValueError, rf"fixed\['{first}'\] must be finite"),
            (dict(fixed=None), TypeError, "fixed must be a dict"),
            (dict(cranks=["x"]), TypeError, r"cranks\[0\] must be a planar.Crank"),
            (dict(links=["x"]), TypeError, r"links\[0\] must be a planar.Link"),
            (dict(hint={mech.moving[0]: (0.0, 0.0)}), ValueError, "hint must give every moving joint"),
            (dict(hint={**hint, mech.moving[0]: (np.nan, 0.0)}), ValueError, "must be finite"),
            (dict(hint_angle="a"), TypeError, "hint_angle must be a real number")):
        parts = dict(fixed=mech.fixed, cranks=mech.cranks, links=mech.links, hint=hint, hint_angle=mech.hint_angle)
        parts.update(bad)
        with pytest.raises(error, match=words):
            Linkage(**parts)
    with pytest.raises(ValueError, match="assembly must be a non-negative integer"):
        mech.solve([0.0], assembly="x")


def four_bar_with_pin_on_the_coupler():
    """A crank's pin that is also a rigid link's further joint (defined twice: the link's rows stay implicit)
    and a crank on a moving pivot (its pin depends on an explicit joint)."""
    return Linkage({"O": (0.0, 0.0), "F": (60.0, 0.0)},
                   [Crank("1", "O", "A", 15.0), Crank("2", "B", "P", 5.0, ratio=2.0)],
                   [Link("c", ("B", "C", "A"), shape=((0, 0), (40, 0), (-10, -30))),
                    Link("r", ("F", "C"), length=45.0)])


def links_defining_each_other():
    """Two ternary links whose further joints define each other (D from B and C, B from D and E): a cycle,
    so one of them stays implicit."""
    return Linkage({"O": (0.0, 0.0), "F": (60.0, 0.0)}, [Crank("1", "O", "A", 15.0)],
                   [Link("1", ("B", "C", "D"), shape=((0, 0), (30, 0), (10, 20))),
                    Link("2", ("D", "E", "B"), shape=((0, 0), (25, 0), (5, -15))),
                    Link("3", ("A", "B"), length=50.0), Link("4", ("F", "E"), length=40.0)])


def cranks_alone():
    """No links: every joint explicit, nothing left for the Schur complement."""
    return Linkage({"O": (0.0, 0.0), "Q": (5.0, 0.0)}, [Crank("1", "O", "A", 2.0), Crank("2", "Q", "B", 1.0, 0.5)],
                   [])


@pytest.mark.parametrize("make", [planar.examples.fnf_sixbar, four_bar_with_pin_on_the_coupler,
                                  links_defining_each_other, cranks_alone])
def test_block_elimination_solves_like_numpy(make):
    """Oracle: numpy.linalg.solve of the full J_q, at random states (the structure, not the solution, matters)."""
    mech = make()
    n = 2 * len(mech.moving)
    rng = np.random.default_rng(7)
    f, jac, dtheta, gs, piv, a, z, x = kn.workspace(n, len(mech.cranks), mech.layout)
    for _ in range(20):
        y = np.append(rng.normal(size=n), rng.uniform(0, 2 * np.pi))
        kn.linkage_system(y, mech.ci, mech.cf, mech.fixed_xy, f, jac, dtheta)
        assert kn.factor_reduced(jac, mech.layout, gs, piv)
        b = rng.normal(size=n)
        kn.solve_reduced(jac, mech.layout, gs, piv, b, x, a, z)
        ref = np.linalg.solve(jac[:, :n], b)
        assert np.max(np.abs(x - ref)) < 1e-14 * np.max(np.abs(ref)) * np.linalg.cond(jac[:, :n])


def test_each_angle_is_solved_alone(mech, sol):
    """Identity: an angle's state and derivatives do not depend on the other angles asked for (neighbours
    predict by expansion, lone angles from the traced curve, in any order)."""
    rng = np.random.default_rng(3)
    pick = rng.permutation(N)[:40]
    alone = mech.solve(PHI[pick])
    scale = {"v": np.max(np.abs(sol.velocity("K"))), "a": np.max(np.abs(sol.acceleration("K")))}
    for j in MOVING:
        assert np.max(np.abs(alone.position(j) - sol.position(j)[pick])) < 1e-12
        assert np.max(np.abs(alone.velocity(j) - sol.velocity(j)[pick])) < 1e-13 * scale["v"]
        assert np.max(np.abs(alone.acceleration(j) - sol.acceleration(j)[pick])) < 1e-13 * scale["a"]
    shuffled = mech.solve(PHI[::-1])
    assert np.max(np.abs(shuffled.states[::-1] - sol.states)) < 1e-13


def test_examples_import_as_the_tutorials_spell_it():
    """``import planar.examples`` and ``from planar.examples import fnf_sixbar`` reach the one examples module."""
    import importlib
    import planar
    examples = importlib.import_module("planar.examples")
    assert examples is planar.examples is planar.linkage.examples
    from planar.examples import fnf_sixbar
    assert fnf_sixbar is planar.linkage.examples.fnf_sixbar


@pytest.mark.parametrize("shift", [5000.0, 1e6])
def test_a_linkage_far_from_the_origin_moves_as_at_it(mech, shift):
    """The six-link moved by shift along x (a LockError 'locks at none found' before): identity oracle, the
    motion at the origin translated, to 64 ulps of the coordinates (times the velocities' and accelerations'
    scale)."""
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    far = Linkage({k: v + (shift, 0.0) for k, v in mech.fixed.items()}, mech.cranks, mech.links,
                  hint={k: v + (shift, 0.0) for k, v in mech.hint.items()}, hint_angle=mech.hint_angle)
    near, moved = mech.solve(phi, omega=2.0), far.solve(phi, omega=2.0)
    tol = 64 * np.finfo(float).eps * (shift + mech.mean_length)
    for joint in mech.moving:
        np.testing.assert_allclose(moved.position(joint) - (shift, 0.0), near.position(joint), rtol=0, atol=tol)
        np.testing.assert_allclose(moved.velocity(joint), near.velocity(joint), rtol=0, atol=16 * tol)
        np.testing.assert_allclose(moved.acceleration(joint), near.acceleration(joint), rtol=0, atol=64 * tol)
