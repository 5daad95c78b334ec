"""The shipped files describe the product as it is, not how it got there.

The package (spatialkin/**, planar/**: Python sources and .md/.toml/.txt/.json data), README.md, CHANGELOG.md (when
present; its '## x.y.z' release headings are exempt) and the notebooks' cell sources (markdown and code, not outputs)
must not mention:

- ``../shared/...`` files (they do not ship) and the "seed 000/001/002" documents;
- a development round ("round 3", "the seventh round", "this session");
- an issue or pull-request number ("issue 19", "issues 8 and 14", "#19", "PR 7");
- a commit hash (7-40 lower-case hex characters, letters and digits both, standing as a word);
- a date ("2026-11-23", "26 Nov 2026") or the workplace's tooling ("farm-bench", "this workplace").

History lives in git log; cite the published sources instead. The detector is checked first against sample
strings with the verdict they must get (the oracle), then run on every file; a failure names file and line.
"""
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Folders of the shipped package, and the suffixes of the files read there (sources and data).
PACKAGES = ("spatialkin", "planar")
SUFFIXES = {".py", ".md", ".toml", ".txt", ".json", ".rst", ".cfg", ".yaml", ".yml"}
#: A CHANGELOG's release headings ("## 1.2.0", "## [0.3.1] - 2026-12-01") may carry a version and a date.
RELEASE_HEADING = re.compile(r"^#{2,3}\s+\[?v?\d+\.\d+(?:\.\d+)?\b")

MONTHS = "Jan|Feb|Mar|Apr|May|Jun|Jul|Aug|Sep|Sept|Oct|Nov|Dec"
ORDINALS = r"first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|tenth|eleventh|twelfth|\d+(?:st|nd|rd|th)"
#: (kind, pattern). Each is narrow on purpose: the self-test below lists what must and must not match.
PATTERNS = [
    ("shared file", re.compile(r"(?:\.\./)+shared/|\bshared/(?:reference|seeds)/")),
    ("seed document", re.compile(r"\bseeds?[-_ ]?0\d\d(?!\d)", re.IGNORECASE)),
    # "round 3", "rounds 2-4", "the seventh round" (not "round-off", "round(x, 6)", "the first round of Newton steps")
    ("development round", re.compile(
        r"\brounds?[- ]\d+\b|\b(?:" + ORDINALS + r")\s+(?:development\s+|review\s+)?round\b"
        r"(?![- ]?off\b| of (?:Newton|bisection|iterations?|refinement|subdivision|steps)\b)"
        r"|\b(?:this|last|previous|next|earlier)\s+session\b", re.IGNORECASE)),
    # "issue 19", "issues 8 and 14", "Issue #3", "PR 12", "#19" (not "#1f77b4", '"#000000"', "# 19", "x#1")
    ("issue number", re.compile(
        r"\b(?:issues?|PR|pull request)\s*#?\d+\b|(?<![\w&#/'\"])#\d{1,5}\b(?!\.\d|[\w'\"])", re.IGNORECASE)),
    # 7-40 lower-case hex characters with a letter and a digit, as a word ('_' may precede it, as in a file name
    # "002_e94892734c112872.txt"); not after '#' (a colour), '.', '+' or '-' (inside a number)
    ("commit hash", re.compile(
        r"(?<![0-9A-Za-z#.+-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![\w-])")),
    ("date", re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b|\b[0-3]?\d\s+(?:" + MONTHS + r")[a-z]*\.?\s+20\d\d\b"
                        r"|\b(?:" + MONTHS + r")[a-z]*\.?\s+[0-3]?\d,?\s+20\d\d\b")),
    ("tooling", re.compile(r"\bfarm-bench\b|\bthis workplace\b", re.IGNORECASE)),
]


def findings(text):
    """[(kind, matched text)] of every pattern in one line of text."""
    return [(kind, m.group(0)) for kind, pattern in PATTERNS for m in pattern.finditer(text)]


# --- the detector against its oracle -------------------------------------------------------------------------
@pytest.mark.parametrize("text, kind", [
    ("Seed 002 and ../shared/reference/looper-drive.md (the scheme)", "shared file"),
    ("decoded in shared/reference/ssi-notes.md", "shared file"),
    ("Seed 002, reference [3]", "seed document"),
    ("planar (a): seed-000 crank-slider k = 0.5", "seed document"),
    ("the reference geometry of seed 001's six-link", "seed document"),
    ("fixed in round 3 of the review", "development round"),
    ("rounds 2-4 kept it", "development round"),
    ("the seventh round: cone apex beside a plane", "development round"),
    ("in the second round of review", "development round"),
    ("measured in the 7th round", "development round"),
    ("what this session changed", "development round"),
    ("the examples of issue 14", "issue number"),
    ("issues 8 and 14", "issue number"),
    ("what remains (Issue #19, item 2)", "issue number"),
    ("merged in PR 12", "issue number"),
    ("as asked in #19.", "issue number"),
    ("the Python near_curve it replaced (spatialkin 5b6a3a9)", "commit hash"),
    ("see 3d3b305 for the change", "commit hash"),
    ("seed 002_e94892734c112872.txt", "commit hash"),
    ("seed 002_e94892734c112872.txt", "seed document"),
    ("a full hash 41e0134f5a9c2b7d8e6f0a1b2c3d4e5f6a7b8c9d here", "commit hash"),
    ("what it found on 26 Nov 2026", "date"),
    ("Measured on 2026-11-23: all 522 cases pass.", "date"),
    ("since November 26, 2026", "date"),
    ("timed by farm-bench", "tooling"),
    ("the limits of this workplace", "tooling"),
])
def test_detector_flags(text, kind):
    assert kind in [k for k, _ in findings(text)], findings(text)


