"""The first run after an install (spatialkin.cli.firstrun): when the cache is ready, the line while kernels
compile, and the interpreted run giving the same table as the compiled one (oracle: the compiled job)."""
import json
import sys

import numpy as np
import pytest

from spatialkin._lib import jit as _jit
from spatialkin.cli import firstrun
from spatialkin.cli import FIRST_RUN, main


def test_ready_needs_a_stamp_of_these_versions_naming_every_index_of_the_same_source(tmp_path, monkeypatch):
    monkeypatch.setattr(firstrun, "cache_folder", lambda: str(tmp_path))
    assert not firstrun.ready()
    source, index = tmp_path / "k.py", tmp_path / "k.nbi"
    source.write_text("x = 1\n")
    index.write_text("i")
    stamp = {"versions": firstrun._versions(), "indexes": [[str(index), str(source), firstrun.source_hash(source)]]}
    (tmp_path / firstrun.STAMP_NAME).write_text(json.dumps(stamp))
    assert firstrun.ready()
    source.write_text("x = 2\n")                  # the kernel edited after the warm-up: its index is stale
    assert not firstrun.ready()
    source.write_text("x = 1\n")                  # back to the same source (numba compares content, not time)
    assert firstrun.ready()
    index.unlink()                                # the cache cleared
    assert not firstrun.ready()
    index.write_text("i")
    stamp["versions"] = {**stamp["versions"], "numba": "0.0"}
    (tmp_path / firstrun.STAMP_NAME).write_text(json.dumps(stamp))
    assert not firstrun.ready()


def test_cold_cache_takes_the_interpreted_path(monkeypatch, capsys, tmp_path):
    calls = []
    monkeypatch.setenv(firstrun.ENV, "interpret")
    monkeypatch.setattr(firstrun, "ready", lambda: False)
    monkeypatch.setattr(firstrun, "start_background", lambda: calls.append("background") or True)
    monkeypatch.setattr(firstrun, "run_interpreted", lambda argv: calls.append(argv) or 0)
    out = str(tmp_path / "somewhere")
    assert main(["looper", "--out", out]) == 0
    assert calls == [["looper", "--out", out], "background"]     # the warm-up starts after the run
    assert FIRST_RUN in capsys.readouterr().err
    bad = tmp_path / "bad.toml"                   # bad input on a first run: still its one line, nothing started
    bad.write_text("crank_radius = -1\n")
    calls.clear()
    assert main(["looper", "--out", out, "--config", str(bad)]) == 2
    err = capsys.readouterr().err
    assert calls == [] and len(err.strip().splitlines()) == 1 and "crank_radius" in err


def test_interpreted_run_gives_the_compiled_table(tmp_path):
    cfg = tmp_path / "coarse.toml"
    cfg.write_text("step_deg = 1.0\n")
    assert main(["looper", "--out", str(tmp_path / "compiled"), "--config", str(cfg)]) == 0
    assert firstrun.run_interpreted(["looper", "--out", str(tmp_path / "plain"), "--config", str(cfg)]) == 0
    a = np.loadtxt(tmp_path / "compiled" / "looper_motion.csv", delimiter=",", skiprows=1)
    b = np.loadtxt(tmp_path / "plain" / "looper_motion.csv", delimiter=",", skiprows=1)
    # the same arithmetic in the same order: bitwise equal here; allow round-off should a libm differ
    np.testing.assert_allclose(b, a, rtol=1e-13, atol=1e-13 * np.max(np.abs(a)))


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


def test_import_compiles_nothing():
    """A fresh interpreter imports spatialkin, planar and the job without a single compile event."""
    import subprocess
    code = ("from numba.core import event\nhits = []\n"
            "class L(event.Listener):\n    def on_start(self, e): hits.append(1)\n    def on_end(self, e): pass\n"
            "event.register('numba:compile', L())\n"
            "import spatialkin, planar, spatialkin.cli.looper_job, spatialkin.mechanisms, spatialkin.cli\n"
            "print(len(hits))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "0"
