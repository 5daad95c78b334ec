"""tests/spatialkin: the looper drives several test modules share."""
import pytest

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
