import os

import pytest

os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
# the suite compiles its kernels in the foreground: no background warm-up process (spatialkin._lib.warm)
os.environ.setdefault("SPATIALKIN_FIRST_RUN", "compile")
# every process the suite starts (scripts, notebook kernels, workers) imports the package under test, this checkout,
# whatever copy is installed: the same code, and the kernels numba has cached for it (a cache is per source path)
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [ROOT, os.environ.get("PYTHONPATH")]))

_REPORT = []

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


def pytest_collection_modifyitems(config, items):
    for item in items:
        if _selected(item.nodeid, SLOW):
            item.add_marker(pytest.mark.slow)
        if _selected(item.nodeid, IMAGES):
            item.add_marker(pytest.mark.images)


@pytest.fixture(scope="session")
def stress_report():
    """Lines a stress test wants in the terminal summary."""
    return _REPORT


def pytest_terminal_summary(terminalreporter):
    if _REPORT:
        terminalreporter.write_sep("-", "stress report")
        for line in _REPORT:
            terminalreporter.write_line(line)
