"""Files written whole or not at all: write to a temporary file beside the target, then rename."""
import os
import tempfile
from contextlib import contextmanager

__all__ = ["atomic_path"]


@contextmanager
def atomic_path(path):
    """Yield a temporary path in the target's folder; on success it replaces `path` atomically, on error
    it is removed and `path` is left untouched. An OSError about the temporary file (a missing folder, no
    permission, a full disk, a folder of the target's name) is raised about `path`, the file asked for."""
    folder = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=os.path.splitext(path)[1], dir=folder)
    except OSError as err:
        raise about(err, path) from None
    os.close(fd)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException as err:
        if os.path.exists(tmp):
            os.remove(tmp)
        if isinstance(err, OSError) and err.errno is not None and err.filename == tmp:
            raise about(err, path) from None
        raise


def about(err, path):
    """The OSError err (its type, number and reason) about path."""
    return type(err)(err.errno, err.strerror, os.fspath(path))


def check_out_file(out_file):
    """ValueError naming --out when out_file cannot be written: a folder of that name, or a file where one of the
    folders above it would be (a missing folder is created when the file is written)."""
    path = os.path.abspath(out_file)
    if os.path.isdir(path):
        raise ValueError(f"--out {out_file}: a folder of that name exists; give a file name")
    _check_above(out_file, path)
    return out_file


def check_out_dir(out_dir):
    """ValueError naming --out when out_dir cannot be the job's folder: a file of that name, or a file where one
    of the folders above it would be (a missing folder is created by the run)."""
    path = os.path.abspath(out_dir)
    if os.path.exists(path) and not os.path.isdir(path):
        raise ValueError(f"--out {out_dir}: a file of that name exists; give a folder (created if missing)")
    _check_above(out_dir, path)
    return out_dir


def _check_above(given, path):
    """ValueError naming --out (as given) when the nearest existing folder above path is a file."""
    above = os.path.dirname(path)
    while not os.path.exists(above):
        above = os.path.dirname(above)
    if not os.path.isdir(above):
        raise ValueError(f"--out {given}: {above} is a file, so no folder can be made below it")
