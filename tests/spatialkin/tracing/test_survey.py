"""The consistency survey of near-degenerate pairs (tests/spatialkin/tracing/survey_degenerate.py; all 37 families: run it as a
script) on the families of trims grazed, corners, near-tangent circles, split pairs and a cone's apex beside a sphere
where a silent miss is most likely: in 3 placements and both argument orders, at offsets 1e-9 to 1e-3 of either sign,
every answer (statuses and lengths to 4 digits) the same. Oracles: the intersection's invariance under rigid motion and
argument order, and for the trim families the statuses their geometry fixes on each side of the edge."""
import numpy as np
from tests.spatialkin.tracing import survey_degenerate as sd

FAMILIES = (sd.fam_torus_plane_edge, sd.fam_plane_cyl_rim, sd.fam_plane_torus_two_edges, sd.fam_corner,
            sd.fam_steinmetz_radius, sd.fam_torus_sphere_inner, sd.fam_cyl_torus_inner, sd.fam_sphere_cyl_rim,
            sd.fam_viviani_trim, sd.fam_cone_apex_on_sphere)
#: Statuses at +offset and -offset: a circle whose extreme passes the trim edge by the offset comes back as an arc
#: from edge to edge, inside it as a loop (the torus's outer circle against a plane's u edge; a tilted plane's
#: ellipse against a cylinder's rim); a circle through a square's corners region: 4 arcs inside it, nothing outside;
#: a rectangle's corner outside a torus's circle by the offset: a third, tiny arc.
SIDES = {
    sd.fam_torus_plane_edge: (["closed", "closed"], ["boundary", "closed"]),
    sd.fam_plane_cyl_rim: (["boundary"], ["closed"]),
    sd.fam_corner: ([], ["boundary"] * 4),
    sd.fam_plane_torus_two_edges: (["boundary", "boundary", "closed"], ["boundary", "closed"]),
}


def test_near_degenerate_answers_agree_across_placements_and_orders():
    lines = []
    assert sd.survey(FAMILIES, echo=lines.append) == [], "\n".join(line for line in lines if line.startswith("!!!"))
    assert len(lines) == len(FAMILIES) * len(sd.OFFSETS) * 2


def test_a_trim_grazed_by_the_offset_ends_the_curve_on_its_side():
    for family, (outside, inside) in SIDES.items():
        for eps in sd.OFFSETS:
            for sign, expected in ((1.0, outside), (-1.0, inside)):
                a, b = family(np.random.default_rng(0), sign * eps)
                got = sorted(status for status, _ in sd.answer(a, b)[0])
                assert got == expected, (family.__name__, sign * eps, got)


def test_a_refusal_beside_curves_is_flagged_not_a_crash(monkeypatch):
    """An offset whose placements answer with curves in one and an exception in another (the survey's answer of a
    refusal is the exception's name) is flagged and echoed with both answers, not a TypeError of their sort."""
    answers = iter([((("closed", 1.0),), 0.0), (("TopologyError",), 0.0)] * (len(sd.OFFSETS) * 2 * sd.PLACEMENTS))
    monkeypatch.setattr(sd, "answer", lambda a, b: next(answers))
    lines = []
    flagged = sd.survey((sd.fam_corner,), echo=lines.append)
    assert len(flagged) == len(sd.OFFSETS) * 2
    assert all(line.startswith("!!!") and "TopologyError" in line and "closed" in line for line in lines)
