"""Curves into files engineers open: dense polylines (CSV, VTK polydata), B-splines (DXF, STEP).

Every file is written whole or not at all (spatialkin._lib.files.atomic_path). A curve is an intersection Curve, or a
B-spline (scipy.interpolate.BSpline, e.g. ``curve.to_bspline(tol)`` or a mechanism trajectory's
``to_bspline``); a polyline is spaced by a chord-height tolerance (never the solver's steps), a B-spline is
written with its own knots and control points (degree 5).

DXF needs ezdxf (a dependency); STEP needs OpenCascade (cadquery-ocp), the ``cad`` extra. The helpers
``dense_polyline``, ``dxf_document``, ``require`` and ``atomic_path`` are public for other exporters (planar's DXF
drawings).
"""
import contextlib
import os
from xml.sax.saxutils import escape

import numpy as np
from scipy.interpolate import BSpline

from ._lib.files import atomic_path
from ._lib.validation import check_positive

__all__ = ["atomic_path", "dense_polyline", "dxf_document", "export_curves", "polylines", "require", "splines",
           "write_csv", "write_dxf", "write_step", "write_vtp"]

#: The extra that provides ezdxf and OpenCascade.
CAD_EXTRA = "spatialkin[cad]"
#: Default chord height of polylines, relative to the curve's extent (its bounding-box diagonal).
CHORD_FRACTION = 1e-6
#: Default B-spline tolerance for DXF and STEP, relative to the scene scale (Curve.to_bspline).
SPLINE_TOL = 1e-8
#: Most points of one polyline.
MAX_POLYLINE = 2_000_000
#: Length units a file can declare: DXF's $INSUNITS code and OpenCascade's STEP unit name (None: no unit, which
#: STEP cannot state). The coordinates are written as they are: the unit says what they are in.
UNITS = {"mm": (4, "MM"), "cm": (5, "CM"), "m": (6, "M"), "in": (1, "INCH"), None: (0, None)}


def _as_pieces(curves):
    """[(evaluate(x) -> (M, 3), x0, x1, closed, source)] for Curves and BSplines (a single one is allowed)."""
    from .tracing.curve.result import Curve
    if isinstance(curves, (Curve, BSpline)):
        curves = [curves]
    if isinstance(curves, (str, bytes)) or not hasattr(curves, "__iter__"):
        raise TypeError(f"curves must be a Curve, a scipy BSpline or a list of them, got {type(curves).__name__}")
    pieces = []
    for k, c in enumerate(curves):
        if isinstance(c, Curve):
            pieces.append((c, 0.0, c.length, c.closed, c))
        elif isinstance(c, BSpline):
            coefficients = np.asarray(c.c)
            if coefficients.ndim != 2 or coefficients.shape[1] != 3:
                raise ValueError(f"curves[{k}] must be a B-spline of points (its control points of shape (n, 3)), "
                                 f"got control points of shape {coefficients.shape}")
            if not (np.all(np.isfinite(coefficients)) and np.all(np.isfinite(c.t))):
                raise ValueError(f"curves[{k}] must have finite control points and knots")
            t, k_ = c.t, c.k
            pieces.append((c, float(t[k_]), float(t[-k_ - 1]), c.extrapolate == "periodic", c))
        else:
            raise TypeError(f"curves[{k}] must be a spatialkin Curve or a scipy BSpline, got {type(c).__name__}")
    return pieces


def dense_polyline(evaluate, x0, x1, chord_tol):
    """(x (M,), points (M, 3)) of a curve on [x0, x1] such that every chord's midpoint lies within chord_tol of
    the curve's point at the mid-parameter (spans halved until it does)."""
    if x1 <= x0:
        p = np.asarray(evaluate(np.array([x0])), dtype=float).reshape(-1, 3)
        return np.array([x0]), p
    x = np.linspace(x0, x1, 17)
    pts = np.asarray(evaluate(x), dtype=float).reshape(-1, 3)
    while True:
        mid = 0.5 * (x[:-1] + x[1:])
        at = np.asarray(evaluate(mid), dtype=float).reshape(-1, 3)
        bad = np.linalg.norm(at - 0.5 * (pts[:-1] + pts[1:]), axis=1) > chord_tol
        if not bad.any():
            return x, pts
        if len(x) + bad.sum() > MAX_POLYLINE:
            raise ValueError(f"a polyline within chord height {chord_tol:.3g} needs more than {MAX_POLYLINE} "
                             "points: give a larger chord_tol")
        order = np.argsort(np.r_[x, mid[bad]], kind="stable")
        x = np.r_[x, mid[bad]][order]
        pts = np.vstack([pts, at[bad]])[order]


