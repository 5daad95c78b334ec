"""tests/spatialkin: its oracle modules (oracles.py, ssi_oracle.py, ...) importable from the subfolders too, and
the looper drives several test modules share."""
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

#: A rocker centre at which the reference links block two ranges of crank angles (the crank cannot turn fully).
BLOCKED_ROCKER_CENTRE = (40.0, 0.0, 60.0)


@pytest.fixture
def blocked_drive():
    """The reference links (spatialkin.mechanisms.looper.reference) with the rocker centre at BLOCKED_ROCKER_CENTRE and
    the rocker frame unturned: a looper drive whose crank cannot turn fully; a fresh one per test."""
    import spatialkin as sk
    from spatialkin.mechanisms.looper import reference
    from spatialkin.mechanisms import LooperDrive
    return LooperDrive(reference.CRANK_RADIUS, reference.COUPLER_LENGTH, reference.ROCKER_LENGTH,
                       rocker_frame=sk.Frame(BLOCKED_ROCKER_CENTRE))
