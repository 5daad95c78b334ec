"""Scene's docstring example runs as written (doctest, in a scratch folder: it writes its files there)."""
import doctest

from spatialkin.render import scene as scene_module


def test_the_scene_example_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    finder = doctest.DocTestFinder()
    test, = [t for t in finder.find(scene_module.Scene, "Scene") if t.name == "Scene"]
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 6
    assert (tmp_path / "curves.png").stat().st_size > 0 and (tmp_path / "curves.vtm").exists()
