"""Test configuration: one quiet torch thread pool (shared/STACK.md's threading trap), and
OpenBLAS on one thread (unsew._threads: the system's, which trimesh loads, spins as OpenMP does)."""

import os

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import pytest  # noqa: E402


@pytest.fixture(autouse=True, scope="session")
def _torch_threads():
    try:
        import torch
    except ImportError:  # pragma: no cover
        yield
        return
    torch.set_num_threads(1)
    yield
