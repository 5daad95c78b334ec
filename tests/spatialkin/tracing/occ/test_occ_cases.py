"""OpenCascade's surface-surface intersection tests (OCCT tests/lowalgos/intss, tests/boolean/bsection and
bopsection, tests/bugs/modalg_*) run through spatialkin, in both argument orders.

Oracle: the independent truth of each case (cases.py: closed forms, or exact sweeps measured at 60 digits by
tests/oracles/occ/truth.py). The comparison (compare.py) asks for the truth's number of connected components, each
component's length and the total length to 1e-7 relative + 1e-9 x scale, each component's closedness and free ends,
and every returned point within 1e-9 x scale of both surfaces (spatialkin promises tol x scale with
tol = 1e-10). Runs that spatialkin fails are strict xfails named by their failure class (occ_compare.CLASSES), so an
unexpected pass is reported.
"""
import pytest

from tests.oracles.occ import cases
from tests.oracles.occ import draw as occ_draw
from tests.spatialkin.tracing.occ import compare as occ_compare

_TRUTHS = {}


def _truth(case):
    if case.id not in _TRUTHS:
        _TRUTHS[case.id] = case.truth()
    return _TRUTHS[case.id]


def _params():
    out = []
    for case in cases.CASES:
        for order in ("ab", "ba"):
            marks = []
            reason = case.xfail.get(order)
            if reason:
                marks.append(pytest.mark.xfail(strict=True, reason=reason))
            out.append(pytest.param(case, order, id=f"{case.id}-{order}", marks=marks))
    return out


@pytest.mark.parametrize("case, order", _params())
def test_occ_case(case, order):
    found = occ_compare.problems(case, order, truth=_truth(case))
    assert not found, "\n".join(f"[{kind}] {message}" for kind, message in found)


def test_every_case_translates_and_has_a_truth():
    """Every case builds both spatialkin surfaces (no NotExpressible) and its truth (a swept one is stored); the
    case ids are unique."""
    for case in cases.CASES:
        case.surfaces()
        _truth(case)
    ids = [case.id for case in cases.CASES]
    assert len(ids) == len(set(ids))
    assert set(cases.XFAIL) <= set(ids)


def test_truth_lies_on_both_surfaces():
    """The truth's own points (closed forms and stored sweeps alike) lie on both spatialkin surfaces, within
    1e-9 x scale: the translation of the surfaces and the truth agree."""
    bad = []
    for case in cases.CASES:
        truth = _truth(case)
        if truth.coincident:
            continue
        a, b = case.surfaces()
        pts = [p for comp in truth.components for line in comp.polylines(0.05 * case.scale) for p in line[::7]]
        pts += list(truth.points)
        if not pts:
            continue
        import numpy as np
        pts = np.array(pts)
        d = max(float(a.distance(pts).max()), float(b.distance(pts).max()))
        if d > 1e-9 * case.scale:
            bad.append(f"{case.id}: {d:.3g}")
    assert not bad, "truth points off a surface: " + "; ".join(bad)


