"""borrowed and kept (spatialkin._lib.jit): compiled code reads and writes the very arrays it borrows, an owner kept
alive holds its values while other arrays come and go, every array made is freed (numba's own allocation counts,
in a fresh process), and in Python both are the identity and a no-op; two processes saving specialisations of one
kernel to the cache at once both keep theirs."""
import os
import subprocess
import sys
import textwrap

import numba
import numpy as np
import pytest

from spatialkin._lib import jit
from spatialkin._lib.jit import borrowed, kept


@numba.njit(cache=False)
def _through_borrowed(a, pair):
    """Writes 2 * pair[1] * pair[0] + a into a through borrowed views; returns the sum read back through them."""
    b, (c, w) = borrowed((a, pair))
    for i in range(b.shape[0]):
        b[i] += 2.0 * w * c[i]
    return b.sum()


@numba.njit(cache=False)
def _owner_kept(n, rounds):
    """An owner's borrowed view filled with 0..n-1, then `rounds` other arrays made and filled with -1 (they would
    reuse the owner's memory were it freed early); the view's sum read at the end, the owner kept to there."""
    owner = np.empty(n)
    view = borrowed(owner)
    for i in range(n):
        view[i] = float(i)
    junk = 0.0
    for _ in range(rounds):
        other = np.empty(n)
        other.fill(-1.0)
        junk += other[0]
    total = view.sum()
    kept(owner)
    return total, junk


def test_borrowed_views_read_and_write_the_callers_arrays():
    """The caller's array holds what compiled code wrote through its borrowed view (against numpy's arithmetic), and
    a tuple's float passes through unchanged."""
    a = np.arange(5.0)
    c = np.linspace(1.0, 2.0, 5)
    expected = np.arange(5.0) + 2.0 * 3.0 * c
    total = _through_borrowed(a, (c, 3.0))
    np.testing.assert_array_equal(a, expected)
    assert total == expected.sum()


def test_a_kept_owner_keeps_its_values_while_other_arrays_are_made():
    """The view of a kept owner still reads 0 + 1 + ... + (n - 1) after 200 arrays of its size were made and
    filled with -1."""
    n = 64
    total, junk = _owner_kept(n, 200)
    assert total == n * (n - 1) / 2
    assert junk == -200.0


def test_borrowed_kernels_free_every_array_they_make():
    """In a fresh process with numba's allocation statistics on: 500 calls of a kernel that borrows its arguments
    and a kept array of its own leave as many frees as allocations, and the kept array is made each call."""
    script = textwrap.dedent("""
        import numba, numpy as np
        from numba.core.runtime import rtsys
        from spatialkin._lib.jit import borrowed, kept

        @numba.njit(cache=False)
        def f(a, pair):
            b, (c, w) = borrowed((a, pair))
            owner = np.empty(100)
            v = borrowed(owner)
            for i in range(b.shape[0]):
                v[i] = b[i] + w * c[i]
            total = v[:b.shape[0]].sum()
            kept(owner)
            return total

        a, c = np.arange(3.0), np.ones(3)
        f(a, (c, 2.0))
        s0 = rtsys.get_allocation_stats()
        for _ in range(500):
            f(a, (c, 2.0))
        s1 = rtsys.get_allocation_stats()
        print(s1.alloc - s0.alloc, s1.free - s0.free, s1.mi_alloc - s0.mi_alloc, s1.mi_free - s0.mi_free)
    """)
    env = dict(os.environ, NUMBA_NRT_STATS="1")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, check=True)
    alloc, free, mi_alloc, mi_free = map(int, out.stdout.split())
    assert alloc == free and mi_alloc == mi_free
    assert mi_alloc >= 500


def test_in_python_borrowed_is_the_identity_and_kept_does_nothing():
    a = np.ones(3)
    pair = (a, 1.0)
    assert borrowed(a) is a and borrowed(pair) is pair
    assert kept(a, pair) is None


#: A cached kernel in a module file of its own (numba caches only kernels whose source is a file).
RACED_KERNEL = "from spatialkin._lib.jit import jit\n\n\n@jit\ndef twice(x):\n    return x + x\n"

#: A process that compiles one specialisation of the raced kernel, numba's index write held back in between
#: (after the index was read) until the other process has read it too, or HOLD_S passed.
RACER = textwrap.dedent("""
    import os, sys, time
    from numba.core import caching
    folder, me, other = sys.argv[1:4]
    write = caching.IndexDataCacheFile._save_index
    def held(self, overloads):
        open(os.path.join(folder, me), "w").close()
        until = time.monotonic() + {hold}
        while not os.path.exists(os.path.join(folder, other)) and time.monotonic() < until:
            time.sleep(0.05)
        write(self, overloads)
    caching.IndexDataCacheFile._save_index = held
    sys.path.insert(0, folder)
    import raced
    print(raced.twice(2 if me == "a" else 2.5))
""")
#: How long a racer holds its index write for the other to read it (the lock makes the other wait this long).
HOLD_S = 8.0


def test_two_processes_saving_one_kernel_at_once_both_keep_their_specialisation(tmp_path):
    """Two processes compile different specialisations of one cached kernel at once, each reading the index before
    either writes it (numba's read-add-write would keep only the last): with the saves locked, a third process
    loads both from the cache and compiles nothing. Oracle: numba's compile events and 2 + 2, 2.5 + 2.5."""
    if jit.JIT_DISABLED or jit.fcntl is None:
        pytest.skip("no cache with jit off, no flock here")
    (tmp_path / "raced.py").write_text(RACED_KERNEL)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    code = RACER.format(hold=HOLD_S)
    racers = [subprocess.Popen([sys.executable, "-c", code, str(tmp_path), me, other], env=env, text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE) for me, other in ("ab", "ba")]
    outs = [racer.communicate(timeout=300) for racer in racers]
    assert [racer.returncode for racer in racers] == [0, 0], [err[-2000:] for _, err in outs]
    assert [out.strip() for out, _ in outs] == ["4", "5.0"]
    check = ("import sys\nfrom numba.core import event\nhits = []\n"
             "class L(event.Listener):\n    def on_start(self, e): hits.append(1)\n    def on_end(self, e): pass\n"
             "event.register('numba:compile', L())\n"
             f"sys.path.insert(0, {str(tmp_path)!r})\nimport raced\nprint(raced.twice(2), raced.twice(2.5), len(hits))\n")
    out = subprocess.run([sys.executable, "-c", check], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["4", "5.0", "0"]
