"""Exports read back: CSV, VTK polydata, DXF splines, STEP B-spline edges; looper paths as B-splines.
Oracles: the surfaces' exact distance functions, the curve's own dense evaluation, the B-spline written."""
import math
import os

import numpy as np
import pytest

import spatialkin as sk
from spatialkin.mechanisms.looper import reference
from spatialkin.export import dense_polyline, export_curves, write_csv, write_dxf, write_step, write_vtp
from spatialkin.mechanisms import LooperDrive


@pytest.fixture(scope="module")
def looper_pair():
    torus, sphere = reference.looper_pair()
    return torus, sphere, sk.intersect(torus, sphere)


def no_temporaries(folder):
    return not [f for f in os.listdir(folder) if f.startswith(".tmp-")]


def test_dense_polyline_meets_the_chord_height():
    """A circle of radius 2 at chord height 1e-6: every chord midpoint within 1e-6 of the circle point at the
    mid-parameter, and about pi / sqrt(2 h / r) points (no more than twice that)."""
    def circle(t):
        return np.stack([2 * np.cos(t), 2 * np.sin(t), 0 * t], 1)
    x, pts = dense_polyline(circle, 0.0, 2 * math.pi, 1e-6)
    mid = circle(0.5 * (x[1:] + x[:-1]))
    assert np.max(np.linalg.norm(mid - 0.5 * (pts[1:] + pts[:-1]), axis=1)) <= 1e-6
    assert len(x) <= 2 * math.pi / math.sqrt(8e-6 / 2.0) * 2


def test_csv_and_vtp_read_back(tmp_path, looper_pair):
    """CSV: a header with units, rows (curve, s, x, y, z) on both surfaces to 1e-12; VTP: float64 points, one
    line cell per curve, closed lines ending on their first point, s and curve arrays."""
    pyvista = pytest.importorskip("pyvista")
    torus, sphere, curves = looper_pair
    write_csv(tmp_path / "c.csv", curves, unit="mm")
    with open(tmp_path / "c.csv") as fh:
        assert fh.readline().strip() == "curve,s [mm],x [mm],y [mm],z [mm]"
    rows = np.loadtxt(tmp_path / "c.csv", delimiter=",", skiprows=1)
    assert set(rows[:, 0]) == {0.0, 1.0}
    assert max(torus.distance(rows[:, 2:]).max(), sphere.distance(rows[:, 2:]).max()) < 1e-12
    for k, c in enumerate(curves):
        s = rows[rows[:, 0] == k, 1]
        np.testing.assert_allclose(c(s), rows[rows[:, 0] == k, 2:], atol=1e-12)
    write_vtp(tmp_path / "c.vtp", curves)
    back = pyvista.read(tmp_path / "c.vtp")
    assert back.points.dtype == np.float64 and back.n_lines == 2 and back.n_points == len(rows)
    np.testing.assert_array_equal(np.asarray(back.points), rows[:, 2:])
    np.testing.assert_array_equal(np.asarray(back.point_data["s"]), rows[:, 1])
    lines = back.lines
    first = lines[1:1 + lines[0]]
    assert first[0] == first[-1]                           # closed: the line ends on its first point
    assert no_temporaries(tmp_path)


def test_dxf_splines_read_back(tmp_path, looper_pair):
    """One SPLINE per curve with the B-spline's degree, knots and control points; ezdxf's own evaluation of it
    lies within 1e-9 x scale of the curve (Curve.closest)."""
    ezdxf = pytest.importorskip("ezdxf")
    _, _, curves = looper_pair
    write_dxf(tmp_path / "c.dxf", curves, tol=1e-9)
    entities = list(ezdxf.readfile(tmp_path / "c.dxf").modelspace().query("SPLINE"))
    assert len(entities) == 2
    for entity, curve in zip(entities, curves):
        sp = curve.to_bspline(1e-9)
        assert entity.dxf.degree == 5 and len(entity.control_points) == len(sp.c)
        np.testing.assert_allclose(np.asarray(entity.knots), sp.t, rtol=0, atol=0)
        tool = entity.construction_tool()
        u = np.linspace(sp.t[5], sp.t[-6], 200)
        pts = np.array([tuple(tool.point(x)) for x in u])
        assert np.max(curve.closest(pts)[1]) <= 1e-9 * 30.0
    assert no_temporaries(tmp_path)


