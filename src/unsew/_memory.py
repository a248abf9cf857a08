"""Process memory figures for metrics.json and the benchmarks: peak and current resident set.

Linux reports the peak resident set (VmHWM, also ``getrusage``'s ru_maxrss) and lets a process
reset it (writing 5 to /proc/self/clear_refs), so a stage's own peak can be measured in-process.
Elsewhere the functions fall back to ``resource.getrusage`` (peak since start) or return None.

:func:`bound_heap` and :func:`release_free_memory` keep glibc's heap from holding on to memory
the fit has freed; they do nothing elsewhere.
"""

from __future__ import annotations

import sys

__all__ = ["peak_rss_mb", "current_rss_mb", "reset_peak", "bound_heap", "release_free_memory"]

#: Blocks at least this large are mapped and unmapped on their own, never kept in the heap [bytes].
MMAP_THRESHOLD = 4 << 20
#: At most this many malloc arenas (glibc's default is 8 per core, each keeping its free blocks).
ARENA_MAX = 2
_M_MMAP_THRESHOLD, _M_ARENA_MAX = -3, -8  # mallopt parameters (glibc malloc.h)


def _status_kb(field: str) -> int | None:
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def peak_rss_mb() -> float | None:
    """Peak resident memory of this process [MB] since start (or since :func:`reset_peak`)."""
    kb = _status_kb("VmHWM")
    if kb is not None:
        return kb / 1024.0
    try:
        import resource

        r = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return r / 2**20 if sys.platform == "darwin" else r / 1024.0  # bytes on macOS, kB on Linux
    except (ImportError, OSError):
        return None


def current_rss_mb() -> float | None:
    """Resident memory of this process now [MB], or None where unknown."""
    kb = _status_kb("VmRSS")
    return None if kb is None else kb / 1024.0


def reset_peak() -> bool:
    """Reset the peak to the current resident memory (Linux); False where not supported."""
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
        return True
    except OSError:
        return False


def _glibc():
    if not sys.platform.startswith("linux"):
        return None
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6")
        return libc if hasattr(libc, "mallopt") and hasattr(libc, "malloc_trim") else None
    except OSError:
        return None


def bound_heap() -> bool:
    """Fix glibc malloc's mmap threshold at :data:`MMAP_THRESHOLD` and its arenas at
    :data:`ARENA_MAX` for this process. glibc otherwise raises the threshold to the size of the
    largest block freed (up to 32 MB), after which such blocks come from the heap and stay there
    when freed, and gives threads arenas of their own; either can keep memory the fit freed long
    ago. The arena limit only binds threads that start afterwards: call it first thing (the CLI
    does). Returns False where not glibc."""
    libc = _glibc()
    if libc is None:
        return False
    return bool(libc.mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
        libc.mallopt(_M_ARENA_MAX, ARENA_MAX)
    )


def release_free_memory() -> bool:
    """Give the heap's free pages back to the system (glibc ``malloc_trim(0)``); False elsewhere."""
    libc = _glibc()
    if libc is None:
        return False
    libc.malloc_trim(0)
    return True
