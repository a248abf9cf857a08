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
    _CHOLMOD = [
        pytest.param("cholmod", marks=pytest.mark.skip(reason="scikit-sparse not installed (unsew[cholmod])"))
    ]

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

    def f(w_, b_):
        return sparse_solve(_values(p, w_), b_, p, backend=backend)

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
        sparse_solve(
            torch.tensor([1.0, 2.0, 1.0], dtype=torch.float64),
            torch.ones(2, dtype=torch.float64),
            p,
            backend=backend,
        )


@pytest.mark.parametrize("backend", ALL_BACKENDS)
def test_factor_once_solve_twice(backend, monkeypatch):
    """Every backend factorizes A once in the forward solve and answers the adjoint solve of the
    backward pass with that same factorization (STYLE.md habit 5): one factorization, two solves."""
    import unsew.sim.solve as solve_mod

    factors, solves = [], []
    orig_init, orig_solve = solve_mod._Factor.__init__, solve_mod._Factor.solve

    def counting_init(self, *a, **k):
        factors.append(self)
        orig_init(self, *a, **k)

    def counting_solve(self, rhs):
        solves.append(self)
        return orig_solve(self, rhs)

    monkeypatch.setattr(solve_mod._Factor, "__init__", counting_init)
    monkeypatch.setattr(solve_mod._Factor, "solve", counting_solve)
    p = _pattern()
    g = torch.Generator().manual_seed(3)
    w = torch.randn(p.rows.shape[0], generator=g, dtype=torch.float64).requires_grad_()
    b = torch.randn(N, generator=g, dtype=torch.float64).requires_grad_()
    x = sparse_solve(_values(p, w), b, p, backend=backend)
    assert len(factors) == 1 and len(solves) == 1
    x.sum().backward()
    assert len(factors) == 1, "the backward pass factorized again"
    assert solves == [factors[0], factors[0]]  # the adjoint solve used the forward's factor
    assert w.grad is not None and b.grad is not None


@pytest.mark.parametrize("fused", [True, False])
def test_a_differentiable_drape_factorizes_once_per_step(fused, monkeypatch):
    """Through a whole drape and its backward pass (fused step Function or separate assembly +
    sparse_solve): one factorization per step, reused by that step's adjoint solve."""
    import numpy as np

    import unsew.sim.solve as solve_mod
    import unsew.sim.step_solve as step_mod
    from unsew.sim import MATERIALS, Cloth, DrapeSettings, PlaneSDF, SimModel, SimState, drape
    from unsew.sim.meshes import grid_sheet

    counts = {"factor": 0, "solve": 0}
    orig_init, orig_solve = solve_mod._Factor.__init__, solve_mod._Factor.solve

    def counting_init(self, *a, **k):
        counts["factor"] += 1
        orig_init(self, *a, **k)

    def counting_solve(self, rhs):
        counts["solve"] += 1
        return orig_solve(self, rhs)

    monkeypatch.setattr(solve_mod._Factor, "__init__", counting_init)
    monkeypatch.setattr(solve_mod._Factor, "solve", counting_solve)
    assert step_mod._Factor is solve_mod._Factor
    uv, f = grid_sheet(3, 3, 0.1, 0.1)
    m = SimModel.build(f, f)
    x = np.c_[uv[:, 0], np.full(len(uv), 0.05), uv[:, 1]]
    uvt = torch.as_tensor(uv).clone().requires_grad_()
    out = drape(
        m,
        SimState.at_rest(x),
        PlaneSDF((0, -1, 0)),
        Cloth(uvt, MATERIALS["cotton"].gamma(), 0.1),
        steps=3,
        settings=DrapeSettings(fused=fused, backend="cholespy"),
    )
    assert counts == {"factor": 3, "solve": 3}
    out.x.sum().backward()
    assert counts == {"factor": 3, "solve": 6}
    assert uvt.grad is not None


@pytest.mark.parametrize("mode", ["simplicial", "supernodal"])
@pytest.mark.parametrize("backend", _CHOLMOD)
def test_cholmod_symbolic_analysis_is_reused_across_values(backend, mode, monkeypatch):
    """The cholmod backend analyses the pattern once per mode; new values on the same pattern
    solve right."""
    import unsew.sim.solve as solve_mod

    monkeypatch.setattr(solve_mod, "CHOLMOD_MODE", mode)
    p = _pattern()
    g = torch.Generator().manual_seed(2)
    first = None
    for k in range(3):
        w = torch.randn(p.rows.shape[0], generator=g, dtype=torch.float64)
        b = torch.randn(N, generator=g, dtype=torch.float64)
        x = sparse_solve(_values(p, w), b, p, backend=backend)
        assert_close(
            x, torch.linalg.solve(p.dense(_values(p, w)), b), rtol=1e-12, atol=1e-14, what=f"values {k} "
        )
        first = first or p._cholmod_symbolic[mode]
        assert list(p._cholmod_symbolic) == [mode]
        assert p._cholmod_symbolic[mode] is first is not None


@pytest.mark.parametrize("mode", ["simplicial", "supernodal"])
@pytest.mark.parametrize("backend", _CHOLMOD)
def test_cholmod_refuses_an_indefinite_matrix_in_either_mode(backend, mode, monkeypatch):
    """A symmetric matrix with one negative eigenvalue among positive ones (its leading minors
    positive until the last) is refused in both modes: simplicial LDL' factors it without a
    complaint, so its pivots are what tell."""
    import unsew.sim.solve as solve_mod
    from unsew.errors import SimulationError

    monkeypatch.setattr(solve_mod, "CHOLMOD_MODE", mode)
    p = SparsePattern(3, [0, 1, 1, 2, 2], [0, 0, 1, 1, 2])
    values = torch.tensor([2.0, 1.0, 2.0, 3.0, 2.0], dtype=torch.float64)  # det -9.0
    assert torch.linalg.eigvalsh(p.dense(values)).min() < 0
    with pytest.raises(SimulationError, match="not positive definite"):
        sparse_solve(values, torch.ones(3, dtype=torch.float64), p, backend=backend)


def test_unknown_backend_is_refused():
    with pytest.raises(ValueError, match="unknown solver backend"):
        resolve_backend("mkl")
