"""The design bench runs and its numbers say what they should: central differences at a good step agree with
the exact sensitivities to 1e-7 (relative), and a sweep's rate is positive on every worker count."""
import numpy as np

from spatialkin.design import LooperDesign
from spatialkin.design.bench import FIELDS, sensitivity_rows, sweep_rows


def test_sensitivity_rows_against_central_differences():
    design = LooperDesign.reference().replace(rocker_y=2.0, rocker_rz=0.05)
    rows = sensitivity_rows(design, np.linspace(0, 2 * np.pi, 73), repeats=1)
    assert rows[0][2] is None and rows[0][1] > 0
    best = {f: min(r[2][f] for r in rows[1:]) for f in FIELDS}
    assert max(best.values()) < 1e-7


def test_sweep_rows(capsys):
    rows = sweep_rows(LooperDesign.reference(), 6, process_counts=(1,))
    assert [r[0] for r in rows] == ["in this process", "1 process"]
    assert all(r[1] == 6 and r[3] > 0 for r in rows)
    assert rows[0][4] == rows[1][4]          # the same geometries fail either way
