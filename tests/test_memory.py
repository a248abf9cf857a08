"""unsew._memory: the peak and current resident memory, and glibc's heap handed back."""

import sys

import numpy as np
import pytest

from unsew._memory import current_rss_mb, peak_rss_mb

linux = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")


@linux
def test_peak_is_at_least_current_and_sees_a_large_array():
    before = peak_rss_mb()
    a = np.ones(40 * 2**20 // 8)  # 40 MB, touched
    assert current_rss_mb() <= peak_rss_mb()
    assert peak_rss_mb() >= before
    assert peak_rss_mb() >= current_rss_mb() - 1e-9
    del a


_FREE_16MB = """
import sys, numpy as np
from unsew._memory import bound_heap, current_rss_mb
ok = bound_heap()
rss0 = current_rss_mb()
for _ in range(3):
    a = np.ones(16 * 2**20 // 8)  # 16 MB, touched, freed
    del a
print(ok, current_rss_mb() - rss0)
"""


@linux
def test_bound_heap_gives_a_freed_16mb_block_back():
    """With the mmap threshold fixed at 4 MB a freed 16 MB block leaves the process at once
    (glibc's own threshold rises to 16 MB after the first such free, and the later blocks then
    stay in the heap: +16 MB resident). A fresh process, so no earlier test moved the threshold."""
    import os
    import subprocess

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    out = subprocess.run(
        [sys.executable, "-c", _FREE_16MB], capture_output=True, text=True, env=env, check=True
    )
    ok, grown = out.stdout.split()
    if ok != "True":
        pytest.skip("not glibc")
    assert float(grown) < 4.0, f"{grown} MB still resident after freeing"
