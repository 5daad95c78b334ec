"""Sweeps: local processes and a Dask LocalCluster give the same table as an in-process loop; a failed
geometry is a row with its reason; a broken pool of local workers raises, naming the missing main guard; the
README's design example runs as a script."""
import concurrent.futures
import importlib
import os
import re
import subprocess
import sys
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

import numpy as np
import pytest

from spatialkin.design import LooperDesign
from spatialkin.design.sweep import evaluate, grid_space, random_space, sweep

sweep_module = importlib.import_module("spatialkin.design.sweep")     # the package's 'sweep' is the function

README = Path(__file__).resolve().parents[3] / "README.md"

OUTPUTS = ("swing", "min_transmission", "assembly_margin", "u2_max_at", "tip_speed_max")


@pytest.fixture(scope="module")
def space():
    # crank radius 4 with rocker 20: the coupler's circle never reaches the rocker sphere (fails)
    return grid_space(crank_radius=[4.0, 8.0, 9.0], rocker_length=[20.0, 30.0])


@pytest.fixture(scope="module")
def serial(space):
    return sweep(space, OUTPUTS, processes=0, progress=False, as_frame=False)


def test_serial_rows_match_direct_evaluation(space, serial):
    assert serial.dtype.names == ("crank_radius", "rocker_length") + OUTPUTS + ("ok", "reason")
    assert len(serial) == 6
    bad = serial[~serial["ok"]]
    assert len(bad) >= 1 and all("cannot be assembled" in r for r in bad["reason"])
    assert np.all(np.isnan(bad["swing"]))
    row = serial[(serial["crank_radius"] == 8.0) & (serial["rocker_length"] == 30.0)][0]
    direct = evaluate(LooperDesign.reference(), OUTPUTS)
    for name in OUTPUTS:
        assert row[name] == pytest.approx(direct[name], rel=1e-12)
    # the reference drive: swing 37.158 deg (reference page: u2 about 77.8-115 deg), turning point at 0 or 180
    assert np.degrees(row["swing"]) == pytest.approx(37.1575, abs=1e-3)


def test_local_processes_give_the_same_table(space, serial):
    table = sweep(space, OUTPUTS, processes=2, chunk=2, progress=False, as_frame=False)
    assert np.array_equal(table["ok"], serial["ok"])
    for name in OUTPUTS:
        assert np.allclose(table[name], serial[name], rtol=1e-12, equal_nan=True)


def test_dask_local_cluster_gives_the_same_table(space, serial):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        table = sweep(space, OUTPUTS, client=client, chunk=2, progress=False, as_frame=False)
    assert np.array_equal(table["ok"], serial["ok"])
    assert list(table["reason"]) == list(serial["reason"])
    for name in OUTPUTS:
        assert np.allclose(table[name], serial[name], rtol=1e-12, equal_nan=True)


def test_pandas_frame_when_asked(space):
    pandas = pytest.importorskip("pandas")
    frame = sweep({"crank_radius": [8.0]}, ("swing",), processes=0, progress=False, as_frame=True)
    assert isinstance(frame, pandas.DataFrame) and list(frame.columns) == ["crank_radius", "swing", "ok", "reason"]


def test_random_space_lies_within_bounds():
    design = LooperDesign.reference(free=("crank_radius", "rocker_x"))
    space = random_space(design, 50, seed=1)
    for name, values in space.items():
        lo, hi = design.bounds[name]
        assert values.shape == (50,) and np.all((values >= lo) & (values <= hi))


@pytest.mark.parametrize("kwargs, word", [(dict(space={}), "space"), (dict(space={"crank": [1.0]}), "space"),
                                          (dict(outputs=("speed",)), "outputs"), (dict(processes=-1), "processes"),
                                          (dict(samples=2), "samples"),
                                          (dict(outputs=("swing", "swing")), r"outputs: \['swing'\] given twice")])
def test_bad_input_names_the_argument(kwargs, word):
    args = dict(space={"crank_radius": [8.0]}, outputs=("swing",), progress=False)
    args.update(kwargs)
    with pytest.raises(ValueError, match=word):
        sweep(**args)


