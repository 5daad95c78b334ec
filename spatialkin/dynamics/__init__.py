"""Dynamics of mechanisms whose motion is known: mass properties of links (``Body``) and inverse dynamics by
Newton-Euler (``inverse_dynamics``: the joints' forces, the driving torques, the shaking force and moment), and the
crank counterweight that minimises the RMS shaking force (``Counterweight``).

Units: kg, the mechanism's length unit L and s; forces in kg L / s^2, moments in kg L^2 / s^2.
"""
from .balance import Counterweight
from .body import Body, combined
from .newton_euler import DRIVEN, REVOLUTE, SPHERICAL, Joint, Loads, inverse_dynamics

__all__ = ["Body", "combined", "Counterweight", "Joint", "Loads", "inverse_dynamics", "REVOLUTE", "DRIVEN", "SPHERICAL"]
