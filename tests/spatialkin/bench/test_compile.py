"""The first-call table (python -m spatialkin.bench.compile) on a cheap entry: both ways run in fresh interpreters
on an empty cache, numba's compile events are recorded (the kernels the entry reaches, each with its own time),
and the default way compiles nothing in the foreground."""
import pytest

from spatialkin._lib import jit as _jit
from spatialkin.bench import compile as compile_table


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no compiling with jit off")
def test_the_table_records_the_compiles_of_an_entry(monkeypatch):
    monkeypatch.setattr(compile_table, "ENTRIES", (("a sphere's distances", "sk.Sphere(1.0).distance(np.ones((3, 3)))"),))
    monkeypatch.setattr(compile_table, "LATER", "sk.Sphere(2.0).distance(np.zeros((1, 3)))")
    lines = []
    costs = compile_table.table(echo=lines.append, every=True)
    assert any(name.endswith("geometry.surfaces.distances") for name in costs)
    assert all(took >= 0 and count >= 1 for took, count, _ in costs.values())
    row = next(line for line in lines if line.startswith("a sphere's distances"))
    compiled_first, _, default_first, _ = (float(x) for x in row.split()[3:7])
    assert compiled_first > 0 and default_first > 0
    assert lines[-1].startswith(f"all {len(costs)} kernels")
    default = compile_table.run_entry(compile_table.ENTRIES[0][1], "interpret")
    assert default["records"] == []                 # plain Python at once: nothing compiled in the foreground
