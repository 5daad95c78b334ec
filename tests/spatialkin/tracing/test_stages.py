"""The opt-in stage timer of sk.intersect (spatialkin._lib.stages): off by default, the same results with it
on, and its stages sum to the whole call. No timing is asserted beyond that sum."""
import time

import numpy as np
import pytest

from spatialkin.mechanisms.looper.reference import looper_pair
from spatialkin._lib import stages
from spatialkin.tracing.components import intersect

#: The stages sum to the call measured around it within this fraction of it (they cover the same interval;
#: the difference is the timer's own calls and entering the block) ...
SUM_FRACTION = 0.05
#: ... plus this absolute slack (seconds) for a pre-empted timer call on a shared machine.
SUM_SLACK = 2e-3
#: Stages every traced loop passes.
TRACED_STAGES = ("topology", "trace_setup", "integration", "correction", "result")


def test_off_by_default_and_same_results():
    """The timer is off outside profiled(); with it on, sk.intersect returns bit-identical curves."""
    pair = looper_pair()
    assert stages.ON is False
    plain = intersect(*pair)
    with stages.profiled():
        assert stages.ON is True
        timed = intersect(*pair)
    assert stages.ON is False
    assert len(plain) == len(timed)
    for c, d in zip(plain, timed):
        np.testing.assert_array_equal(c.points, d.points)
        np.testing.assert_array_equal(c.s, d.s)
        assert c.length == d.length and c.status == d.status


def test_stages_sum_to_the_whole_call():
    """Exclusive stage times: each traced stage is charged, none is negative, and the sum is the whole call
    (measured around it) within SUM_FRACTION."""
    pair = looper_pair()
    intersect(*pair)
    with stages.profiled() as prof:
        t0 = time.perf_counter()
        intersect(*pair)
        whole = time.perf_counter() - t0
    assert set(prof.seconds) == set(stages.STAGES)
    assert all(v >= 0 for v in prof.seconds.values())
    assert all(prof.seconds[s] > 0 for s in TRACED_STAGES)
    assert abs(prof.covered - whole) <= SUM_FRACTION * whole + SUM_SLACK
    assert prof.covered <= prof.total * (1 + 1e-12)
    assert abs(sum(prof.shares().values()) - prof.covered / prof.total) < 1e-12


def test_block_restores_the_timer_on_an_exception():
    """An exception inside a nested stage and inside the block leaves the timer off and its stack empty; blocks
    do not nest."""
    with pytest.raises(KeyError):
        with stages.profiled() as prof:
            stages.enter("integration")
            raise KeyError("boom")
    assert stages.ON is False and stages._stack == []
    assert prof.seconds["integration"] >= 0 and prof.total > 0
    with stages.profiled():
        with pytest.raises(RuntimeError):
            with stages.profiled():
                pass
    assert stages.ON is False


def test_switch_closes_nested_stages():
    """A stage of the outer level closes the nested ones an exception left open (the intersect loop's repair)."""
    with stages.profiled():
        stages.enter("integration")
        stages.enter("correction")
        stages.switch("dedupe")
        assert stages._stack == ["dedupe"]
        mark = stages.enter("result")
        stages.leave(mark)
        assert stages._stack == ["dedupe"]
