"""The looper drive's forces at machine speed beside its kinematics: a whole cycle of 3601 crank angles, the motion
(LooperDrive.solve) against all its loads (LooperMotion.loads: crank torque, five joints, shaking force and
moment) with the example steel links, interleaved in one process, medians."""
import statistics
import time

import numpy as np

#: Calls per side (full run, --quick), after one untimed call of each.
CALLS, QUICK_CALLS = 21, 5
#: Crank angles of the cycle.
ANGLES = 3601


def run(quick=False, echo=print):
    """Time both sides and print the table; returns (kinematics s, loads s) medians."""
    from ..dynamics import Body
    from ..mechanisms import LooperDrive
    from ..mechanisms.looper.reference import STEEL_LINKS
    drive = LooperDrive.reference()
    bodies = {k: Body(v["mass"], v["com"], v["inertia"]) for k, v in STEEL_LINKS.items()}
    angles = np.linspace(0.0, 2 * np.pi, ANGLES)
    omega = 2000 * np.pi / 30
    motion = drive.solve(angles, omega=omega)
    motion.loads(bodies)
    kinematics, loads = [], []
    for _ in range(QUICK_CALLS if quick else CALLS):
        t0 = time.perf_counter()
        motion = drive.solve(angles, omega=omega)
        t1 = time.perf_counter()
        motion.loads(bodies)
        t2 = time.perf_counter()
        kinematics.append(t1 - t0)
        loads.append(t2 - t1)
    k, f = statistics.median(kinematics), statistics.median(loads)
    echo(f"looper drive over {ANGLES} crank angles at 2000 rpm (medians of {len(loads)} interleaved calls): "
         f"motion {1e3 * k:.1f} ms, all loads {1e3 * f:.1f} ms (loads/motion {f / k:.2f})")
    return k, f
