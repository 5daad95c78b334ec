"""The six-link drawn as DXF, read back with ezdxf. Oracles: the solved joint positions, the crank radii, the
exact joint paths (solved on a fine grid)."""
import os

import numpy as np
import pytest

import planar
from planar.linkage import write_dxf

ezdxf = pytest.importorskip("ezdxf")


def test_sixbar_drawing_reads_back(tmp_path):
    mech = planar.examples.fnf_sixbar()
    angles = np.linspace(0, 2 * np.pi, 73)
    sol = mech.solve(angles)
    chord = 1e-3
    write_dxf(tmp_path / "six.dxf", sol, indices=(5,), paths=("K",), chord_tol=chord)
    msp = ezdxf.readfile(tmp_path / "six.dxf").modelspace()
    joints = {j: sol.position(j)[5] for j in mech.joints}
    ends = [np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]]) for e in msp.query("LINE")]
    assert ends
    for seg in ends:                                   # every line joins two joints of position 5
        for end in seg:
            assert min(np.linalg.norm(end - p) for p in joints.values()) < 1e-12
    radii = sorted(round(e.dxf.radius, 12) for e in msp.query("CIRCLE[layer=='CRANK_CIRCLES']"))
    assert radii == sorted(round(c.radius, 12) for c in mech.cranks)
    path = np.array([tuple(v)[:2] for v in list(msp.query("LWPOLYLINE[layer=='PATHS']"))[0].get_points("xy")])
    fine = mech.solve(np.linspace(0, 2 * np.pi, 20001)).position("K")
    a, b = fine[:-1], fine[1:]                           # the exact path as a fine polyline (sagitta ~1e-7)
    d = b - a
    t = np.clip(np.einsum("pij,ij->pi", path[:, None, :] - a[None], d) / np.einsum("ij,ij->i", d, d), 0, 1)
    gap = np.linalg.norm(a[None] + t[..., None] * d[None] - path[:, None, :], axis=2).min(axis=1)
    assert np.max(gap) < 1e-6                           # vertices on the exact path
    assert len(path) > 50
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".tmp-")]
    with pytest.raises(ValueError, match="indices"):
        write_dxf(tmp_path / "bad.dxf", sol, indices=(1000,))
    with pytest.raises(ValueError, match="joint"):
        write_dxf(tmp_path / "bad.dxf", sol, paths=("Z",))
    assert not os.path.exists(tmp_path / "bad.dxf")
