"""Files written whole or not at all, and errors about the file asked for (never its temporary file)."""
import os

import pytest

from spatialkin._lib.files import atomic_path


def test_a_file_is_written_whole_or_not_at_all(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp, open(tmp, "w") as fh:
            fh.write("half")
            raise RuntimeError("stopped")
    assert target.read_text() == "old" and os.listdir(tmp_path) == ["a.txt"]
    with atomic_path(target) as tmp, open(tmp, "w") as fh:
        fh.write("new")
    assert target.read_text() == "new" and os.listdir(tmp_path) == ["a.txt"]


def test_errors_name_the_path_asked_for(tmp_path):
    """A missing folder, a folder of the target's name, and an error raised about the temporary file while it is
    written: each raised as the same OSError about the target, no temporary file left."""
    missing = tmp_path / "no" / "such" / "x.csv"
    with pytest.raises(FileNotFoundError) as caught:
        with atomic_path(missing):
            pass
    assert caught.value.filename == str(missing) and str(missing) in str(caught.value)
    folder = tmp_path / "taken.csv"
    folder.mkdir()
    with pytest.raises(IsADirectoryError) as caught:
        with atomic_path(folder) as tmp, open(tmp, "w") as fh:
            fh.write("x")
    assert caught.value.filename == str(folder)
    target = tmp_path / "full.csv"
    with pytest.raises(OSError) as caught:
        with atomic_path(target) as tmp:
            raise OSError(28, "No space left on device", tmp)
    assert caught.value.errno == 28 and caught.value.filename == str(target)
    with pytest.raises(OSError) as caught:          # an error about another file is left as it is
        with atomic_path(target):
            raise OSError(2, "No such file or directory", "elsewhere")
    assert caught.value.filename == "elsewhere"
    assert sorted(os.listdir(tmp_path)) == ["taken.csv"]
