"""The kernels' first use on a machine (spatialkin._lib.warm, spatialkin._lib.jit): when the cache is warm, the
kernels switched between their compiled and plain Python forms in place, a cold start in a fresh process (plain
Python at once, one line, a background warm-up), the line while kernels compile, no compiling at import, and none
after `spatialkin warmup` on pairs its workload never saw.

Oracles: closed forms (two spheres meet in a circle of radius sqrt(3)/2; the looper drive's ball centre on both
surfaces), the compiled results and numba's compile events."""
import json
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import spatialkin as sk
from spatialkin._lib import jit as _jit
from spatialkin._lib import warm
from spatialkin.mechanisms import LooperDrive
from tests import suite_warmup

#: Interpreted and compiled kernels: the same arithmetic; allow round-off should the compiler contract a product.
SAME = 1e-12


def test_ready_needs_a_stamp_of_these_versions_naming_every_index_of_the_same_source(tmp_path, monkeypatch):
    monkeypatch.setattr(warm, "cache_folder", lambda: str(tmp_path))
    assert not warm.ready()
    source, index = tmp_path / "k.py", tmp_path / "k.nbi"
    source.write_text("x = 1\n")
    index.write_text("i")
    stamp = {"versions": warm.versions(), "kernels": warm.kernels_digest(),
             "indexes": [[str(index), str(source), warm.source_hash(source)]]}
    (tmp_path / warm.STAMP.format(warm.WORKLOAD)).write_text(json.dumps(stamp))
    assert warm.ready()
    assert not warm.ready("planar.warmup")        # each workload its own stamp
    source.write_text("x = 2\n")                  # the kernel edited after the warm-up: its index is stale
    assert not warm.ready()
    source.write_text("x = 1\n")                  # back to the same source (numba compares content, not time)
    assert warm.ready()
    index.unlink()                                # the cache cleared
    assert not warm.ready()
    index.write_text("i")
    stamp["versions"] = {**stamp["versions"], "numba": "0.0"}
    (tmp_path / warm.STAMP.format(warm.WORKLOAD)).write_text(json.dumps(stamp))
    assert not warm.ready()


def test_a_change_to_any_kernel_module_drops_every_index_of_its_folders(tmp_path, monkeypatch):
    """A kernel inlines kernels of other modules (the engine's right-hand side, the small LU solvers), and numba
    checks a cached kernel against its own module only: a stamp whose kernels digest is not the current one is not
    ready, and drop_stale removes every index in the folders of the kernels it names or that are registered (a
    callee's too), and the stamp; a current stamp keeps them, and other folders are left alone."""
    cache, kernels, other = tmp_path / "cache", tmp_path / "kernels", tmp_path / "other"
    for folder in (cache, kernels, other):
        folder.mkdir()
    monkeypatch.setattr(warm, "cache_folder", lambda: str(cache))
    monkeypatch.setattr(warm, "kernel_folders", lambda package: {str(kernels)} if package == "spatialkin" else set())
    assert warm.drop_stale() == 0                 # no stamp: nothing to drop
    source = tmp_path / "k.py"
    source.write_text("x = 1\n")
    stamped = [cache / "k.f-1.py311.nbi", cache / "k.g-9.py311.nbi"]
    callee, elsewhere = kernels / "m.h-3.py311.nbi", other / "n.i-4.py311.nbi"
    data = cache / "k.f-1.py311.1.nbc"
    for path in stamped + [callee, elsewhere, data]:
        path.write_text("i")
    entries = [[str(index), str(source), warm.source_hash(source)] for index in stamped]
    stamp_path = cache / warm.STAMP.format(warm.WORKLOAD)
    stamp_path.write_text(json.dumps({"versions": warm.versions(), "kernels": warm.kernels_digest(),
                                      "indexes": entries}))
    assert warm.ready() and warm.drop_stale() == 0
    assert all(path.exists() for path in stamped + [callee, elsewhere]) and stamp_path.exists()
    stamp_path.write_text(json.dumps({"versions": warm.versions(), "kernels": "0" * 64, "indexes": entries}))
    assert not warm.ready()
    assert warm.drop_stale() == 3
    assert not any(path.exists() for path in stamped + [callee]) and not stamp_path.exists()
    assert elsewhere.exists() and data.exists()   # (another folder; numba's data files, unreachable without index)
    assert not warm.ready("planar.warmup") and warm.drop_stale("planar.warmup") == 0