def test_a_failed_task_becomes_failed_rows():
    """A task that raises (a cluster error, a lost Dask worker) gives rows with the reason instead of ending the
    run."""
    import concurrent.futures

    from spatialkin.design.sweep import _result

    future = concurrent.futures.Future()
    future.set_exception(RuntimeError("the worker died"))
    rows = _result(future, 3, 2)
    assert len(rows) == 3 and all(not ok and "the worker died" in reason for ok, reason, _ in rows)


def test_progress_bar(capsys):
    pytest.importorskip("tqdm")
    sweep({"crank_radius": [8.0, 9.0]}, ("swing",), processes=0, progress=True, as_frame=False)
    assert "2/2" in capsys.readouterr().err


def test_workers_fork_when_the_main_script_is_no_file(monkeypatch):
    """A script piped on stdin (__main__.__file__ = '<stdin>'): a forkserver's workers would fail re-running
    it, so the pool forks this process instead."""
    import sys

    from spatialkin.design.sweep import _context
    monkeypatch.setattr(sys.modules["__main__"], "__file__", "<stdin>", raising=False)
    assert _context().get_start_method() == "fork"


def _die_in_worker(*args):
    """A worker task that ends its own process, as a worker that cannot start or crashes does."""
    os._exit(3)


def test_a_dead_local_worker_raises_naming_the_main_guard(monkeypatch):
    """Oracle: a worker process that dies breaks the pool (BrokenProcessPool); sweep raises RuntimeError with it
    as the cause, naming the main-module guard and processes=0, instead of a table of failed rows."""
    monkeypatch.setattr(sweep_module, "evaluate_chunk", _die_in_worker)
    with pytest.raises(RuntimeError, match=r"if __name__ == \"__main__\":.*processes=0") as info:
        sweep({"crank_radius": [8.0, 9.0]}, ("swing",), processes=1, progress=False, as_frame=False)
    assert isinstance(info.value.__cause__, BrokenProcessPool)


class _BrokenPool:
    """A ProcessPoolExecutor whose every task fails as a broken pool's do."""

    def __init__(self, *args, **kwargs):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def submit(self, fn, *args):
        future = concurrent.futures.Future()
        future.set_exception(BrokenProcessPool("A process in the process pool was terminated abruptly"))
        return future


def test_a_broken_pool_raises_instead_of_failed_rows(monkeypatch):
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", _BrokenPool)
    with pytest.raises(RuntimeError, match="worker process of spatialkin.design.sweep died") as info:
        sweep({"crank_radius": [8.0, 9.0, 10.0]}, ("swing",), processes=2, chunk=1, progress=False)
    assert isinstance(info.value.__cause__, BrokenProcessPool)


def test_a_geometry_that_raises_in_a_worker_is_a_failed_row():
    """Oracle: crank radius 4 with rocker 20 cannot be assembled (its error, raised in the worker, is the row's
    reason); the other geometry of the same task is evaluated as in this process."""
    space = {"crank_radius": [4.0, 8.0], "rocker_length": [20.0, 30.0]}
    table = sweep(space, ("swing",), processes=1, progress=False, as_frame=False)
    assert table["ok"].tolist() == [False, True]
    assert "cannot be assembled" in table["reason"][0] and np.isnan(table["swing"][0])
    assert table["swing"][1] == pytest.approx(evaluate(LooperDesign.reference(), ("swing",))["swing"], rel=1e-12)


def test_the_readme_design_example_runs_as_a_script(tmp_path):
    """The README's design example, saved as a script and run by Python (its sweep on worker processes that
    re-import the script), fits and sweeps without a failed worker."""
    section = README.read_text().split("## Designing a looper drive", 1)[1]
    code = re.search(r"^```python\n(.*?)^```", section, flags=re.S | re.M).group(1)
    script = tmp_path / "design_example.py"
    script.write_text(code)
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "True" in run.stdout and "worker failed" not in run.stdout + run.stderr
