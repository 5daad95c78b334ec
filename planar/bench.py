"""Planar cases of ``spatialkin bench``: speed against peers, with the accuracy of each as a check.

(a) The crank-slider of Pylypaka et al. (k = 0.5, e = 1, L = 4): positions, velocities and accelerations of the
    crank pin and the slider at 3600 crank positions - the Frenet module against pylinkage's numba path
    (``step_fast_with_kinematics``, optional: ``pip install pylinkage``) and the closed form.
(b) The double-crank six-link of the FNF warp-knitting machine (Koshel and Koshel), a full turn at 3601 positions
    with velocities and accelerations - the continuation pipeline against a warm-started per-angle
    ``scipy.optimize.root`` of the same loop equations (given the same jitted residual and Jacobian, so only the
    method differs).

Times are the best of several warm runs (numba compiled and cached beforehand); ratios compare runs made
side by side in one process.

References
----------
S. Pylypaka, A. Chepyzhniy, T. Kresan, "Determining kinematic characteristics of planar mechanisms' driven member
using Frenet trihedron", 2017.
S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk KNUTD
(Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian).
"""
import math

import numpy as np
from scipy.optimize import root

from spatialkin.bench import best_time

from .frenet import CrankSlider, DrivenLink
from .linkage import examples, kernels as kn

SLIDER = dict(k=0.5, e=1.0, L=4.0)
SLIDER_POSITIONS = 3600
SIXBAR_POSITIONS = 3601
REPEATS = 7
#: Newton / root tolerance of the per-angle solve (scaled units, as the linkage's own Newton).
ROOT_TOL = 1e-14


# --- (a) crank-slider -----------------------------------------------------------------------------
def slider_closed_form(k, e, L, phi, omega=1.0):
    """Pin and slider (positions, velocities, accelerations) (n, 2) of the crank-slider with the crank
    centre at the origin, crank angle phi from +x anticlockwise (pin r (cos phi, sin phi)) and the slider on
    y = e to the right of the pin; the oracle of both implementations."""
    r = 1.0 / k
    c, s = np.cos(phi), np.sin(phi)
    pin = r * np.column_stack([c, s])
    pin_v = omega * r * np.column_stack([-s, c])
    pin_a = -omega ** 2 * pin
    u = e - r * s
    w = np.sqrt(L * L - u * u)
    du = -r * c
    ddu = r * s
    dw = -u * du / w
    ddw = (-(du * du) - u * ddu - dw * dw) / w          # from w dw = -u du
    x = r * c + w
    slider = np.column_stack([x, np.full_like(x, e)])
    slider_v = omega * np.column_stack([-r * s + dw, np.zeros_like(x)])
    slider_a = omega ** 2 * np.column_stack([-r * c + ddw, np.zeros_like(x)])
    return (pin, pin_v, pin_a), (slider, slider_v, slider_a)


def frenet_slider(n, k=SLIDER["k"], e=SLIDER["e"], L=SLIDER["L"], omega=1.0):
    """run() -> positions, velocities, accelerations (n, 2 points, 2) of the crank pin (rho = 0) and the
    slider (rho = L) from the Frenet module at crank angles phi = 2 pi i / n from +x.

    The Frenet module's pin is (sin ks, -cos ks)/k = r (cos(ks - pi/2), sin(ks - pi/2)) with the guide y = e and
    the slider to the right on branch 0: the same axes as the oracle, with ks = phi + pi/2."""
    link = DrivenLink(CrankSlider(k, e, L), omega)
    s = (2 * np.pi * np.arange(n) / n + np.pi / 2) / k
    rho = np.array([0.0, L])

    def run():
        t = link.trajectory(s[:, None], rho)
        return t.position, t.velocity, t.acceleration
    return run, link


