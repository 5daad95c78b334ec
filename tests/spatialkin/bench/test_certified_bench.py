"""The certified bench (spatialkin.bench.certified): a row per pair kind and per CAD face case, each certified answer's
claims read from its certificate, the closed-form kinds proven without a search, the faces' arcs proven."""
from spatialkin.bench import certified
from spatialkin.bench.kinds import face_cases, pair_kind_cases


def test_a_row_per_kind_with_what_was_proven():
    lines = []
    rows = certified.run(repeats=1, echo=lines.append)
    kinds = [name for name, _, _ in pair_kind_cases()]
    faces = [name for name, _, _ in face_cases()]
    assert [r[0] for r in rows] == kinds + faces and len(lines) == len(kinds) + len(faces) + 4
    table = lines[2:2 + len(kinds)] + lines[3 + len(kinds):-1]
    assert lines[2 + len(kinds)].startswith("CAD faces")
    for (name, plain, cert, ratio, proven, failed, bound, how), line in zip(rows, table):
        assert plain > 0 and cert > 0 and abs(ratio - cert / plain) < 1e-12
        assert (failed == "-") == proven and line.startswith(name) and how in line
        if proven:
            assert bound < 1e-9
    how = {r[0]: r[7] for r in rows}
    for name in ("plane-sphere", "sphere-sphere", "plane-cylinder"):
        assert how[name] == "closed form"
    assert how["torus-torus"] == "search"
    for name in faces:
        assert how[name] == "search" and next(r[4] for r in rows if r[0] == name)
