"""The API reference: every public name of the API contract has a numpydoc docstring whose examples run.

For each name of PUBLIC (the contract's names: DESIGN.md, "Public API contract") the docstring is checked for a
one-line summary and the numpydoc sections it needs: Parameters when the callable takes arguments, Returns when
it is a function or method (every one listed returns something), Raises naming each typed error its code raises
(the tuple beside each name, read off the code), Examples, and References where a formula comes from a paper.
Then its Examples run under doctest (NORMALIZE_WHITESPACE | ELLIPSIS) in a fresh namespace, so that every example
imports what it uses; a name with no example, or with a failing one, fails here by name. The examples print only
rounded values far from a rounding boundary, shapes, booleans and counts, so that they pass on any x86-64 CPU.
"""
import doctest
import inspect
import re

import pytest

import planar
import spatialkin as sk
from planar.linkage import LinkageMotion
from spatialkin.design import LooperDesign, sweep
from spatialkin.mechanisms import LooperDrive, LooperMotion
from spatialkin.geometry.surfaces import Surface

#: name -> (object, the exceptions its Raises section must name: what its code raises).
PUBLIC = {
    "sk.Frame": (sk.Frame, ("ValueError",)),
    "sk.rotation_about": (sk.rotation_about, ("ValueError",)),
    "sk.rotation_to_z": (sk.rotation_to_z, ("ValueError",)),
    "sk.Torus": (sk.Torus, ("ValueError", "TypeError")),
    "sk.Sphere": (sk.Sphere, ("ValueError", "TypeError")),
    "sk.Plane": (sk.Plane, ("ValueError", "TypeError")),
    "sk.Cylinder": (sk.Cylinder, ("ValueError", "TypeError")),
    "sk.Cone": (sk.Cone, ("ValueError", "TypeError")),
    "Surface.point": (Surface.point, ("ValueError",)),
    "Surface.distance": (Surface.distance, ("ValueError",)),
    "sk.trace": (sk.trace, ("ValueError", "TypeError", "TracingError")),
    "sk.intersect": (sk.intersect, ("CoincidentSurfacesError", "ValueError", "TypeError", "TopologyError",
                                    "CertificationError")),
    "sk.Curve": (sk.Curve, ("TypeError",)),
    "sk.Curve.points": (sk.Curve.points, ()),
    "sk.Curve.s": (sk.Curve.s, ()),
    "sk.Curve.params": (sk.Curve.params, ()),
    "sk.Curve.closed": (sk.Curve.closed, ()),
    "sk.Curve.length": (sk.Curve.length, ()),
    "sk.Curve.certificate": (sk.Curve.certificate, ()),
    "sk.Curve.__call__": (sk.Curve.__call__, ("ValueError",)),
    "sk.Curve.to_bspline": (sk.Curve.to_bspline, ("ValueError", "SplineToleranceError")),
    "sk.intersect_many": (sk.intersect_many, ("ValueError", "TypeError", "BatchError", "RuntimeError")),
    "sk.BatchError": (sk.BatchError, ()),
    "sk.TracingError": (sk.TracingError, ("ValueError",)),
    "sk.TopologyError": (sk.TopologyError, ()),
    "sk.CoincidentSurfacesError": (sk.CoincidentSurfacesError, ()),
    "LooperDrive": (LooperDrive, ("ValueError", "TypeError")),
    "LooperDrive.solve": (LooperDrive.solve, ("ValueError",)),
    "LooperDrive.reference": (LooperDrive.reference, ()),
    "LooperMotion": (LooperMotion, ()),
    "planar.CrankSlider": (planar.CrankSlider, ("ValueError",)),
    "planar.CrankRocker": (planar.CrankRocker, ("ValueError",)),
    "planar.DrivenLink": (planar.DrivenLink, ("TypeError", "ValueError")),
    "planar.DrivenLink.position": (planar.DrivenLink.position, ("ValueError",)),
    "planar.DrivenLink.velocity": (planar.DrivenLink.velocity, ("ValueError",)),
    "planar.DrivenLink.acceleration": (planar.DrivenLink.acceleration, ("ValueError",)),
    "planar.examples.fnf_sixbar": (planar.examples.fnf_sixbar, ()),
    "planar.Linkage.solve": (planar.Linkage.solve, ("ValueError", "LockError")),
    "LinkageMotion.position": (LinkageMotion.position, ("ValueError",)),
    "LinkageMotion.velocity": (LinkageMotion.velocity, ("ValueError",)),
    "LinkageMotion.acceleration": (LinkageMotion.acceleration, ("ValueError",)),
    "LooperDesign": (LooperDesign, ("ValueError",)),
    "LooperDesign.from_drive": (LooperDesign.from_drive, ("ValueError",)),
    "LooperDesign.sensitivities": (LooperDesign.sensitivities, ("ValueError",)),
    "LooperDesign.fit": (LooperDesign.fit, ("ValueError",)),
    "spatialkin.design.sweep": (sweep, ("ValueError",)),
}
#: Result objects whose Attributes section must describe these fields (shapes and units).
FIELDS = {
    "sk.Curve": ("points", "s", "params", "closed", "length", "certificate"),
    "LooperMotion": ("ball_center", "ball_velocity", "ball_acceleration", "crank_angle", "rocker_angles",
                     "rocker_rates", "rocker_accelerations", "looper_tip"),
}
#: Names whose formulas come from a paper: their References cite it (one of these words in the section).
CITED = {
    "sk.trace": ("Investigation of the trajectories", "Hairer"),
    "sk.intersect": ("Investigation of the trajectories", "Kearfott", "Moore", "Patrikalakis", "Hong"),
    "sk.Torus": ("Investigation of the trajectories",),
    "sk.Sphere": ("Investigation of the trajectories",),
    "sk.Curve.to_bspline": ("Piegl",),
    "LooperDrive": ("Investigation of the trajectories",),
    "LooperDrive.reference": ("Investigation of the trajectories",),
    "LooperDesign.sensitivities": ("Griewank", "Investigation of the trajectories"),
    "planar.CrankSlider": ("Pylypaka",),
    "planar.CrankRocker": ("Pylypaka",),
    "planar.DrivenLink": ("Pylypaka",),
    "planar.examples.fnf_sixbar": ("Koshel",),
    "planar.Linkage.solve": ("Koshel",),
}
#: Words of history or of documents that do not ship; the reference cites the published sources instead.
UNSHIPPED = re.compile(r"\.\./shared|seed[ -]?0\d\d|\bseed\b.*\.md", re.IGNORECASE)
#: A numpydoc section heading: a title over a line of as many dashes.
HEADING = re.compile(r"^([A-Z][A-Za-z ]+)\n(-+)$", re.MULTILINE)
FLAGS = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS


