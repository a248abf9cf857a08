"""Thread settings applied before torch is imported (see shared/STACK.md: on 2 cores torch's
OpenMP busy-waits and slows everything 10-50x when another process uses a core)."""

import os

__all__ = ["configure_threads"]


def configure_threads() -> None:
    """Set OMP_WAIT_POLICY=PASSIVE unless the user chose otherwise. Call before importing torch."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
