"""The reference looper drive (lengths in mm), defined once.

``LooperDrive.reference()``, the looper job's default configuration, ``spatialkin demo``, the bench cases and
the tests take the reference geometry from here: the crank frame is the global axes, the rocker frame sits at
the rocker centre P2 turned a quarter turn about x (its z, the rocker shaft, along +y).

References
----------
The scheme (torus ∩ sphere for the spatial five-link crank-rocker that drives the looper of blind-stitch sewing
machines) is that of "Investigation of the trajectories of characteristic points of spatial mechanisms of
technological machines of the light industry" (in Ukrainian; [Looper]). The reference geometry is assumed: the
paper gives no dimensions.
"""
import math

from ...geometry.frame import Frame, rotation_about
from ...geometry.surfaces import Sphere, Torus

__all__ = ["CRANK_RADIUS", "COUPLER_LENGTH", "ROCKER_LENGTH", "ROCKER_CENTRE", "ROCKER_TURN", "LOOPER_TIP",
           "STEEL_LINKS", "rocker_rotation", "rocker_frame", "looper_pair"]

#: R1, crank pin axis to crank shaft: the torus's major radius.
CRANK_RADIUS = 8.0
#: r1, ball centre C to the crank pin axis: the torus's minor radius.
COUPLER_LENGTH = 50.0
#: R2, ball centre C to the rocker centre P2: the sphere's radius.
ROCKER_LENGTH = 30.0
#: P2, the rocker centre, in the crank frame (the global axes).
ROCKER_CENTRE = (6.0, 0.0, 75.0)
#: Turn (rad) of the rocker frame about the global x axis: its local z (the rocker shaft) points along +y.
ROCKER_TURN = -math.pi / 2
#: The looper tip in the rocker arm's frame: 40 mm along the arm (x from P2 to C), 12 mm off it.
LOOPER_TIP = (40.0, 0.0, 12.0)


#: An example of mass properties for the reference drive: plausible steel links (density 7850 kg/m^3), sized as a
#: designer might sketch them; not data from the papers. Per link, in its own frame: mass (kg), centre of mass (mm),
#: inertia about it (kg mm^2), slender rods and point masses combined (spatialkin.dynamics.combined):
#: - crank: a 15 g arm over the 8 mm crank radius;
#: - coupler: a 20 g rod (8 mm, 50 mm from the pin axis to C) and the 6 g ball at C;
#: - rocker shaft: a 37 g shaft (10 mm, 60 mm long) about its axis, centred on P2;
#: - rocker arm: a 12 g rod (8 mm, 30 mm from P2 to C) and the 15 g looper at its tip (40, 0, 12).
STEEL_LINKS = {
    "crank": {"mass": 0.015, "com": [4.0, 0.0, 0.0], "inertia": [[0.0, 0.0, 0.0], [0.0, 0.08, 0.0],
                                                                 [0.0, 0.0, 0.08]]},
    "coupler": {"mass": 0.026, "com": [30.769, 0.0, 0.0], "inertia": [[0.0, 0.0, 0.0], [0.0, 7.051, 0.0],
                                                                      [0.0, 0.0, 7.051]]},
    "rocker_shaft": {"mass": 0.037, "com": [0.0, 0.0, 0.0], "inertia": [[11.3, 0.0, 0.0], [0.0, 11.3, 0.0],
                                                                       [0.0, 0.0, 0.46]]},
    "rocker_arm": {"mass": 0.027, "com": [28.889, 0.0, 6.667], "inertia": [[0.96, 0.0, -2.0], [0.0, 6.027, 0.0],
                                                                          [-2.0, 0.0, 5.067]]},
}


def rocker_rotation():
    """The rocker frame's rotation (3, 3): ROCKER_TURN about the global x axis."""
    return rotation_about((1.0, 0.0, 0.0), ROCKER_TURN)


def rocker_frame():
    """The rocker frame: origin ROCKER_CENTRE, rotation rocker_rotation()."""
    return Frame(ROCKER_CENTRE, rocker_rotation())


def looper_pair():
    """(torus, sphere) of the reference drive: the ball centre's two surfaces, whose intersection is its path.

    The torus (CRANK_RADIUS, COUPLER_LENGTH) in the crank frame (the global axes), the sphere (ROCKER_LENGTH)
    about the rocker centre in rocker_frame().
    """
    return Torus(CRANK_RADIUS, COUPLER_LENGTH), Sphere(ROCKER_LENGTH, rocker_frame())
