"""Dynamics of mechanisms whose motion is known: mass properties of links (``Body``) and inverse dynamics by
Newton-Euler (``inverse_dynamics``: the joints' forces, the driving torques, the shaking force and moment).

Units: kg, the mechanism's length unit L and s; forces in kg L / s^2, moments in kg L^2 / s^2.
"""
from .body import Body
from .newton_euler import DRIVEN, REVOLUTE, SPHERICAL, Joint, Loads, inverse_dynamics

__all__ = ["Body", "Joint", "Loads", "inverse_dynamics", "REVOLUTE", "DRIVEN", "SPHERICAL"]