def _chord_tol(pts, chord_tol):
    if chord_tol is None:
        extent = float(np.linalg.norm(np.ptp(pts, axis=0))) if len(pts) else 1.0
        return CHORD_FRACTION * max(extent, 1e-300)
    return check_positive("chord_tol", chord_tol, strict=True)


def polylines(curves, chord_tol=None):
    """[(x (M,), points (M, 3), closed)] of every curve, spaced by the chord height (default CHORD_FRACTION of
    each curve's extent)."""
    out = []
    for evaluate, x0, x1, closed, _ in _as_pieces(curves):
        rough = np.asarray(evaluate(np.linspace(x0, x1, 33)), dtype=float).reshape(-1, 3)
        out.append((*dense_polyline(evaluate, x0, x1, _chord_tol(rough, chord_tol)), closed))
    return out


def check_unit(unit, what="a DXF or CSV file", unitless=True):
    """The unit (a key of UNITS; None only where the file may be unitless), or ValueError naming the argument and
    the units allowed."""
    allowed = [u for u in UNITS if u is not None or unitless]
    if unit not in allowed:
        raise ValueError(f"unit must be one of {', '.join(map(repr, allowed))} (the length unit {what} declares; its "
                         f"coordinates are written as they are), got {unit!r}")
    return unit


def write_csv(path, curves, unit="mm", chord_tol=None):
    """Points of every curve as CSV: curve index, parameter (arc length s for a Curve), x, y, z; the header names
    the unit of each column (a key of UNITS; None: no unit)."""
    check_unit(unit)
    rows = polylines(curves, chord_tol)
    label = "" if unit is None else f" [{unit}]"
    with atomic_path(path) as tmp, open(tmp, "w") as fh:
        fh.write(f"curve,s{label},x{label},y{label},z{label}\n")
        for k, (x, pts, _) in enumerate(rows):
            block = np.column_stack([np.full(len(x), k), x, pts])
            np.savetxt(fh, block, delimiter=",", fmt=["%d", "%.17g", "%.17g", "%.17g", "%.17g"])
    return path


def write_vtp(path, curves, chord_tol=None):
    """VTK XML polydata (.vtp): one line cell per curve (closed ones end on their first point), float64 points,
    point data 's' (the parameter) and 'curve' (the index)."""
    rows = polylines(curves, chord_tol)
    pts = np.vstack([p for _, p, _ in rows]) if rows else np.empty((0, 3))
    params = np.concatenate([x for x, _, _ in rows]) if rows else np.empty(0)
    ids = np.concatenate([np.full(len(x), k) for k, (x, _, _) in enumerate(rows)]) if rows else np.empty(0)
    conn, offsets, start = [], [], 0
    for x, _, closed in rows:
        idx = list(range(start, start + len(x)))
        if closed and len(idx) > 1 and np.allclose(pts[idx[0]], pts[idx[-1]], rtol=0, atol=0):
            idx[-1] = idx[0]                       # the closing point is the first one
        conn += idx
        offsets.append(len(conn))
        start += len(x)

    def array(name, values, kind, comps=1):
        text = " ".join(repr(float(v)) if kind == "Float64" else str(int(v)) for v in np.ravel(values))
        return (f'<DataArray type="{kind}" Name="{escape(name)}" NumberOfComponents="{comps}" format="ascii">'
                f"{text}</DataArray>")
    xml = ['<?xml version="1.0"?>',
           '<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">', "<PolyData>",
           f'<Piece NumberOfPoints="{len(pts)}" NumberOfVerts="0" NumberOfLines="{len(rows)}" '
           'NumberOfStrips="0" NumberOfPolys="0">',
           "<PointData>", array("s", params, "Float64"), array("curve", ids, "Int64"), "</PointData>",
           "<Points>", array("Points", pts, "Float64", 3), "</Points>",
           "<Lines>", array("connectivity", conn, "Int64"), array("offsets", offsets, "Int64"), "</Lines>",
           "</Piece>", "</PolyData>", "</VTKFile>"]
    with atomic_path(path) as tmp, open(tmp, "w") as fh:
        fh.write("\n".join(xml) + "\n")
    return path


def splines(curves, tol=SPLINE_TOL):
    """B-splines of the curves: a BSpline as it is, a Curve by ``to_bspline(tol)`` (contact points skipped)."""
    out = []
    for _, _, _, _, c in _as_pieces(curves):
        if isinstance(c, BSpline):
            out.append(c)
        elif c.length > 0:
            out.append(c.to_bspline(tol))
    return out


def require(module):
    """Import an optional CAD module, or raise ImportError naming the extra that provides it."""
    try:
        return __import__(module)
    except ImportError:
        raise ImportError(f"this export needs {module}: pip install '{CAD_EXTRA}'") from None


