import os

import pytest

os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
# the suite compiles its kernels in the foreground: no background warm-up process (spatialkin.firstrun)
os.environ.setdefault("SPATIALKIN_FIRST_RUN", "compile")

_REPORT = []


@pytest.fixture(scope="session")
def stress_report():
    """Lines a stress test wants in the terminal summary."""
    return _REPORT


def pytest_terminal_summary(terminalreporter):
    if _REPORT:
        terminalreporter.write_sep("-", "stress report")
        for line in _REPORT:
            terminalreporter.write_line(line)