def test_translation_agrees_with_opencascade():
    """Every surface made from DRAW arguments, and every primitive face, as OpenCascade itself builds it (OCP):
    points of OpenCascade's surface over its own parameter box lie on the spatialkin surface (within 1e-12 of the
    coordinates' magnitude), inside spatialkin's axial trims, and the X axis of a placement given by its normal
    only is OpenCascade's (gp_Ax3)."""
    pytest.importorskip("OCP")
    import math

    import numpy as np
    from OCP.BRep import BRep_Tool
    from OCP.BRepPrimAPI import (BRepPrimAPI_MakeCone, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeSphere,
                                 BRepPrimAPI_MakeTorus)
    from OCP.BRepTools import BRepTools
    from OCP.Geom import (Geom_ConicalSurface, Geom_CylindricalSurface, Geom_Plane, Geom_SphericalSurface,
                          Geom_ToroidalSurface)
    from OCP.gp import gp_Ax2, gp_Ax3, gp_Dir, gp_Pnt
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    for case in cases.CASES:
        case.geos()

    def ax3(nums):
        p = gp_Pnt(*nums[:3])
        if len(nums) == 3:
            return gp_Ax3(p, gp_Dir(0, 0, 1), gp_Dir(1, 0, 0))
        if len(nums) == 6:
            return gp_Ax3(p, gp_Dir(*nums[3:6]))
        return gp_Ax3(p, gp_Dir(*nums[3:6]), gp_Dir(*nums[6:9]))

    def ax2(place):
        if place is None:
            return gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0))
        o, x, _, z = place
        return gp_Ax2(gp_Pnt(*o), gp_Dir(*z), gp_Dir(*x))

    bad, seen = [], set()
    for command, args, g in occ_draw.MADE:
        key = (command, repr(args))
        if key in seen:
            continue
        seen.add(key)
        if isinstance(args, str):
            nums = occ_draw.values(args)
            npar = {"plane": 0, "cylinder": 1, "sphere": 1, "cone": 2, "torus": 2}[command]
            place = ax3(nums[:len(nums) - npar] if len(nums) > npar else [0, 0, 0])
            par = nums[len(nums) - npar:]
            surf = {"plane": lambda: Geom_Plane(place),
                    "cylinder": lambda: Geom_CylindricalSurface(place, par[0]),
                    "sphere": lambda: Geom_SphericalSurface(place, par[0]),
                    "cone": lambda: Geom_ConicalSurface(place, math.radians(par[0]), par[1]),
                    "torus": lambda: Geom_ToroidalSurface(place, par[0], par[1])}[command]()
            if not np.allclose(place.XDirection().Coord(), g.x, atol=1e-15, rtol=0):
                bad.append(f"{command} {args}: X {place.XDirection().Coord()} != {g.x}")
            vr = g.v_range if g.v_range is not None else (-3.0, 3.0)
            if command == "sphere":
                vr = (-math.pi / 2, math.pi / 2)
            if command == "torus":
                vr = (0.0, 2 * math.pi)
            box = (0.0, 2 * math.pi, *vr) if command != "plane" else (-3.0, 3.0, -3.0, 3.0)
        else:
            shape = {"pcylinder": lambda: BRepPrimAPI_MakeCylinder(ax2(args[2]), args[0], args[1]),
                     "pcone": lambda: BRepPrimAPI_MakeCone(ax2(args[3]), args[0], args[1], args[2]),
                     "psphere": lambda: BRepPrimAPI_MakeSphere(ax2(args[1]), args[0]),
                     "ptorus": lambda: BRepPrimAPI_MakeTorus(ax2(args[2]), args[0], args[1])}[command]().Shape()
            face = TopoDS.Face(TopExp_Explorer(shape, TopAbs_FACE).Current())
            surf = BRep_Tool.Surface_s(face)
            box = BRepTools.UVBounds_s(face)
        pts = np.array([surf.Value(u, v).Coord() for u in np.linspace(box[0], box[1], 9)
                        for v in np.linspace(box[2], box[3], 7)])
        sk_surface = occ_draw.to_sk(occ_draw.Geo(**{**g.__dict__, "u_range": None})
                                    if g.kind != "plane" else g)
        tol = 1e-12 * max(1.0, float(np.abs(pts).max()))
        d = float(sk_surface.distance(pts).max())
        if d > tol:
            bad.append(f"{command} {args}: OpenCascade's points {d:.3g} off the spatialkin surface")
        if g.kind in ("cylinder", "cone") and g.v_range is not None and not isinstance(args, str):
            v = sk_surface.parameters(pts)[:, 1]
            lo, hi = sk_surface.v_range
            if v.min() < lo - tol or v.max() > hi + tol or min(abs(v.min() - lo), abs(v.max() - hi)) > tol:
                bad.append(f"{command} {args}: face's axial extent [{v.min()}, {v.max()}] is not spatialkin's "
                           f"[{lo}, {hi}]")
    assert not bad, "\n".join(bad)
