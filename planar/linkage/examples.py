"""Ready-made planar linkages with reference geometries (assumed dimensions where the source gives none)."""
from .model import Crank, Link, Linkage

#: Gear teeth of the FNF drive: z1 on crank 1, z2 on crank 2, in external mesh (omega2 = -z1/z2 omega1).
FNF_TEETH = (40, 20)
#: Phase of crank 2 (rad): phi2 = FNF_PHASE - 2 phi1.
FNF_PHASE = 4.73


def fnf_sixbar():
    """The double-crank six-link mechanism of the FNF warp-knitting machine, with its reference geometry.

    Cranks 1 = O1A and 2 = O2D, geared (z1 = 40, z2 = 20 in external mesh: phi2 = 4.73 - 2 phi1), rods 3 = AB
    and 5 = DC, ternary link 4 = B-C-K, output rocker 6 = EK pivoted at E; links 3, 4, 5, 6 form the Assur group
    of class III (a triad) [1]_. Angles anticlockwise from the global x-axis, lengths in mm: O1 = (0, 0),
    O2 = (81, 0), E = (153, 155); O1A = 14, O2D = 16, AB = 137, DC = 107, EK = 58; link 4 has C at 99 mm from B
    and K at (30, 45) in B's frame along BC. The dimensions are assumed (the paper gives none) and checked to
    assemble over a full cycle. The assembly is the one whose rocker 6 swings about 28.5 deg (K near (95, 155)
    at phi1 = 0).

    Returns
    -------
    Linkage
        Fixed joints O1, O2, E; moving joints A, D, B, C, K; cranks '1', '2'; links '3', '5', '4', '6'.

    See Also
    --------
    Linkage.solve : its motion at given input angles.

    References
    ----------
    .. [1] S. O. Koshel, A. V. Koshel, "Double-crank mechanism kinematic study of warp knitting machine", Visnyk
       KNUTD (Bulletin of the Kyiv National University of Technologies and Design), 2014, no. 2 (in Ukrainian).

    Examples
    --------
    >>> import numpy as np
    >>> import planar
    >>> mech = planar.examples.fnf_sixbar()
    >>> mech.moving, [c.name for c in mech.cranks]
    (['A', 'D', 'B', 'C', 'K'], ['1', '2'])
    >>> sol = mech.solve(np.linspace(0.0, 2 * np.pi, 361), omega=1.0)
    >>> sol.position("K")[0].round(1).tolist()
    [95.0, 155.0]
    >>> round(float(np.degrees(np.ptp(sol.link_angle("6")))), 1)      # the rocker's swing
    28.5
    """
    z1, z2 = FNF_TEETH
    return Linkage(
        fixed={"O1": (0.0, 0.0), "O2": (81.0, 0.0), "E": (153.0, 155.0)},
        cranks=[Crank("1", "O1", "A", 14.0),
                Crank("2", "O2", "D", 16.0, ratio=-z1 / z2, phase=FNF_PHASE)],
        links=[Link("3", ("A", "B"), length=137.0),
               Link("5", ("D", "C"), length=107.0),
               Link("4", ("B", "C", "K"), shape=((0.0, 0.0), (99.0, 0.0), (30.0, 45.0))),
               Link("6", ("E", "K"), length=58.0)],
        hint={"A": (14.0, 0.0), "D": (81.28, -16.0), "B": (45.45, 133.34), "C": (128.78, 79.88),
              "K": (95.0, 155.02)},
        hint_angle=0.0)
