"""Process memory figures for metrics.json and the benchmarks: peak and current resident set.

Linux reports the peak resident set (VmHWM, also ``getrusage``'s ru_maxrss) and lets a process
reset it (writing 5 to /proc/self/clear_refs), so a stage's own peak can be measured in-process.
Elsewhere the functions fall back to ``resource.getrusage`` (peak since start) or return None.
"""

from __future__ import annotations

import sys

__all__ = ["peak_rss_mb", "current_rss_mb", "reset_peak"]


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
