"""The sparse solve Function: gradcheck in float64 through a symmetric parametrisation,
and agreement with dense torch.linalg.solve."""

import pytest
import torch
from helpers import assert_close

from unsew.sim.solve import SparsePattern, resolve_backend, sparse_solve

N = 6

try:
    import sksparse.cholmod  # noqa: F401

    _CHOLMOD = [pytest.param("cholmod")]
except ImportError:  # the optional extra
    _CHOLMOD = [pytest.param("cholmod", marks=pytest.mark.skip(reason="scikit-sparse not installed (unsew[cholmod])"))]

ALL_BACKENDS = ["cholespy", "scipy", *_CHOLMOD]


def _pattern():
    # a banded lower triangle plus one far entry
    rows, cols = [], []
    for i in range(N):
        for j in range(max(0, i - 2), i + 1):
            rows.append(i)
            cols.append(j)
    rows.append(N - 1)
    cols.append(0)
    return SparsePattern(N, rows, cols)


def _values(p: SparsePattern, w: torch.Tensor) -> torch.Tensor:
    """Lower values of the SPD matrix A = S(w) + N I, S symmetric with S's lower entries = w."""
    return w + N * (p.rows == p.cols).to(w.dtype)


@pytest.mark.parametrize("backend", ALL_BACKENDS)
def test_gradcheck_sparse_solve(backend):
    p = _pattern()
    g = torch.Generator().manual_seed(0)
    w = torch.randn(p.rows.shape[0], generator=g, dtype=torch.float64).requires_grad_()
    b = torch.randn(N, generator=g, dtype=torch.float64).requires_grad_()
    f = lambda w_, b_: sparse_solve(_values(p, w_), b_, p, backend=backend)
    assert torch.autograd.gradcheck(f, (w, b), eps=1e-6, atol=1e-8, rtol=1e-6)


@pytest.mark.parametrize("backend", ALL_BACKENDS)
def test_matches_dense_solve_and_its_autograd(backend):
    p = _pattern()
    g = torch.Generator().manual_seed(1)
    w = torch.randn(p.rows.shape[0], generator=g, dtype=torch.float64).requires_grad_()
    b = torch.randn(N, generator=g, dtype=torch.float64).requires_grad_()
    c = torch.randn(N, generator=g, dtype=torch.float64)
    x = sparse_solve(_values(p, w), b, p, backend=backend)
    gw, gb = torch.autograd.grad((x * c).sum(), (w, b))
    xr = torch.linalg.solve(p.dense(_values(p, w)), b)  # plain autograd reference
    gwr, gbr = torch.autograd.grad((xr * c).sum(), (w, b))
    assert_close(x, xr, rtol=1e-12, atol=1e-14)
    assert_close(gw, gwr, rtol=1e-10, atol=1e-14)
    assert_close(gb, gbr, rtol=1e-10, atol=1e-14)


@pytest.mark.parametrize("backend", ["cholespy", *_CHOLMOD])  # Cholesky backends (splu does not check)
def test_non_pd_matrix_raises_simulation_error(backend):
    from unsew.errors import SimulationError

    p = SparsePattern(2, [0, 1, 1], [0, 0, 1])
    with pytest.raises(SimulationError):
        sparse_solve(torch.tensor([1.0, 2.0, 1.0], dtype=torch.float64), torch.ones(2, dtype=torch.float64), p, backend=backend)


def test_symbolic_analysis_is_reused_across_values():
    """The cholmod backend analyses the pattern once; new values on the same pattern solve right."""
    p = _pattern()
    g = torch.Generator().manual_seed(2)
    for k in range(3):
        w = torch.randn(p.rows.shape[0], generator=g, dtype=torch.float64)
        b = torch.randn(N, generator=g, dtype=torch.float64)
        x = sparse_solve(_values(p, w), b, p)
        assert_close(x, torch.linalg.solve(p.dense(_values(p, w)), b), rtol=1e-12, atol=1e-14, what=f"values {k} ")
    if resolve_backend("auto") == "cholmod":
        assert p._cholmod_symbolic is not None


def test_unknown_backend_is_refused():
    with pytest.raises(ValueError, match="unknown solver backend"):
        resolve_backend("mkl")