def test_the_kernels_digest_covers_every_kernel_module(tmp_path, monkeypatch):
    """kernels_digest reads every module of spatialkin.kernels (its sources, by relative path) and the jit module: the
    digest of a copy is the same, that of the copy with one module changed differs, and so does that with the jit
    module changed too."""
    import shutil
    original = warm.kernels_digest()
    copy = tmp_path / "kernels"
    shutil.copytree(warm.KERNELS, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(warm, "KERNELS", str(copy))
    try:
        warm.kernel_hashes.cache_clear()
        assert warm.kernels_digest() == original
        with open(copy / "linalg.py", "a") as f:
            f.write("\n# changed\n")
        warm.kernel_hashes.cache_clear()
        changed = warm.kernels_digest()
        assert changed != original
        jit_copy = tmp_path / "jit.py"                 # the jit module's helpers are compiled into the kernels too
        jit_copy.write_text(open(_jit.__file__).read() + "\n# changed\n")
        monkeypatch.setattr(_jit, "__file__", str(jit_copy))
        warm.kernel_hashes.cache_clear()
        assert warm.kernels_digest() not in (original, changed)
    finally:
        warm.kernel_hashes.cache_clear()         # (the next reading is of the real folder again)
    assert len(original) == 64


def spheres_circle():
    """sk.trace of two unit spheres one radius apart: the circle of radius sqrt(3)/2 in x = 1/2."""
    return sk.trace(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))), (0.5, 0.9, 0.0))


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="one form only with jit off")
def test_the_kernels_switch_form_in_place_with_the_same_answers():
    from numba.core.registry import CPUDispatcher

    from spatialkin.kernels.march import curve as kc
    from spatialkin.tracing.march import ivp
    compiled = spheres_circle()
    motion = LooperDrive.reference().solve(np.linspace(0.0, 2 * np.pi, 37))
    try:
        _jit.use(_jit.INTERPRETED)
        assert _jit.mode() == _jit.INTERPRETED
        assert not isinstance(kc.curve_frame, CPUDispatcher) and not isinstance(ivp.kb.branch_advance, CPUDispatcher)
        plain = spheres_circle()
        plain_motion = LooperDrive.reference().solve(np.linspace(0.0, 2 * np.pi, 37))
    finally:
        _jit.use(_jit.COMPILED)
    assert isinstance(kc.curve_frame, CPUDispatcher) and isinstance(ivp.kb.branch_advance, CPUDispatcher)
    assert abs(plain.length - np.pi * np.sqrt(3.0)) < 1e-9 and abs(compiled.length - np.pi * np.sqrt(3.0)) < 1e-9
    assert abs(plain.length - compiled.length) <= SAME * compiled.length
    np.testing.assert_allclose(plain(np.linspace(0, plain.length, 9)), compiled(np.linspace(0, plain.length, 9)),
                               rtol=0, atol=SAME)
    np.testing.assert_allclose(plain_motion.ball_center, motion.ball_center, rtol=0,
                               atol=SAME * np.max(np.abs(motion.ball_center)))


def test_refresh_turns_to_compiled_once_every_workload_is_warm(monkeypatch):
    monkeypatch.setattr(warm, "ready", lambda workload=warm.WORKLOAD: True)
    monkeypatch.setattr(warm, "_STARTED", {})
    said = []
    monkeypatch.setattr(warm, "_SAY", [said.append])
    monkeypatch.setattr(warm, "_SAID", set())
    try:
        _jit.use(_jit.INTERPRETED)
        warm._LAST_POLL[0] = 0.0
        warm.refresh()
        assert _jit.mode() == _jit.COMPILED
        assert said == [warm.COLD]              # said once, at the first entry that ran plain Python
    finally:
        _jit.use(_jit.COMPILED)


