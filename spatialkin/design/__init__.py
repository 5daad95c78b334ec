"""Designing a looper drive: a design vector of named parameters, exact sensitivities of the motion by the
implicit function theorem, synthesis to targets, tolerance analysis and sweeps.

    from spatialkin.design import LooperDesign, sweep
    design = LooperDesign.from_drive(drive, free=("rocker_length", "crank_radius"))
    sens = design.sensitivities(crank_angles)        # values and exact derivatives, the whole cycle at once
    fitted = design.fit(targets)                     # scipy.optimize.least_squares with those derivatives
    table = sweep(space, outputs, client=None)       # local processes, or a dask.distributed Client

No pyvista and no matplotlib here: pictures are in spatialkin.plots.design.

References
----------
"Investigation of the trajectories of characteristic points of spatial mechanisms of technological machines of the
light industry" (in Ukrainian; [Looper]): the looper drive, torus ∩ sphere.
A. Griewank, A. Walther, Evaluating Derivatives, SIAM 2008, ch. 13: Taylor arithmetic of implicit functions.
"""
from .fit import FitResult, Targets
from .looper import LooperDesign
from .params import PARAMETERS
from .sensitivity import Sensitivities
from .sweep import OUTPUTS, grid_space, random_space, sweep

__all__ = ["FitResult", "LooperDesign", "OUTPUTS", "PARAMETERS", "Sensitivities", "Targets", "grid_space",
           "random_space", "sweep"]
