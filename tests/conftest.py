import os
import shutil
import tempfile
import time

import pytest

os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
# the suite compiles its kernels in the foreground: no background warm-up process (spatialkin._lib.warm)
os.environ.setdefault("SPATIALKIN_FIRST_RUN", "compile")
# every process the suite starts (scripts, notebook kernels, workers) imports the package under test, this checkout,
# whatever copy is installed: the same code, and the kernels numba has cached for it (a cache is per source path)
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [ROOT, os.environ.get("PYTHONPATH")]))

_REPORT = []
#: What the session's warm-up took, said after the tests.
_WARMED = []
#: The folder of the session's warm-up record (tests/suite_warmup.py), removed at the end.
_WARMUP_FOLDER = []

#: Tests that take long or start processes, marked ``slow`` (deselect with ``-m "not slow"``): the stress suites,
#: the notebooks, worker pools and whole-command runs. A path selects a module or folder, a ``::`` id one test.
SLOW = (
    "tests/spatialkin/tracing/test_stress.py",
    "tests/spatialkin/tracing/search/test_topology_stress.py",
    "tests/spatialkin/tracing/test_survey.py",
    "tests/notebooks/test_notebooks.py::test_notebook_runs",
    "tests/spatialkin/continuation/test_continuation.py::test_locks_of_an_ellipse_match_the_closed_form_and_solve_ivp",
    "tests/spatialkin/continuation/test_continuation.py::test_full_turn_closes_after_one_period",
    "tests/spatialkin/tracing/test_batch.py::test_workers_give_the_same_curves_in_order",
    "tests/spatialkin/tracing/test_batch.py::test_a_failing_pair_on_workers_is_named_or_returned_in_place",
    "tests/spatialkin/tracing/test_batch.py::test_a_dead_worker_is_named_and_the_next_batch_gets_a_new_pool",
    "tests/spatialkin/tracing/test_batch.py::test_a_script_with_workers",
    "tests/spatialkin/design/test_design_sweep.py::test_local_processes_give_the_same_table",
    "tests/spatialkin/design/test_design_sweep.py::test_dask_local_cluster_gives_the_same_table",
    "tests/spatialkin/design/test_design_sweep.py::test_workers_fork_when_the_main_script_is_no_file",
    "tests/spatialkin/_lib/test_warm.py::test_a_cold_cache_runs_plain_python_at_once_and_warms_in_the_background",
    "tests/spatialkin/_lib/test_warm.py::test_the_looper_job_on_a_cold_cache_says_so_once_and_gives_the_compiled_table",
    "tests/spatialkin/_lib/test_warm.py::test_after_spatialkin_warmup_the_stress_cases_compile_nothing",
    "tests/spatialkin/bench/test_compile.py",
    "tests/spatialkin/bench/test_bench.py::test_bench_quick_command",
)
#: Tests that compare rendered pictures with stored baselines, marked ``images``.
IMAGES = (
    "tests/spatialkin/render/test_images.py",
    "tests/planar/frenet/test_frenet.py::test_image_",
)


def _selected(nodeid, table):
    path, _, name = nodeid.partition("::")
    for entry in table:
        where, _, test = entry.partition("::")
        if (path == where or (where.endswith("/") and path.startswith(where))) and name.startswith(test):
            return True
    return False


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session):
    """On a cold numba cache (spatialkin's or planar's workload not stamped warm), `spatialkin warmup` once, each
    workload in a fresh process of its own, before any test and any test runner's worker starts: they all load the
    kernels from the cache it leaves. Not in a worker, for --collect-only, with jit off, or when the session's
    warm-up ran already."""
    from tests import suite_warmup
    config = session.config
    if hasattr(config, "workerinput") or config.option.collectonly or os.environ.get(suite_warmup.RECORD_ENV):
        return
    from spatialkin._lib import jit, warm
    if jit.JIT_DISABLED or all(warm.ready(workload) for workload in warm.workloads()):
        return
    reporter = config.pluginmanager.get_plugin("terminalreporter")
    if reporter is not None:
        reporter.write_line("numba's cache is cold: `spatialkin warmup` first, a process per workload")
    _WARMUP_FOLDER.append(tempfile.mkdtemp(prefix="spatialkin-suite-"))
    t0 = time.perf_counter()
    data = suite_warmup.record(os.path.join(_WARMUP_FOLDER[0], "warmup.json"))
    _WARMED.append(f"spatialkin warmup before the tests took {time.perf_counter() - t0:.0f} s (not in the time "
                   "pytest gives below)")
    if reporter is not None:
        reporter.write_line(data["report"])
        if not data["complete"]:            # (the warm-up coverage test then makes a record of its own)
            reporter.write_line(f"the warm-up holds {len(data['uncompiled'])} specialisations none of its processes "
                                f"compiled (first: {data['uncompiled'][0]})")


def pytest_unconfigure(config):
    for folder in _WARMUP_FOLDER:
        shutil.rmtree(folder, ignore_errors=True)


def pytest_collection_modifyitems(config, items):
    for item in items:
        if _selected(item.nodeid, SLOW):
            item.add_marker(pytest.mark.slow)
        if _selected(item.nodeid, IMAGES):
            item.add_marker(pytest.mark.images)


@pytest.fixture
def stress_report(request):
    """Lines a stress test wants in the terminal summary (a list to extend): passed on with its teardown report,
    which reaches the main process from a test runner's worker too."""
    lines = []
    yield lines
    request.node.user_properties.extend(("stress report", line) for line in lines)


def pytest_runtest_logreport(report):
    if report.when == "teardown":
        _REPORT.extend(line for name, line in report.user_properties if name == "stress report")


def pytest_terminal_summary(terminalreporter):
    for line in _WARMED:
        terminalreporter.write_line(line)
    if _REPORT:
        terminalreporter.write_sep("-", "stress report")
        for line in _REPORT:
            terminalreporter.write_line(line)
