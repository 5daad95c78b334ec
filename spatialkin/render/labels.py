"""Where the text of a picture goes, in pixels, with no pyvista: labels set off their points clear of what is
drawn and of each other (joined to their points by leader lines), and the length of a scale bar.

Pixels count from the window's lower-left corner, x to the right and y up, as VTK's display coordinates do.
"""
import math

import numpy as np

#: Distances (pixels) from a label's point to the nearest edge of its box, tried in turn (nearest first).
OFFSETS = (14.0, 26.0, 42.0, 64.0, 92.0)
#: Directions tried at each distance (evenly around the point, starting to the right).
DIRECTIONS = 16
#: Clearance (pixels) kept between a label's box and other boxes, and added around drawn points.
CLEARANCE = 4.0
#: Cost of one drawn point under a label's box, of a leader line crossing another box, and of a pixel of leader.
POINT_COST, CROSSING_COST, LEADER_COST = 40.0, 400.0, 0.6
#: A leader line is drawn only when the box's nearest edge is at least this far from the point (pixels).
LEADER_MIN = 8.0
#: Round lengths of a scale bar: these times a power of ten.
ROUND_STEPS = (1.0, 2.0, 5.0)


def densify(points, step):
    """Points (M, 2) along a pixel polyline (N, 2), no two consecutive ones further apart than step."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(points) < 2:
        return points
    gaps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    counts = np.maximum(1, np.ceil(gaps / step).astype(int))
    pieces = [a + np.linspace(0.0, 1.0, n, endpoint=False)[:, None] * (b - a)
              for a, b, n in zip(points[:-1], points[1:], counts)]
    return np.vstack([*pieces, points[-1:]])


def box_at(anchor, size, direction, offset):
    """(x0, y0, x1, y1) of a box of size (w, h) set off anchor along the unit direction: its nearest point to the
    anchor lies `offset` pixels from it along that direction (centre + the half sizes scaled by the direction)."""
    w, h = size
    dx, dy = direction
    cx = anchor[0] + dx * offset + 0.5 * w * dx / max(abs(dx), abs(dy))
    cy = anchor[1] + dy * offset + 0.5 * h * dy / max(abs(dx), abs(dy))
    return np.array([cx - 0.5 * w, cy - 0.5 * h, cx + 0.5 * w, cy + 0.5 * h])


def nearest_on_box(box, point):
    """The point of a box (x0, y0, x1, y1) nearest to a point (2,)."""
    return np.array([min(max(point[0], box[0]), box[2]), min(max(point[1], box[1]), box[3])])


def segment_hits_box(a, b, box, samples=24):
    """True when the segment a-b passes through the box (sampled along it; the ends excluded)."""
    t = np.linspace(0.0, 1.0, samples)[1:-1, None]
    pts = a + t * (b - a)
    return bool(np.any((pts[:, 0] > box[0]) & (pts[:, 0] < box[2]) & (pts[:, 1] > box[1]) & (pts[:, 1] < box[3])))


def place_labels(anchors, sizes, obstacles, frame):
    """Boxes for labels, one at a time in the order given, each where it covers least of what is drawn.

    Each label is tried at OFFSETS from its point in DIRECTIONS; a box must lie inside `frame` and clear of the
    boxes already placed (by CLEARANCE); among those, the cost is POINT_COST per drawn point under the box (grown
    by CLEARANCE), CROSSING_COST per placed box its leader line crosses, and LEADER_COST per pixel of leader.
    When no box fits, the one of least cost that stays inside the frame is taken.

    Parameters
    ----------
    anchors : array_like (N, 2)
        The labels' points, pixels.
    sizes : array_like (N, 2)
        Width and height of each label's box, pixels.
    obstacles : array_like (M, 2)
        Pixels of what is drawn (curves, links, joints; densified) that labels should not cover; the other
        labels' points are added to them.
    frame : (x0, y0, x1, y1)
        The part of the window labels may use, pixels.

    Returns
    -------
    boxes : ndarray (N, 4)
        (x0, y0, x1, y1) of each label's box.
    leaders : list of ndarray (2, 2) or None
        From each label's point to the nearest point of its box; None where the box is at the point.
    """
    anchors = np.asarray(anchors, dtype=float).reshape(-1, 2)
    sizes = np.asarray(sizes, dtype=float).reshape(-1, 2)
    obstacles = np.vstack([np.asarray(obstacles, dtype=float).reshape(-1, 2), anchors])
    fx0, fy0, fx1, fy1 = frame
    angles = 2 * np.pi * np.arange(DIRECTIONS) / DIRECTIONS
    directions = np.column_stack([np.cos(angles), np.sin(angles)])
    placed, leaders = [], []
    for k, (anchor, size) in enumerate(zip(anchors, sizes)):
        others = np.delete(obstacles, len(obstacles) - len(anchors) + k, axis=0)
        best, best_cost, fallback, fallback_cost = None, math.inf, None, math.inf
        for offset in OFFSETS:
            for direction in directions:
                box = box_at(anchor, size, direction, offset)
                if box[0] < fx0 or box[1] < fy0 or box[2] > fx1 or box[3] > fy1:
                    continue
                grown = box + np.array([-CLEARANCE, -CLEARANCE, CLEARANCE, CLEARANCE])
                covered = np.count_nonzero((others[:, 0] > grown[0]) & (others[:, 0] < grown[2])
                                           & (others[:, 1] > grown[1]) & (others[:, 1] < grown[3]))
                end = nearest_on_box(box, anchor)
                crossings = sum(segment_hits_box(anchor, end, other) for other in placed)
                cost = POINT_COST * covered + CROSSING_COST * crossings + LEADER_COST * offset
                clash = any(grown[0] < o[2] and o[0] < grown[2] and grown[1] < o[3] and o[1] < grown[3]
                            for o in placed)
                if not clash and cost < best_cost:
                    best, best_cost = box, cost
                if cost < fallback_cost:
                    fallback, fallback_cost = box, cost
        box = best if best is not None else fallback
        if box is None:                                  # the frame is smaller than the label: at its point
            box = np.array([anchor[0], anchor[1], anchor[0] + size[0], anchor[1] + size[1]])
        placed.append(box)
        end = nearest_on_box(box, anchor)
        leaders.append(np.array([anchor, end]) if np.linalg.norm(end - anchor) >= LEADER_MIN else None)
    return np.array(placed).reshape(-1, 4), leaders


def round_length(longest):
    """The largest of 1, 2 or 5 times a power of ten not above `longest` (> 0): a scale bar's length."""
    if not (longest > 0 and math.isfinite(longest)):
        raise ValueError(f"longest must be positive and finite, got {longest!r}")
    power = 10.0 ** math.floor(math.log10(longest))
    return max(step * power for step in ROUND_STEPS if step * power <= longest * (1 + 1e-12))