def pylinkage_slider(n, k=SLIDER["k"], e=SLIDER["e"], L=SLIDER["L"], omega=1.0):
    """run() -> {'pin', 'slider'}: (positions, velocities, accelerations) (n, 2) from pylinkage's numba path
    at crank angles 2 pi i / n; None when pylinkage is not installed.

    pylinkage 1.3's Mechanism bridge leaves prismatic joints static on the fast path, so the component API
    (Ground, Crank, RRPDyad) is used; its crank steps before recording, hence the start one step back."""
    try:
        import pylinkage as pl
    except ImportError:
        return None
    r = 1.0 / k
    dphi = 2 * np.pi / n
    phi0 = -dphi
    xa, ya = r * math.cos(phi0), r * math.sin(phi0)
    xb = xa + math.sqrt(L * L - (e - ya) ** 2)
    origin = pl.Ground(0.0, 0.0, name="O")
    g1, g2 = pl.Ground(0.0, e, name="guide1"), pl.Ground(1.0, e, name="guide2")
    crank = pl.Crank(anchor=origin, radius=r, angular_velocity=dphi, initial_angle=phi0, name="pin")
    slider = pl.RRPDyad(revolute_anchor=crank.output, line_anchor1=g1, line_anchor2=g2, distance=L,
                        x=xb, y=e, name="slider")
    linkage = pl.Linkage([origin, g1, g2, crank, slider], name="crank-slider")
    linkage.set_input_velocity(crank, omega=omega, alpha=0.0)
    linkage.compile()
    i_pin, i_slider = linkage.components.index(crank), linkage.components.index(slider)

    def run():
        crank.x, crank.y = xa, ya
        slider.x, slider.y = xb, e
        pos, vel, acc = linkage.step_fast_with_kinematics(iterations=n, dt=1.0)
        return {"pin": (pos[:, i_pin], vel[:, i_pin], acc[:, i_pin]),
                "slider": (pos[:, i_slider], vel[:, i_slider], acc[:, i_slider])}
    return run


def _max_error(got, ref):
    return max(float(np.max(np.abs(g - r)) / max(np.max(np.abs(r)), 1.0)) for g, r in zip(got, ref))


def slider_case(n=SLIDER_POSITIONS, repeats=REPEATS):
    """Rows (name, positions per second, max relative error vs the closed form, ratio to pylinkage) and
    the max difference between the Frenet module and pylinkage."""
    k, e, L = SLIDER["k"], SLIDER["e"], SLIDER["L"]
    phi = 2 * np.pi * np.arange(n) / n
    pin_ref, slider_ref = slider_closed_form(k, e, L, phi)
    run, _ = frenet_slider(n)
    t_ours, (pos, vel, acc) = best_time(run, repeats)
    ours = {name: tuple(a[:, j] for a in (pos, vel, acc)) for j, name in enumerate(("pin", "slider"))}
    rows = [("Frenet module (jitted law + trajectory pipeline)", n / t_ours,
             max(_max_error(ours["pin"], pin_ref), _max_error(ours["slider"], slider_ref)), None)]
    peer = pylinkage_slider(n)
    diff = None
    if peer is not None:
        t_peer, res = best_time(peer, repeats)
        err = max(_max_error(res["pin"], pin_ref), _max_error(res["slider"], slider_ref))
        diff = max(_max_error(ours[j], res[j]) for j in ("pin", "slider"))
        rows.append(("pylinkage step_fast_with_kinematics", n / t_peer, err, t_peer / t_ours))
    return rows, diff


# --- (b) six-link ---------------------------------------------------------------------------------
def sixbar_ours(phi):
    """run() -> motion of a freshly built six-link (assembly, traced cycle, Newton, derivatives)."""
    def run():
        return examples.fnf_sixbar().solve(phi)
    return run


def sixbar_root(phi):
    """run() -> (positions, velocities, accelerations) (N, n) scaled, by a warm-started per-angle
    scipy.optimize.root (hybr, analytic Jacobian) of the same loop equations, velocities and accelerations
    by the implicit-function formulas with numpy.linalg.solve: what a user writes without a continuation
    pipeline."""
    mech = examples.fnf_sixbar()
    start = mech.assemble(phi[0])
    n = start.size - 1
    f, jac = np.empty(n), np.empty((n, n + 1))
    dtheta = np.empty((n, len(mech.cranks)))
    quad = np.empty(n)
    args = (mech.ci, mech.cf, mech.fixed_xy)

    def system(q, a):
        kn.linkage_system(np.append(q, a), *args, f, jac, dtheta)
        return f.copy(), jac[:, :n].copy()

    def run():
        q = start[:-1].copy()
        qs, vs, accs = (np.empty((len(phi), n)) for _ in range(3))
        for i, a in enumerate(phi):
            res = root(lambda x: system(x, a)[0], q, jac=lambda x: system(x, a)[1], method="hybr",
                       options={"xtol": ROOT_TOL})
            q = res.x
            y = np.append(q, a)
            kn.linkage_system(y, *args, f, jac, dtheta)
            v = np.linalg.solve(jac[:, :n], -jac[:, n])
            kn.linkage_quadratic(y, np.append(v, 1.0), *args, quad)
            qs[i], vs[i], accs[i] = q, v, np.linalg.solve(jac[:, :n], -quad)
        return qs, vs, accs
    return run, mech.mean_length


