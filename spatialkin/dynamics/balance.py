"""A counterweight on a crank turning at a constant rate that minimises the RMS shaking force over the cycle.

A point mass m at radius rho and angle phi in the crank's own frame (its plane normal to the crank axis) adds
m omega^2 R(theta) (rho cos phi, rho sin phi) to the force the mechanism shakes into the frame (its centripetal
force, R(theta) the crank frame's axes at crank angle theta), and nothing else: the mechanism's motion is given.
The added force is linear in the mass moment w = m rho (cos phi, sin phi), so the sum over the cycle of
|F(theta) + omega^2 R(theta) w|^2 is least at the solution of a 2 x 2 normal system, exactly.

References
----------
R. L. Norton, Design of Machinery, 5th ed., ch. 12 (balancing linkages by counterweights on the cranks).
"""
from dataclasses import dataclass

import numpy as np

from .._lib.validation import check_positive
from .body import Body, combined


@dataclass(frozen=True)
class Counterweight:
    """The counterweight: its mass (kg), radius (length unit) and angle (rad, in the crank's frame from its x axis
    towards its y axis) and as a Body on the crank; the shaking force's peak and RMS (over the cycle's instants) and
    the peak driving torque before and after it is added."""
    mass: float
    radius: float
    angle: float
    body: Body
    before: dict
    after: dict

    def __repr__(self):
        return (f"Counterweight(mass={self.mass:.6g} kg at radius {self.radius:g}, angle "
                f"{np.degrees(self.angle):.2f} deg; RMS shaking force {self.before['rms_force']:.4g} -> "
                f"{self.after['rms_force']:.4g}, peak {self.before['peak_force']:.4g} -> {self.after['peak_force']:.4g})")


def mass_moment(shaking, axes, rate):
    """The mass moment w (2,) (kg x length) of the counterweight minimising sum |shaking + rate^2 axes @ w|^2:
    shaking (N, d) the force without it, axes (N, d, 2) the crank frame's x and y axes at each instant, rate the
    crank's angular rate."""
    columns = rate ** 2 * axes
    normal = np.einsum("nda,ndb->ab", columns, columns)
    return np.linalg.solve(normal, -np.einsum("nda,nd->a", columns, shaking))


def figures(loads, torque):
    """{'peak_force', 'rms_force', 'peak_torque'} of loads (its shaking force) and a torque (N,)."""
    magnitude = np.linalg.norm(loads.shaking_force, axis=1)
    return {"peak_force": float(np.max(magnitude)), "rms_force": float(np.sqrt(np.mean(magnitude ** 2))),
            "peak_torque": float(np.max(np.abs(torque)))}


def counterweight(loads_of, bodies, crank, axes, rate, radius, torque_of):
    """The counterweight on the link `crank` at `radius` (length unit, > 0) of least RMS shaking force.

    loads_of(bodies) gives the mechanism's Loads with the given bodies; axes (N, d, 2) are the crank frame's x and
    y axes at each instant (d = 3, or 2 for a planar mechanism: the shaking force's first d components), rate the
    crank's angular rate, torque_of(loads) the crank's driving torque (N,). Returns a Counterweight."""
    radius = check_positive("radius", radius)
    before = loads_of(bodies)
    moment = mass_moment(before.shaking_force[:, :axes.shape[1]], axes, rate)
    mass, angle = float(np.hypot(*moment)) / radius, float(np.arctan2(moment[1], moment[0]))
    weight = Body.point(mass, (radius * np.cos(angle), radius * np.sin(angle), 0.0))
    bodies = dict(bodies or {})
    after = loads_of({**bodies, crank: combined(bodies[crank], weight) if crank in bodies else weight})
    return Counterweight(mass, radius, angle, weight, figures(before, torque_of(before)),
                         figures(after, torque_of(after)))
