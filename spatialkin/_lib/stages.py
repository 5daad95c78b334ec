"""An opt-in stage timer of the intersect path: where the time of one ``sk.intersect`` call goes.

Off by default: each timed place in the library costs one test of ``stages.ON`` (a module attribute) and
nothing else. ``profiled()`` turns it on for the calls made inside it and hands back a ``StageProfile``, the
exclusive wall time of each stage (time spent in a nested stage is counted there only, never twice), so that
the stages sum to the time between entering and leaving ``profiled()`` up to the timer's own calls.

The library marks its places with ::

    if stages.ON:
        stages.switch("topology")          # a stage of the outer level (replaces the one running)
    ...
    mark = stages.enter("integration") if stages.ON else None   # a nested stage ...
    try:
        ...
    finally:
        if mark is not None:
            stages.leave(mark)             # ... back to the stage it interrupted, also on an exception

Stages (STAGES, in the order of the path): Python set-up (validation, settings, the closed forms of
spatialkin.tracing.closed.forms, exact curves, the starts' bookkeeping), the topology stage (the interval search that
finds the seeds), per-trace set-up (Python between two integrations: charts, event parameters, the branch's
decisions), integration (solve_ivp and the compiled engine, spatialkin.ode.solvers.integrate), correction (Newton
onto the surfaces: locating a seed on the curve, projecting a segment's start, correcting the stored points,
re-measuring arc length), de-duplication (which starts and pieces lie on a curve already traced) and result
building (assembling the spans, the dense output, the CurveResult and the Curve).
"""
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

#: The stages, in the order a call passes them.
STAGES = ("setup", "topology", "trace_setup", "integration", "correction", "dedupe", "result")
#: Column headings of the bench's profile table (spatialkin.bench.sidebyside).
LABELS = {"setup": "Python set-up", "topology": "topology", "trace_setup": "trace set-up",
          "integration": "integration", "correction": "correction", "dedupe": "dedupe", "result": "result"}
#: The stage a profiled call starts in (and that takes whatever no other stage claims).
ROOT = "setup"

#: True while a profiled() block runs: the library's timed places test it and do nothing else when False.
ON = False
_stack = []
_totals = {}
_last = 0.0


@dataclass
class StageProfile:
    """Exclusive wall time per stage of the calls made inside one profiled() block.

    Attributes
    ----------
    seconds : dict
        Stage name (STAGES) -> seconds spent in it (exclusive of nested stages).
    total : float
        Wall time of the whole block, measured around it (seconds).
    """
    seconds: dict = field(default_factory=lambda: dict.fromkeys(STAGES, 0.0))
    total: float = 0.0

    @property
    def covered(self):
        """Sum of the stages (seconds): the block's time less the timer's own calls outside any stage."""
        return sum(self.seconds.values())

    def shares(self):
        """Stage name -> fraction of the whole block's time."""
        return {k: (v / self.total if self.total > 0 else 0.0) for k, v in self.seconds.items()}

    def scaled(self, factor):
        """A copy with every time multiplied by factor (e.g. 1 / calls for a per-call profile)."""
        return StageProfile({k: v * factor for k, v in self.seconds.items()}, self.total * factor)


def _charge(now):
    """Charge the time since the last mark to the running stage."""
    global _last
    if _stack:
        _totals[_stack[-1]] += now - _last
    _last = now


def switch(name):
    """Make `name` the running stage of the outer level (the nested ones, if an exception skipped their leave,
    are closed)."""
    _charge(time.perf_counter())
    _stack[1:] = []
    _stack[0:1] = [name]


def enter(name):
    """Start the nested stage `name`; returns the mark that ``leave`` returns to."""
    _charge(time.perf_counter())
    _stack.append(name)
    return len(_stack) - 1


def leave(mark):
    """End the stage begun by enter() (and any stage nested in it) and resume the one it interrupted."""
    _charge(time.perf_counter())
    del _stack[mark:]


@contextmanager
def profiled():
    """Time the stages of the intersect calls made inside the block.

    Yields
    ------
    StageProfile
        Filled when the block ends: the exclusive seconds per stage and the block's whole wall time.

    Examples
    --------
    >>> with profiled() as prof:                     # doctest: +SKIP
    ...     sk.intersect(a, b)
    >>> prof.shares()["integration"]                 # doctest: +SKIP
    """
    global ON, _totals, _last
    if ON:
        raise RuntimeError("profiled() blocks do not nest")
    prof = StageProfile()
    _totals = dict.fromkeys(STAGES, 0.0)
    _stack[:] = [ROOT]
    t0 = _last = time.perf_counter()
    ON = True
    try:
        yield prof
    finally:
        ON = False
        now = time.perf_counter()
        _charge(now)
        _stack[:] = []
        prof.seconds = dict(_totals)
        prof.total = now - t0