COLD_START = textwrap.dedent("""
    import warnings
    warnings.simplefilter("always")
    with warnings.catch_warnings(record=True) as caught:
        import spatialkin as sk
        from spatialkin._lib import jit, warm
        curve, = sk.intersect(sk.Sphere(1.0), sk.Sphere(1.0, sk.Frame((1.0, 0.0, 0.0))), tol=1e-10)
        loops = sk.intersect(sk.Torus(2.0, 1.0), sk.Sphere(1.2, sk.Frame((2.5, 0.0, 0.3))))
    started = warm._STARTED.get(warm.WORKLOAD)
    print(jit.mode(), started.pid if started else -1, sorted(round(c.length, 9) for c in loops))
    print(sum(str(w.message) == warm.COLD for w in caught))
    print(*{w.filename for w in caught if str(w.message) == warm.COLD})
""")


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no cache with jit off")
def test_a_cold_cache_runs_plain_python_at_once_and_warms_in_the_background(tmp_path):
    """A fresh process on an empty cache: the kernels run as plain Python (nothing compiles in the foreground), the
    answers are the compiled process's, one warning says so, and a background warm-up is running (stopped here)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env.pop(warm.ENV, None)
    run = subprocess.run([sys.executable, "-c", COLD_START], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    first, second, where = run.stdout.strip().splitlines()
    mode, pid, lengths = first.split(" ", 2)
    try:
        assert mode == _jit.INTERPRETED and int(pid) > 0
        want = sorted(round(c.length, 9) for c in sk.intersect(sk.Torus(2.0, 1.0), sk.Sphere(1.2, sk.Frame(
            (2.5, 0.0, 0.3)))))
        assert lengths == str(want)
        assert second == "1"
        assert where == "<string>"              # the warning names the user's line, not spatialkin's or numba's
    finally:
        if int(pid) > 0:
            try:
                os.killpg(int(pid), signal.SIGKILL)
            except ProcessLookupError:
                pass


def test_workloads_are_spatialkins_then_each_installed_packages():
    assert warm.workloads()[:2] == [warm.WORKLOAD, "planar.warmup"]


def test_a_benchmark_compiles_first_unless_every_workload_is_warm(monkeypatch):
    """compiled_for_timing: nothing said or compiled where the kernels are compiled and every workload is warm;
    else one line, then compile_ahead of every workload."""
    said, compiled = [], []
    monkeypatch.setattr(warm, "compile_ahead", lambda: compiled.append(1) or {"w": 2.5})
    monkeypatch.setattr(warm.jit, "mode", lambda: warm.jit.COMPILED)
    monkeypatch.setattr(warm, "ready", lambda workload: True)
    assert warm.compiled_for_timing(said.append) == 0.0 and said == [] and compiled == []
    monkeypatch.setattr(warm, "ready", lambda workload: workload != "planar.warmup")
    if not _jit.JIT_DISABLED:
        assert warm.compiled_for_timing(said.append) == 2.5 and len(said) == 1 and compiled == [1]
        assert "compiling the kernels first" in said[0]


def test_the_background_warm_up_imports_the_packages_this_process_imported(tmp_path):
    """A child started as the background warm-up is (python -c, the prelude first) in a folder that holds other
    copies of spatialkin and planar (a source checkout beside an installed package) imports this process's copies:
    numba keys its cache by the kernels' source files, so the other copies' kernels would never be looked up."""
    import planar
    for name in ("spatialkin", "planar"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "__init__.py").write_text("raise ImportError('the copy in the working folder')\n")
    code = warm.prelude("planar.warmup") + "import spatialkin, planar; print(spatialkin.__file__); print(planar.__file__)"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.split() == [os.path.abspath(sk.__file__), os.path.abspath(planar.__file__)]
    bare = subprocess.run([sys.executable, "-c", "import spatialkin"], capture_output=True, text=True, cwd=tmp_path)
    assert "the copy in the working folder" in bare.stderr          # (without the prelude, the decoy is found)


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no compiling with jit off")
def test_a_line_when_the_first_kernel_compiles():
    said = []
    listener = _jit.announce_compilation(lambda: said.append(1))
    try:
        space = {"__name__": "spatialkin._first_compile_probe"}
        exec("def probe(x):\n    return x + 1.0\n\ndef probe2(x):\n    return x * 2.0\n", space)
        assert _jit.jit(cache=False)(space["probe"])(1.0) == 2.0
        assert _jit.jit(cache=False)(space["probe2"])(1.0) == 2.0
    finally:
        from numba.core import event
        event.unregister("numba:compile", listener)
    assert said == [1]                      # once, however many kernels compile


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no compiling with jit off")
def test_the_compiling_warning_names_the_users_line(monkeypatch):
    """The line said while a kernel compiles is a RuntimeWarning naming the call that made it compile (this file),
    not a frame of numba's events (contextlib) or of spatialkin."""
    import functools
    import warnings
    monkeypatch.setattr(warm, "_SAID", set())
    monkeypatch.setattr(warm, "_SAY", [None])
    listener = _jit.announce_compilation(functools.partial(warm._say, warm.COMPILING))
    space = {"__name__": "spatialkin._warning_probe"}
    exec("def probe(x):\n    return x + 3.0\n", space)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            assert _jit.jit(cache=False)(space["probe"])(1.0) == 4.0
    finally:
        from numba.core import event
        event.unregister("numba:compile", listener)
    said = [w for w in caught if str(w.message) == warm.COMPILING]
    assert len(said) == 1 and said[0].category is RuntimeWarning
    assert os.path.abspath(said[0].filename) == os.path.abspath(__file__)


