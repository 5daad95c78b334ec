"""The crank torque of a four-bar with masses on all three moving links, under gravity at a constant input rate,
against an independent formulation: Kane's method in sympy.physics.mechanics (the loop-closure equations as
configuration constraints, the coupler's and rocker's rates as dependent speeds), solved at each position for the
torque that keeps the crank's acceleration zero. Agreement to 1e-8 relative."""
import numpy as np
import pytest

import planar
from spatialkin.dynamics import Body

sm = pytest.importorskip("sympy")
me = pytest.importorskip("sympy.physics.mechanics")

#: The four-bar: crank a, coupler b, rocker c, frame d; masses (kg) of uniform rods; gravity; input rate.
A_LEN, B_LEN, C_LEN, D_LEN = 2.0, 5.0, 4.0, 4.5
M1, M2, M3, G, OMEGA = 0.3, 0.7, 0.5, 9.81, 3.0


def kane_model():
    """(mass matrix, forcing, velocity-constraint jacobian in the dependent speeds and its rest) as functions of the
    coordinates Q (3,), speeds U (3,) and the torque T on the crank."""
    q1, q2, q3 = me.dynamicsymbols("q1 q2 q3")
    u1, u2, u3 = me.dynamicsymbols("u1 u2 u3")
    torque = sm.symbols("T")
    n = me.ReferenceFrame("N")
    frames = [n.orientnew(name, "Axis", (q, n.z)) for name, q in (("A", q1), ("B", q2), ("C", q3))]
    for frame, u in zip(frames, (u1, u2, u3)):
        frame.set_ang_vel(n, u * n.z)
    crank, coupler, rocker = frames
    o = me.Point("O")
    o.set_vel(n, 0)
    p = o.locatenew("P", D_LEN * n.x)
    p.set_vel(n, 0)
    pin = o.locatenew("Pa", A_LEN * crank.x)
    pin.v2pt_theory(o, n, crank)
    g1 = o.locatenew("G1", A_LEN / 2 * crank.x)
    g1.v2pt_theory(o, n, crank)
    g2 = pin.locatenew("G2", B_LEN / 2 * coupler.x)
    g2.v2pt_theory(pin, n, coupler)
    g3 = p.locatenew("G3", C_LEN / 2 * rocker.x)
    g3.v2pt_theory(p, n, rocker)
    loop = pin.pos_from(o) + B_LEN * coupler.x - C_LEN * rocker.x - D_LEN * n.x
    conf = [loop.dot(n.x), loop.dot(n.y)]
    t = me.dynamicsymbols._t
    vel = [e.diff(t).subs({q1.diff(t): u1, q2.diff(t): u2, q3.diff(t): u3}) for e in conf]
    bodies = [me.RigidBody(name, g, frame, m, (me.inertia(frame, 0, 0, m * length ** 2 / 12), g))
              for name, g, frame, m, length in (("crank", g1, crank, M1, A_LEN), ("coupler", g2, coupler, M2, B_LEN),
                                                ("rocker", g3, rocker, M3, C_LEN))]
    loads = [(g1, -M1 * G * n.y), (g2, -M2 * G * n.y), (g3, -M3 * G * n.y), (crank, torque * n.z)]
    kane = me.KanesMethod(n, q_ind=[q1], u_ind=[u1], kd_eqs=[q1.diff() - u1, q2.diff() - u2, q3.diff() - u3],
                          q_dependent=[q2, q3], configuration_constraints=conf, u_dependent=[u2, u3],
                          velocity_constraints=vel)
    kane.kanes_equations(bodies, loads)
    q, u = sm.symbols("Q1:4"), sm.symbols("U1:4")
    sub = dict(zip([q1, q2, q3, u1, u2, u3], list(q) + list(u)))
    constraints = sm.Matrix(vel).subs(sub)
    return (sm.lambdify([q, u], kane.mass_matrix.subs(sub)), sm.lambdify([q, u, torque], kane.forcing.subs(sub)),
            sm.lambdify([q, u], constraints.jacobian(sm.Matrix(u[1:]))),
            sm.lambdify([q, u], constraints.subs({u[1]: 0, u[2]: 0})))


def test_crank_torque_against_kanes_method():
    four = planar.Linkage(fixed={"O": (0.0, 0.0), "P": (D_LEN, 0.0)}, cranks=[planar.Crank("1", "O", "A", A_LEN)],
                          links=[planar.Link("2", ("A", "B"), length=B_LEN), planar.Link("3", ("P", "B"), length=C_LEN)],
                          hint={"A": (A_LEN, 0.0), "B": (D_LEN + 1.0, 3.8)})
    angles = np.linspace(0.0, 2 * np.pi, 25)[:-1]
    sol = four.solve(angles, omega=OMEGA)
    ours = sol.loads(bodies={"1": Body.rod(M1, A_LEN), "2": Body.rod(M2, B_LEN), "3": Body.rod(M3, C_LEN)},
                     gravity=(0.0, -G)).torque["1"]
    mass, forcing, dependent, rest = kane_model()
    theirs = []
    for k, q1 in enumerate(angles):
        a, b = sol.position("A")[k], sol.position("B")[k]
        q = (q1, np.arctan2(b[1] - a[1], b[0] - a[0]), np.arctan2(b[1], b[0] - D_LEN))
        u_dep = np.linalg.solve(np.array(dependent(q, (OMEGA, 0, 0)), float),
                                -np.array(rest(q, (OMEGA, 0, 0)), float).ravel())
        u = (OMEGA, *u_dep)
        m = np.array(mass(q, u), float)
        f0 = np.array(forcing(q, u, 0.0), float).ravel()
        f1 = np.array(forcing(q, u, 1.0), float).ravel() - f0
        # the crank at constant rate: its acceleration zero, the others' and the torque from the three equations
        theirs.append(np.linalg.solve(np.column_stack([m[:, 1], m[:, 2], -f1]), f0)[2])
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-8 * np.max(np.abs(theirs)))
