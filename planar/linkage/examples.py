"""Ready-made planar linkages with the reference geometries of ../shared/reference."""
from .model import Crank, Link, Linkage

#: Gear teeth of the FNF drive: z1 on crank 1, z2 on crank 2, in external mesh (omega2 = -z1/z2 omega1).
FNF_TEETH = (40, 20)
#: Phase of crank 2 (rad): phi2 = FNF_PHASE - 2 phi1.
FNF_PHASE = 4.73


def fnf_sixbar():
    """The double-crank six-link mechanism of the FNF warp-knitting machine (seed 001), reference geometry.

    Cranks 1 = O1A and 2 = O2D (geared: phi2 = 4.73 - 2 phi1), rods 3 = AB and 5 = DC, ternary link
    4 = B-C-K, output rocker 6 = EK pivoted at E; links 3, 4, 5, 6 form the class III triad. Angles
    anticlockwise from the global x-axis, lengths in mm. The assembly is the one whose rocker 6 swings
    about 28.5 deg (K near (95, 155) at phi1 = 0).

    References
    ----------
    Seed 001 and ../shared/reference/fnf-sixbar.md (assumed dimensions, checked to assemble over a cycle).
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