@pytest.mark.parametrize("text", [
    "rng = np.random.default_rng(1401)",
    "@pytest.mark.parametrize('seed', [0, 3])",
    "a configuration (seed 789, 'near') whose Newton steps reach round-off",
    "the extremal roots seed what is left; seeds on the arms of a node",
    "to round-off (1e-15), round off errors and round(c.length, 6)",
    "the loop runs half round the cylinder, 2e-4 high; a round trip",
    "the first round of Newton steps; the second round-off term",
    "a session of Jupyter; the user's session",
    "colours = ['#1f77b4', \"#000000\", '#ff7f0e']  # 3 kinds",
    "x = y  # 19 points per turn",
    "#: Grey levels of the drawing.",
    "an issue with 3 loops",
    "EPS = 2.220446049250313e-16; TINY = 2.2250738585072014e-308",
    "[1.0, -8048581381 / 2820520608, 8663915743 / 2820520608]",
    "PHASE = 0.3183098861837907; 1.5e10 and 2e-10",
    "deadbeef and facade are words, 1234567 a number, snake_abcdef1_name an identifier, 0x7fffffff a mask",
    "S. O. Koshel, A. V. Koshel, Visnyk KNUTD, 2014, no. 2; Springer, 2002; SIAM 2009",
    "Math. Comput. Simul. 42 (1996); ACM Trans. Math. Softw. 16(2), 1990, 152-157",
    "a shared/ folder of the user's own; shared memory",
    "version 0.3.1 of scipy 1.17.1; 26 Nov of a year; 1 Nov 99",
])
def test_detector_passes(text):
    assert findings(text) == []


def test_release_heading_is_the_only_changelog_exemption():
    assert RELEASE_HEADING.match("## 0.3.0 - 2026-12-01") and RELEASE_HEADING.match("## [1.2.3]")
    assert not RELEASE_HEADING.match("- fixed in 2026-12-01") and not RELEASE_HEADING.match("## Changes in round 3")


# --- the files ------------------------------------------------------------------------------------------------
def package_files():
    return sorted(p for name in PACKAGES for p in (ROOT / name).rglob("*")
                  if p.is_file() and p.suffix in SUFFIXES and "__pycache__" not in p.parts)


def text_lines(path):
    """(where, line) of a text file, where = 'path:line'."""
    rel = path.relative_to(ROOT).as_posix()
    return [(f"{rel}:{i}", line) for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)]


def notebook_lines(path):
    """(where, line) of a notebook's cell sources (markdown and code), where = 'path cell K line L' (K, L from 1)."""
    rel = path.relative_to(ROOT).as_posix()
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    out = []
    for k, cell in enumerate(cells, 1):
        if cell.get("cell_type") not in ("markdown", "code"):
            continue
        source = cell["source"] if isinstance(cell["source"], str) else "".join(cell["source"])
        out += [(f"{rel} cell {k} line {i}", line) for i, line in enumerate(source.splitlines(), 1)]
    return out


def report(lines, exempt=None):
    """Lines 'where: kind: match | the line' of every finding."""
    return [f"{where}: {kind}: {hit!r} | {line.strip()[:160]}" for where, line in lines
            if not (exempt and exempt(line)) for kind, hit in findings(line)]


def test_package_describes_the_present():
    files = package_files()
    assert any(p.name == "__init__.py" for p in files)
    bad = report([entry for p in files for entry in text_lines(p)])
    assert not bad, "history in the package:\n" + "\n".join(bad)


def test_readme_describes_the_present():
    bad = report(text_lines(ROOT / "README.md"))
    assert not bad, "history in README.md:\n" + "\n".join(bad)


def test_changelog_carries_history_only_in_release_headings():
    path = ROOT / "CHANGELOG.md"
    if not path.exists():
        pytest.skip("no CHANGELOG.md")
    bad = report(text_lines(path), exempt=RELEASE_HEADING.match)
    assert not bad, "history in CHANGELOG.md outside its release headings:\n" + "\n".join(bad)


def test_notebooks_describe_the_present():
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    bad = report([entry for p in notebooks for entry in notebook_lines(p)])
    assert not bad, "history in the notebooks:\n" + "\n".join(bad)
