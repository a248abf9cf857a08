"""Thread settings applied before torch is imported (see shared/STACK.md: on 2 cores torch's
OpenMP busy-waits and slows everything 10-50x when another process uses a core)."""

import os

__all__ = ["configure_threads"]


def configure_threads() -> None:
    """Set OMP_WAIT_POLICY=PASSIVE and OPENBLAS_NUM_THREADS=1 unless the user chose otherwise.
    Call before importing torch or trimesh.

    OpenBLAS spins its threads as OpenMP does. Importing trimesh loads the system's BLAS
    (libblas.so.3, OpenBLAS where Debian's libopenblas0 is installed), which starts its threads
    then, before any setting made later in the process counts; CHOLMOD (the optional solver)
    factorizes on it."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