def sixbar_case(n=SIXBAR_POSITIONS, repeats=3):
    """Rows (name, wall time s, max difference of positions mm, of velocities and accelerations relative)
    and the ratio per-angle root / ours."""
    phi = np.linspace(0.0, 2 * np.pi, n)
    t_ours, sol = best_time(sixbar_ours(phi), repeats)
    mech = sol.linkage
    cached = lambda: mech.solve(phi)                           # noqa: E731 - the traced cycle reused
    t_cached, _ = best_time(cached, repeats)
    run, ell = sixbar_root(phi)
    t_root, (qs, vs, accs) = best_time(run, max(1, repeats // 2))
    m = len(phi)
    ours_q = sol.states[:, :-1] * ell
    ours_v = np.stack([sol.velocity(j) for j in mech.moving], axis=1).reshape(m, -1)
    ours_a = np.stack([sol.acceleration(j) for j in mech.moving], axis=1).reshape(m, -1)
    diff = (float(np.max(np.abs(ours_q - qs * ell))),
            float(np.max(np.abs(ours_v - vs * ell)) / np.max(np.abs(ours_v))),
            float(np.max(np.abs(ours_a - accs * ell)) / np.max(np.abs(ours_a))))
    rows = [("continuation pipeline, fresh mechanism", t_ours, t_root / t_ours),
            ("continuation pipeline, traced cycle reused", t_cached, t_root / t_cached),
            ("per-angle scipy.optimize.root (warm start)", t_root, 1.0)]
    return rows, diff


# --- report ---------------------------------------------------------------------------------------
def report(quick=False, echo=print):
    """Print the planar cases (a spatialkin bench plug-in, entry point group 'spatialkin.bench').

    Returns the measured ratios against the peers {name: ratio} (None where a peer is missing): the Frenet
    module's positions per second over pylinkage's, and the per-angle root solve's time over the six-link
    pipeline's (fresh mechanism)."""
    repeats = 2 if quick else REPEATS
    echo("")
    echo(f"planar (a): Frenet crank-slider k = {SLIDER['k']}, e = {SLIDER['e']}, L = {SLIDER['L']}: pin and "
         f"slider positions, velocities, accelerations at {SLIDER_POSITIONS} crank positions")
    rows, diff = slider_case(repeats=repeats)
    echo(f"{'solver':<52} {'positions/s':>12} {'max rel. error':>15} {'ratio':>7}")
    for name, rate, err, ratio in rows:
        echo(f"{name:<52} {rate:>12.4g} {err:>15.2e} {'' if ratio is None else f'{ratio:.1f}x':>7}")
    pyl = rows[1][3] if len(rows) > 1 else None
    if diff is None:
        echo("pylinkage: not installed -- pip install '.[bench]' for the side-by-side run")
    else:
        echo(f"max difference Frenet module vs pylinkage (relative): {diff:.2e}")
    echo("")
    echo(f"planar (b): FNF double-crank six-link, full turn at {SIXBAR_POSITIONS} positions with velocities and "
         "accelerations")
    rows, (dq, dv, da) = sixbar_case(repeats=1 if quick else 3)
    echo(f"{'solver':<52} {'time [ms]':>12} {'speed-up':>15}")
    for name, t, ratio in rows:
        echo(f"{name:<52} {1e3 * t:>12.2f} {ratio:>14.1f}x")
    echo(f"max difference pipeline vs root solve: positions {dq:.1e} mm, velocities {dv:.1e}, "
         f"accelerations {da:.1e} (relative)")
    return {"Frenet module vs pylinkage": pyl, "six-link full turn vs per-angle root solve": rows[0][2]}
