"""A planar linkage's drawing as DXF: links as lines, joints and the cranks' pin circles as circles, joint paths
as dense polylines (spaced by a chord height, from exact solutions), written atomically with ezdxf (a
dependency of spatialkin)."""
import numpy as np

from spatialkin.export import atomic_path, dense_polyline, dxf_document
from spatialkin._lib.validation import check_positive

#: Joint circles' radius, as a fraction of the linkage's mean link length.
JOINT_FRACTION = 0.03
#: Default chord height of the joint paths, as a fraction of the mean link length.
CHORD_FRACTION = 1e-5
#: Layers of the drawing.
LAYERS = ("LINKS", "JOINTS", "GROUND", "CRANK_CIRCLES", "PATHS")


def write_dxf(path, motion, indices=(0,), paths=(), chord_tol=None, unit="mm"):
    """Draw a LinkageMotion in a DXF (R2010) file.

    Parameters
    ----------
    path : str or path-like
    motion : planar.linkage.LinkageMotion
        From ``linkage.solve(angles)``.
    indices : sequence of int
        Positions (indices into the solved angles) at which the mechanism is drawn: cranks and binary links
        as LINE, ternary links as closed LWPOLYLINE, moving joints as CIRCLE (layer per kind, see LAYERS).
    paths : sequence of str
        Joints whose paths over the solved input range are drawn as LWPOLYLINE, dense by a chord height.
    chord_tol : float, optional
        Chord height of the paths (default CHORD_FRACTION of the mean link length), in the linkage's unit.
    unit : str or None
        The linkage's length unit, which the file's header declares ("mm", "cm", "m", "in"; None: unitless); the
        coordinates are written as they are.

    Each crank pin's circle is drawn as a CIRCLE about its pivot (layer CRANK_CIRCLES).
    """
    linkage = motion.linkage
    size = linkage.mean_length
    indices = [int(i) for i in np.atleast_1d(indices)]
    for i in indices:
        if not -len(motion) <= i < len(motion):
            raise ValueError(f"indices must lie in [0, {len(motion)}), got {i}")
    chord = CHORD_FRACTION * size if chord_tol is None else check_positive("chord_tol", chord_tol)
    doc = dxf_document(unit)
    msp = doc.modelspace()
    for name in LAYERS:
        doc.layers.add(name)
    radius = JOINT_FRACTION * size
    for i in indices:
        p = {j: motion.position(j)[i] for j in linkage.joints}
        for c in linkage.cranks:
            msp.add_line(tuple(p[c.pivot]), tuple(p[c.pin]), dxfattribs={"layer": "LINKS"})
        for link in linkage.links:
            pts = [tuple(p[j]) for j in link.joints]
            if len(pts) > 2:
                msp.add_lwpolyline(pts, close=True, dxfattribs={"layer": "LINKS"})
            else:
                msp.add_line(pts[0], pts[1], dxfattribs={"layer": "LINKS"})
        for j in linkage.moving:
            msp.add_circle(tuple(p[j]), radius, dxfattribs={"layer": "JOINTS"})
    for xy in linkage.fixed.values():
        msp.add_circle(tuple(xy), 1.5 * radius, dxfattribs={"layer": "GROUND"})
    for c in linkage.cranks:
        msp.add_circle(tuple(linkage.fixed[c.pivot]), c.radius, dxfattribs={"layer": "CRANK_CIRCLES"})
    lo, hi = float(np.min(motion.crank_angles)), float(np.max(motion.crank_angles))
    for joint in paths:
        motion.position(joint)                         # names the joint if it is unknown

        def evaluate(angles, joint=joint):
            xy = linkage.solve(angles, omega=motion.omega).position(joint)
            return np.column_stack([xy, np.zeros(len(xy))])
        _, pts = dense_polyline(evaluate, lo, hi, chord)
        msp.add_lwpolyline(pts[:, :2].tolist(), dxfattribs={"layer": "PATHS"})
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return path