def dxf_document(unit):
    """A new ezdxf document (R2010) whose header declares the length unit (a key of UNITS: $INSUNITS, and
    $MEASUREMENT metric or imperial)."""
    ezdxf = require("ezdxf")
    doc = ezdxf.new("R2010")
    doc.units = UNITS[check_unit(unit)][0]
    doc.header["$MEASUREMENT"] = 0 if unit == "in" else 1
    return doc


def write_dxf(path, curves, tol=SPLINE_TOL, layer="CURVES", unit="mm"):
    """DXF (R2010) with one 3-D SPLINE entity per curve: the B-spline's own degree, knots and control points; the
    header declares the unit the coordinates are in (a key of UNITS; None: unitless)."""
    doc = dxf_document(unit)
    msp = doc.modelspace()
    doc.layers.add(layer)
    for sp in splines(curves, tol):
        msp.add_open_spline(np.asarray(sp.c, dtype=float).tolist(), degree=int(sp.k),
                            knots=np.asarray(sp.t, dtype=float).tolist(), dxfattribs={"layer": layer})
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return path


def write_step(path, curves, tol=SPLINE_TOL, unit="mm"):
    """STEP (AP214) of the B-spline curves as edges, through OpenCascade (the ``cad`` extra); the file declares
    the unit the coordinates are in ("mm", "cm", "m" or "in"), and they are written as they are."""
    check_unit(unit, "STEP", unitless=False)
    require("OCP")
    from OCP.BRep import BRep_Builder
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    from OCP.TopoDS import TopoDS_Compound
    try:                                            # cadquery-ocp 7.x
        from OCP.TColgp import TColgp_Array1OfPnt
        from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
    except ImportError:                             # cadquery-ocp 8: NCollection arrays in OCP.collections
        from OCP.OCP.collections import Array1_double as TColStd_Array1OfReal
        from OCP.OCP.collections import Array1_gp_Pnt as TColgp_Array1OfPnt
        from OCP.OCP.collections import Array1_int as TColStd_Array1OfInteger

    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    for sp in splines(curves, tol):
        poles = TColgp_Array1OfPnt(1, len(sp.c))
        for i, p in enumerate(np.asarray(sp.c, dtype=float)):
            poles.SetValue(i + 1, gp_Pnt(*map(float, p)))
        values, counts = np.unique(np.asarray(sp.t, dtype=float), return_counts=True)
        knots = TColStd_Array1OfReal(1, len(values))
        mults = TColStd_Array1OfInteger(1, len(values))
        for i, (v, m) in enumerate(zip(values, counts)):
            knots.SetValue(i + 1, float(v))
            mults.SetValue(i + 1, int(m))
        curve = Geom_BSplineCurve(poles, knots, mults, int(sp.k))
        builder.Add(compound, BRepBuilderAPI_MakeEdge(curve).Edge())
    writer = STEPControl_Writer()
    with atomic_path(path) as tmp, _quiet_stdout(), _step_unit(UNITS[unit][1]):
        writer.Transfer(compound, STEPControl_AsIs)
        if writer.Write(tmp) != IFSelect_RetDone:
            raise OSError(f"OpenCascade could not write {os.path.basename(path)}")
    return path


@contextlib.contextmanager
def _step_unit(name):
    """OpenCascade's STEP writer declaring the unit name, its own unit set to the same so that no coordinate is
    scaled (both are process-wide settings: restored after)."""
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_Controller
    STEPControl_Controller.Init_s()
    keys = ("write.step.unit", "xstep.cascade.unit")
    saved = [Interface_Static.CVal_s(key) for key in keys]
    try:
        for key in keys:
            Interface_Static.SetCVal_s(key, name)
        yield
    finally:
        for key, value in zip(keys, saved):
            Interface_Static.SetCVal_s(key, value)


@contextlib.contextmanager
def _quiet_stdout():
    """OpenCascade prints its transfer statistics on the process's standard output: send them to /dev/null."""
    import sys
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


#: Writers by file suffix.
WRITERS = {".csv": write_csv, ".vtp": write_vtp, ".dxf": write_dxf, ".step": write_step, ".stp": write_step}


def export_curves(path, curves, **options):
    """Write curves to path, the format chosen by its suffix (.csv, .vtp, .dxf, .step/.stp)."""
    suffix = os.path.splitext(str(path))[1].lower()
    if suffix not in WRITERS:
        raise ValueError(f"path must end in one of {sorted(WRITERS)}, got {suffix or 'no suffix'!r}")
    return WRITERS[suffix](path, curves, **options)