def test_step_read_back(tmp_path, looper_pair):
    """STEP through OpenCascade: one edge per curve, read back and sampled by BRepAdaptor, within 1e-9 x scale
    of the curve."""
    pytest.importorskip("OCP")
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    _, _, curves = looper_pair
    write_step(tmp_path / "c.step", curves, tol=1e-9)
    reader = STEPControl_Reader()
    reader.ReadFile(str(tmp_path / "c.step"))
    reader.TransferRoots()
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_EDGE)
    edges = []
    while explorer.More():
        edges.append(BRepAdaptor_Curve(TopoDS.Edge(explorer.Current()) if hasattr(TopoDS, "Edge")
                                       else TopoDS.Edge_s(explorer.Current())))
        explorer.Next()
    assert len(edges) == 2
    for adaptor in edges:
        u = np.linspace(adaptor.FirstParameter(), adaptor.LastParameter(), 200)
        pts = np.array([[p.X(), p.Y(), p.Z()] for p in (adaptor.Value(x) for x in u)])
        assert min(np.max(c.closest(pts)[1]) for c in curves) <= 1e-9 * 30.0
    assert no_temporaries(tmp_path)


def test_export_by_suffix_and_errors(tmp_path, looper_pair):
    _, _, curves = looper_pair
    export_curves(tmp_path / "a.csv", curves[0])
    with pytest.raises(ValueError, match="suffix|end in"):
        export_curves(tmp_path / "a.obj", curves)
    with pytest.raises(TypeError, match="curves"):
        export_curves(tmp_path / "a.csv", [np.zeros(3)])
    with pytest.raises(ValueError, match="chord_tol"):
        write_csv(tmp_path / "b.csv", curves, chord_tol=-1.0)
    with pytest.raises(TypeError, match="chord_tol must be a real number"):
        write_csv(tmp_path / "b.csv", curves, chord_tol="1e-3")
    with pytest.raises(TypeError, match="curves must be a Curve, a scipy BSpline or a list of them"):
        export_curves(tmp_path / "b.csv", None)
    with pytest.raises(ValueError, match="unit must be one of"):
        write_csv(tmp_path / "b.csv", curves, unit="a,b\nc")
    with pytest.raises(ValueError, match="unit must be one of 'mm', 'cm', 'm', 'in', None"):
        write_dxf(tmp_path / "b.dxf", curves, unit="furlong")
    with pytest.raises(TypeError, match="tol must be a real number"):
        curves[0].to_bspline("1e-3")
    assert not os.path.exists(tmp_path / "b.csv") and no_temporaries(tmp_path)


@pytest.mark.parametrize("unit, code", [("mm", 4), ("cm", 5), ("m", 6), ("in", 1), (None, 0)])
def test_files_declare_the_unit_given(tmp_path, looper_pair, unit, code):
    """The DXF header's $INSUNITS is the DXF code of the unit given (AutoCAD's table: 4 mm, 5 cm, 6 m, 1 inch, 0
    unitless), $MEASUREMENT metric but for inches; the CSV's columns name it; the coordinates are not scaled."""
    ezdxf = pytest.importorskip("ezdxf")
    _, _, curves = looper_pair
    write_dxf(tmp_path / "c.dxf", curves, unit=unit)
    doc = ezdxf.readfile(tmp_path / "c.dxf")
    assert doc.header["$INSUNITS"] == code and doc.header["$MEASUREMENT"] == (0 if unit == "in" else 1)
    control = np.asarray(doc.modelspace().query("SPLINE")[0].control_points)
    np.testing.assert_array_equal(control, np.asarray(curves[0].to_bspline(1e-8).c))
    write_csv(tmp_path / "c.csv", curves, unit=unit)
    with open(tmp_path / "c.csv") as fh:
        label = "" if unit is None else f" [{unit}]"
        assert fh.readline().strip() == f"curve,s{label},x{label},y{label},z{label}"


