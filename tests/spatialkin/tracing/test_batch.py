"""sk.intersect_many: the same curves as sk.intersect pair by pair (in this process and on workers), arguments
checked before any work, failures named by index."""
import numpy as np
import pytest

import spatialkin as sk
from spatialkin.tracing import batch


def mixed_pairs():
    """A few kinds, both argument orders."""
    from spatialkin.bench.kinds import pair_kind_cases
    cases = pair_kind_cases()
    return [(a, b) for _, a, b in cases[::4]] + [(b, a) for _, a, b in cases[1::5]]


def same_curves(got, want):
    """The oracle: sk.intersect's curves, bit for bit (points, arc lengths, statuses)."""
    assert len(got) == len(want)
    for g, w in zip(got, want):
        assert g.status == w.status and g.closed == w.closed
        assert np.array_equal(g.points, w.points) and np.array_equal(g.s, w.s)
        assert g.length == w.length


def test_intersect_many_equals_intersect_pair_by_pair():
    pairs = mixed_pairs()
    results = sk.intersect_many(pairs, tol=1e-10)
    assert len(results) == len(pairs)
    for (a, b), got in zip(pairs, results):
        same_curves(got, sk.intersect(a, b, tol=1e-10))


def test_workers_give_the_same_curves_in_order():
    from spatialkin.mechanisms.looper.reference import looper_pair
    torus, sphere = looper_pair()
    radii = sphere.radius * np.linspace(0.98, 1.02, 2 * batch.MIN_CHUNKS_PER_WORKER * batch.CHUNK)
    pairs = [(torus, sk.Sphere(r, sphere.frame)) for r in radii]
    results = sk.intersect_many(pairs, workers=2)
    assert len(results) == len(pairs)
    for (a, b), got in zip(pairs, results):
        same_curves(got, sk.intersect(a, b))


def test_empty_batch():
    assert sk.intersect_many([]) == []


@pytest.mark.parametrize("pairs, kind, words", [
    (5, TypeError, "pairs must be an iterable"),
    ([("x",)], ValueError, "pairs[0] must be a pair"),
    ([None], ValueError, "pairs[0] must be a pair"),
])
def test_bad_pairs_named(pairs, kind, words):
    with pytest.raises(kind, match=words.replace("[", r"\[").replace("]", r"\]")):
        sk.intersect_many(pairs)


def test_bad_surface_and_options_named_before_any_work(monkeypatch):
    good = mixed_pairs()[0]
    calls = []
    monkeypatch.setattr(batch, "intersect", lambda *a, **k: calls.append(a))
    with pytest.raises(TypeError, match=r"pairs\[1\]\[1\] must be a spatialkin surface"):
        sk.intersect_many([good, (good[0], "plane")])
    with pytest.raises(ValueError, match="tol must be a positive"):
        sk.intersect_many([good, good], tol=-1.0)
    with pytest.raises(ValueError, match="workers"):
        sk.intersect_many([good], workers=0)
    with pytest.raises(ValueError, match="errors"):
        sk.intersect_many([good], errors="ignore")
    with pytest.raises(ValueError, match="method"):
        sk.intersect_many([good], method="Euler")
    for option in ("rtol", "atol", "max_length", "singular_tol", "pullback"):
        with pytest.raises(ValueError, match=option):
            sk.intersect_many([good], **{option: -1.0})
    assert calls == []


def test_a_failing_pair_is_named_or_returned_in_place():
    sphere = sk.Sphere(1.0)
    other = sk.Sphere(1.0, sk.Frame((0.5, 0.0, 0.0)))
    pairs = [(sphere, other), (sphere, sphere), (other, sphere)]
    with pytest.raises(sk.BatchError, match=r"pairs\[1\]: CoincidentSurfacesError") as err:
        sk.intersect_many(pairs)
    assert err.value.index == 1 and isinstance(err.value.__cause__, sk.CoincidentSurfacesError)
    results = sk.intersect_many(pairs, errors="return")
    assert isinstance(results[1], sk.CoincidentSurfacesError)
    same_curves(results[0], sk.intersect(sphere, other))
    same_curves(results[2], sk.intersect(other, sphere))