def sections(doc):
    """{title: body} of the numpydoc sections of a docstring (its first line's indentation removed)."""
    text = inspect.cleandoc(doc)
    heads = list(HEADING.finditer(text))
    for m in heads:
        assert len(m.group(2)) == len(m.group(1)), f"the underline of {m.group(1)!r} must be as long as the title"
    ends = [m.start() for m in heads[1:]] + [len(text)]
    return {m.group(1): text[m.end():end] for m, end in zip(heads, ends)}


def takes_arguments(obj):
    """True when calling obj (a class: constructing it) takes arguments besides self or cls."""
    if isinstance(obj, property):
        return False
    if inspect.isclass(obj) and issubclass(obj, BaseException) and not inspect.isfunction(obj.__init__):
        return True                                  # an exception's message (no signature of its own)
    params = list(inspect.signature(obj).parameters)
    if inspect.isfunction(obj) and params[:1] == ["self"]:
        params = params[1:]
    return bool(params)


def check_sections(name, obj, raises):
    doc = obj.__doc__
    assert doc and doc.strip(), f"{name} has no docstring"
    lines = inspect.cleandoc(doc).splitlines()
    assert lines[0].strip() and lines[0].rstrip().endswith("."), f"{name}: the summary must be one sentence"
    assert len(lines) == 1 or not lines[1].strip(), f"{name}: the summary must be one line, then a blank line"
    found = sections(doc)
    if takes_arguments(obj):
        assert found.get("Parameters", "").strip(), f"{name} takes arguments: it needs a Parameters section"
    if inspect.isroutine(obj):
        assert found.get("Returns", "").strip(), f"{name} returns a value: it needs a Returns section"
    if raises:
        body = found.get("Raises", "")
        missing = [e for e in raises if not re.search(rf"\b{e}\b", body)]
        assert not missing, f"{name}: its Raises section must name {missing} (what its code raises)"
    assert ">>>" in found.get("Examples", ""), f"{name} needs an Examples section with examples"
    for field in FIELDS.get(name, ()):
        assert re.search(rf"^{field}\b|[ ,]{field}\b", found.get("Attributes", ""), re.MULTILINE), \
            f"{name}: its Attributes section must describe {field}"
    if name in CITED:
        body = found.get("References", "")
        assert any(source in body for source in CITED[name]), f"{name}: its References must cite {CITED[name]}"
    assert not UNSHIPPED.search(doc), f"{name}: cite the published sources, not unshipped documents or seeds"


def run_examples(name, obj):
    """(examples run, failures, the report of the failures) of obj's docstring alone, in a fresh namespace."""
    tests = doctest.DocTestFinder(recurse=False).find(obj, name=name, globs={})
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report = []
    for test in tests:
        runner.run(test, out=report.append)
    return sum(len(t.examples) for t in tests), runner.failures, "".join(report)


CASES = [pytest.param(name, obj, raises, id=name) for name, (obj, raises) in PUBLIC.items()]


@pytest.mark.parametrize("name, obj, raises", CASES)
def test_numpydoc_sections(name, obj, raises):
    check_sections(name, obj, raises)


@pytest.mark.parametrize("name, obj, raises", CASES)
def test_examples_run(name, obj, raises):
    count, failures, report = run_examples(name, obj)
    assert count >= 1, f"{name} has no examples"
    assert failures == 0, f"{name}: {failures} of its {count} examples failed\n{report}"


def test_intersect_notes_explain_tol_and_the_topology_stage():
    """sk.intersect's Notes tell what tol means (measured distance to both surfaces) and how components are found."""
    notes = sections(sk.intersect.__doc__).get("Notes", "")
    for phrase in ("tol", "both surfaces", "measured", "topology stage", "interval", "closed form"):
        assert phrase in notes, f"sk.intersect's Notes must explain {phrase!r}"


def test_the_checks_catch_a_docstring_without_examples_or_raises():
    """The section checks fail on a docstring that lost its Examples or does not name what the code raises."""
    def lost(x):
        """Something.

        Parameters
        ----------
        x : float

        Returns
        -------
        float

        Raises
        ------
        ValueError
            For a bad x.
        """

    with pytest.raises(AssertionError, match="needs an Examples section"):
        check_sections("lost", lost, ("ValueError",))
    with pytest.raises(AssertionError, match="must name"):
        check_sections("lost", lost, ("TypeError",))
    assert run_examples("lost", lost)[0] == 0