@pytest.mark.parametrize("unit, metres", [("mm", 1e-3), ("m", 1.0), ("in", 0.0254)])
def test_step_declares_the_unit_given(tmp_path, looper_pair, unit, metres):
    """The STEP file states the unit given, its coordinates unscaled: OpenCascade's reader, set to read in mm,
    gives the curve's points times the unit's millimetres (1, 1000, 25.4) within 1e-9 x scale; the writer's
    process-wide unit settings are as they were after."""
    pytest.importorskip("OCP")
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_Controller, STEPControl_Reader
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    _, _, curves = looper_pair
    STEPControl_Controller.Init_s()                     # (the settings exist once the STEP controller is made)
    before = Interface_Static.CVal_s("write.step.unit"), Interface_Static.CVal_s("xstep.cascade.unit")
    write_step(tmp_path / "c.step", curves[:1], tol=1e-9, unit=unit)
    assert (Interface_Static.CVal_s("write.step.unit"), Interface_Static.CVal_s("xstep.cascade.unit")) == before
    with open(tmp_path / "c.step") as fh:
        text = fh.read()
    assert {"mm": "SI_UNIT(.MILLI.,.METRE.)", "m": "SI_UNIT($,.METRE.)", "in": "'INCH'"}[unit] in text
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    try:
        reader = STEPControl_Reader()
        reader.ReadFile(str(tmp_path / "c.step"))
        reader.TransferRoots()
    finally:
        Interface_Static.SetCVal_s("xstep.cascade.unit", before[1])
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_EDGE)
    edge = TopoDS.Edge(explorer.Current()) if hasattr(TopoDS, "Edge") else TopoDS.Edge_s(explorer.Current())
    adaptor = BRepAdaptor_Curve(edge)
    u = np.linspace(adaptor.FirstParameter(), adaptor.LastParameter(), 50)
    pts = np.array([[p.X(), p.Y(), p.Z()] for p in (adaptor.Value(x) for x in u)]) * (1e-3 / metres)
    assert np.max(curves[0].closest(pts)[1]) <= 1e-9 * 30.0


@pytest.mark.parametrize("suffix", ["csv", "vtp", "dxf"])
def test_splines_that_are_no_curves_of_points_are_named(tmp_path, suffix):
    """A B-spline with a NaN control point, or values that are no 3-D points (scalar, 2-D), is refused naming its
    index in the list, and no file is written (a NaN spline was written as 'nan' rows)."""
    from scipy.interpolate import BSpline
    knots = np.r_[[0.0] * 4, [1.0] * 4]
    good = BSpline(knots, np.arange(12.0).reshape(4, 3), 3)
    nan = np.arange(12.0).reshape(4, 3)
    nan[1, 1] = np.nan
    for bad, words in ((BSpline(knots, nan, 3), "curves\\[1\\] must have finite control points"),
                       (BSpline(knots, np.zeros(4), 3), r"curves\[1\] must be a B-spline of points"),
                       (BSpline(knots, np.zeros((4, 2)), 3), r"curves\[1\] must be a B-spline of points")):
        with pytest.raises(ValueError, match=words):
            export_curves(tmp_path / f"c.{suffix}", [good, bad])
    assert not os.path.exists(tmp_path / f"c.{suffix}") and no_temporaries(tmp_path)


def test_looper_paths_as_bsplines():
    """Ball centre and looper tip of the reference drive over a full turn: periodic splines within 1e-9 x
    scale of the exact path (distance of spline samples to a dense exact polyline, refined by one Newton step
    in the crank angle), and the spline at the knots equals the solved positions (Hermite data)."""
    drive = LooperDrive.reference()
    theta = np.linspace(0, 2 * np.pi, 721)
    motion = drive.solve(theta)
    scale = min(drive.torus.size, drive.sphere.size)
    for which in ("ball", "tip"):
        sp = motion.path_bspline(which, 1e-9)
        assert sp.extrapolate == "periodic" and sp.deviation <= 1e-9 * scale
        knots = np.unique(sp.t)
        exact = drive.solve(knots)
        ref = exact.ball_center if which == "ball" else exact.looper_tip.position
        np.testing.assert_allclose(sp(knots), ref, atol=1e-12 * scale)
        u = np.linspace(0, 2 * np.pi, 3001)
        at = drive.solve(u)
        pos = at.ball_center if which == "ball" else at.looper_tip.position
        vel = at.ball_velocity if which == "ball" else at.looper_tip.velocity
        approx = sp(u)
        u_foot = u + np.einsum("ij,ij->i", approx - pos, vel) / np.einsum("ij,ij->i", vel, vel)
        foot = drive.solve(np.mod(u_foot, 2 * np.pi))
        foot = foot.ball_center if which == "ball" else foot.looper_tip.position
        assert np.max(np.linalg.norm(approx - foot, axis=1)) <= 1e-9 * scale
    with pytest.raises(ValueError, match="which"):
        motion.path_bspline("crank")


def test_step_without_opencascade_names_the_extra(tmp_path, looper_pair, monkeypatch):
    """With OpenCascade missing, write_step raises ImportError naming the cad extra and writes nothing."""
    import sys
    monkeypatch.setitem(sys.modules, "OCP", None)
    with pytest.raises(ImportError, match=r"spatialkin\[cad\]"):
        write_step(tmp_path / "c.step", looper_pair[2])
    assert not os.listdir(tmp_path)