def looper_sweep(count):
    """count looper pairs (sphere radius within 2%)."""
    from spatialkin.mechanisms.looper.reference import looper_pair
    torus, sphere = looper_pair()
    return [(torus, sk.Sphere(r, sphere.frame)) for r in sphere.radius * np.linspace(0.98, 1.02, count)]


def test_a_failing_pair_on_workers_is_named_or_returned_in_place():
    pairs = looper_sweep(2 * batch.MIN_CHUNKS_PER_WORKER * batch.CHUNK)
    bad = 2 * batch.CHUNK + 3                  # in the third chunk
    pairs[bad] = (pairs[bad][1], pairs[bad][1])
    with pytest.raises(sk.BatchError, match=rf"pairs\[{bad}\]: CoincidentSurfacesError") as err:
        sk.intersect_many(pairs, workers=2)
    assert err.value.index == bad and isinstance(err.value.__cause__, sk.CoincidentSurfacesError)
    results = sk.intersect_many(pairs, workers=2, errors="return")
    assert isinstance(results[bad], sk.CoincidentSurfacesError)
    assert "Traceback" in "".join(getattr(results[bad], "__notes__", []))        # the worker's traceback
    same_curves(results[bad + 1], sk.intersect(*pairs[bad + 1]))


#: How long the test waits for the pool's manager thread to notice a killed worker (s): it wakes on the worker's
#: exit at once; the bound only keeps a broken interpreter from hanging the suite.
NOTICE_TIMEOUT = 120.0


def test_a_dead_worker_is_named_and_the_next_batch_gets_a_new_pool():
    """A worker killed between two batches: the next batch raises RuntimeError naming the death, and the one after
    runs on a new pool. The test waits until the pool has noticed the death (its manager thread marks it broken)
    before the next batch, so that batch cannot run on the surviving worker first (a race, not a failure)."""
    import os
    import signal
    import time
    pairs = looper_sweep(2 * batch.MIN_CHUNKS_PER_WORKER * batch.CHUNK)
    sk.intersect_many(pairs, workers=2)                      # the kept pool exists
    pool = batch._POOL["executor"]
    victim = next(iter(pool._processes.values()))
    os.kill(victim.pid, signal.SIGKILL)                      # a worker dies (the OOM killer, a crash)
    victim.join(NOTICE_TIMEOUT)
    deadline = time.monotonic() + NOTICE_TIMEOUT
    while not pool._broken and time.monotonic() < deadline:
        time.sleep(0.01)
    assert pool._broken, f"the pool did not notice its killed worker within {NOTICE_TIMEOUT} s"
    with pytest.raises(RuntimeError, match=r"a worker process of sk.intersect_many died"):
        sk.intersect_many(pairs, workers=2)
    assert "executor" not in batch._POOL
    results = sk.intersect_many(pairs, workers=2)
    assert batch._POOL["executor"] is not pool
    for pair, got in zip(pairs[:3], results):
        same_curves(got, sk.intersect(*pair))


def test_batch_error_survives_pickling():
    import pickle
    error = pickle.loads(pickle.dumps(sk.BatchError(4, ValueError("bad radius"))))
    assert error.index == 4 and str(error) == "pairs[4]: ValueError: bad radius"
    assert isinstance(error.error, ValueError)


SCRIPT = """
import spatialkin as sk
from spatialkin.mechanisms.looper.reference import looper_pair
torus, sphere = looper_pair()
pairs = [(torus, sk.Sphere(sphere.radius * (1 + 0.01 * k / 32), sphere.frame)) for k in range(32)]
{guard}    print(len(sk.intersect_many(pairs, workers=2)), "results")
"""


@pytest.mark.parametrize("guarded", [True, False])
def test_a_script_with_workers(tmp_path, guarded):
    """A script on workers: under ``if __name__ == "__main__":`` it runs; without it (its workers re-import it) the
    batch fails naming the remedy, and nothing hangs."""
    import subprocess
    import sys
    path = tmp_path / "sweep.py"
    path.write_text(SCRIPT.format(guard='if __name__ == "__main__":\n' if guarded else "if True:\n"))
    run = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, timeout=300)
    if guarded:
        assert run.returncode == 0 and "32 results" in run.stdout, run.stderr[-2000:]
    else:
        assert run.returncode != 0 and "if __name__ == " in run.stderr and "worker process" in run.stderr
