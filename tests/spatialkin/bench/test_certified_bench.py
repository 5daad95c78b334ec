"""The certified bench (spatialkin.bench.certified): a row per pair kind, each certified answer's claims read from its
certificate (the counts of curves against the plain call's), the closed-form kinds proven without a search."""
from spatialkin.bench import certified
from spatialkin.bench.kinds import pair_kind_cases


def test_a_row_per_kind_with_what_was_proven():
    lines = []
    rows = certified.run(repeats=1, echo=lines.append)
    names = [name for name, _, _ in pair_kind_cases()]
    assert [r[0] for r in rows] == names and len(lines) == len(names) + 3
    for (name, plain, cert, ratio, proven, failed, bound, how), line in zip(rows, lines[2:]):
        assert plain > 0 and cert > 0 and abs(ratio - cert / plain) < 1e-12
        assert (failed == "-") == proven and line.startswith(name) and how in line
        if proven:
            assert bound < 1e-9
    how = {r[0]: r[7] for r in rows}
    for name in ("plane-sphere", "sphere-sphere", "plane-cylinder"):
        assert how[name] == "closed form"
    assert how["torus-torus"] == "search"