def test_import_compiles_nothing():
    """A fresh interpreter imports spatialkin, planar and the job without a single compile event."""
    code = ("from numba.core import event\nhits = []\n"
            "class L(event.Listener):\n    def on_start(self, e): hits.append(1)\n    def on_end(self, e): pass\n"
            "event.register('numba:compile', L())\n"
            "import spatialkin, planar, spatialkin.cli.looper_job, spatialkin.mechanisms, spatialkin.cli\n"
            "print(len(hits))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "0"


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no cache with jit off")
def test_the_looper_job_on_a_cold_cache_says_so_once_and_gives_the_compiled_table(tmp_path):
    """`spatialkin looper` on an empty cache: one line on stderr, exit 0, and the table of the compiled job (run here,
    on the warm cache) to round-off."""
    from spatialkin.cli import main
    cfg = tmp_path / "coarse.toml"
    cfg.write_text("step_deg = 1.0\n")
    assert main(["looper", "--out", str(tmp_path / "compiled"), "--config", str(cfg)]) == 0
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env.pop(warm.ENV, None)
    code = ("import sys\nfrom spatialkin.cli import main\nfrom spatialkin._lib import warm\n"
            f"status = main(['looper', '--out', {str(tmp_path / 'plain')!r}, '--config', {str(cfg)!r}])\n"
            "print('background:', *[p.pid for p in warm._STARTED.values()])\nsys.exit(status)\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    for pid in run.stdout.strip().splitlines()[-1].split()[1:]:
        try:
            os.killpg(int(pid), signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stderr.count(warm.COLD) == 1 and warm.COMPILING not in run.stderr
    a = np.loadtxt(tmp_path / "compiled" / "looper_motion.csv", delimiter=",", skiprows=1)
    b = np.loadtxt(tmp_path / "plain" / "looper_motion.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(b, a, rtol=1e-13, atol=1e-13 * np.max(np.abs(a)))


#: Every how many-th stress case the warm-up's coverage is tried on (all of them take a minute).
COVERAGE_STRIDE = 4

#: A user's calls on pairs the warm-up's workload never saw, in a fresh process: prints whether the cache is stamped
#: warm, the kernels that compiled (numba's compile events), and the specialisations the process then holds.
USERS_CALLS = suite_warmup.COMPILES + textwrap.dedent(f"""
    import numpy as np
    import spatialkin as sk
    from spatialkin._lib import warm
    print(warm.ready(warm.WORKLOAD) and warm.ready("planar.warmup"))
    from tests.oracles.ssi_cases import all_cases
    for case in all_cases()[::{COVERAGE_STRIDE}]:
        for certify in (False, True):
            try:
                curves = sk.intersect(case.a, case.b, certify=certify)
            except (sk.TopologyError, ValueError):
                continue
            for curve in curves:
                if curve.length > 0:
                    curve(np.linspace(0.0, curve.length, 3))
                    curve.closest(curve.points[:2])
    import math
    turned = sk.rotation_about((1, 0, 0), math.asin(0.5))         # (the hard cases of the notebooks)
    for a, b in [(sk.Torus(2.0, 1.0), sk.Plane(sk.Frame((0, 0, 0), turned))),
                 (sk.Sphere(1.0), sk.Cylinder(0.5, sk.Frame((0.5, 0, 0)), v_range=(-1.5, 1.5))),
                 (sk.Cylinder(1.0, v_range=(-2, 2)), sk.Cylinder(1.0, sk.Frame((0, 0, 0), sk.rotation_about(
                     (0, 1, 0), math.pi / 2)), v_range=(-2, 2))),
                 (sk.Torus(2.0, 0.5), sk.Plane(sk.Frame((0, 0, 0.5)))),
                 (sk.Torus(8.0, 50.0), sk.Sphere(0.5, sk.Frame((58.5, 0, 0))))]:
        sk.intersect(a, b)
    import planar
    from planar.frenet import figures
    planar.examples.fnf_sixbar().solve(np.linspace(0.0, 2 * np.pi, 361))
    for law in (planar.CrankSlider(k=0.5, e=1.0, L=4.0), planar.CrankRocker(k=0.5, d=4.0)):
        link = planar.DrivenLink(law, omega=1.0)
        figures.positions(link, [0.0, 4.0], count=3, samples=31)
        link.velocity(np.linspace(0.0, 4.0, 5), -4.0), link.acceleration(np.linspace(0.0, 4.0, 5), 2.0)
    print(sorted(compiled))
""") + suite_warmup.SPECIALISATIONS


@pytest.mark.skipif(_jit.JIT_DISABLED, reason="no cache with jit off")
def test_after_spatialkin_warmup_the_stress_cases_compile_nothing(tmp_path):
    """`spatialkin warmup` (a process per workload; it reports, and leaves the cache stamped warm for its workload and
    planar's, an installed package's); then, in a fresh one, a user's calls on pairs the workload never saw (every
    COVERAGE_STRIDE-th stress case: with and without certify=True, then a dense evaluation and closest points of each
    curve; the notebooks' hard cases) and planar's six-link over a turn and driven links in the Frenet trihedron (the
    notebook's figures) compile no kernel of spatialkin or planar, and need no specialisation the warm-up did not
    make: each would load from a cache that only the warm-up wrote.

    The warm-up is the session's (tests/conftest.py runs it on a cold cache before any test), or one run here on an
    empty cache of its own: either compiled every specialisation it left in the cache (its record is complete). The
    user's calls run on the suite's cache, which the other tests may have added specialisations to: those would load
    without a compile event, and are caught by the comparison with the warm-up's own. Oracles: numba's compile events
    (none for a kernel loaded from its cache) and the specialisations each process holds."""
    warmed = suite_warmup.recorded()
    if warmed is None or not warmed["complete"]:
        warmed = suite_warmup.warm_up({**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")})
    assert warmed["complete"]
    assert warmed["report"].startswith("spatialkin warmup: ") and "kernel specialisations ready" in warmed["report"]
    out = subprocess.run([sys.executable, "-c", USERS_CALLS], capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stderr[-2000:]
    stamped, *_, compiled, held = out.stdout.strip().splitlines()
    assert stamped == "True" and compiled == "[]"
    assert sorted(set(json.loads(held)) - set(warmed["specialisations"])) == []
