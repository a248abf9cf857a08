"""Sparse SPD solve as a differentiable torch Function (factor once, solve twice).

A is symmetric positive definite, (n x n), given by its LOWER triangle: COO ``rows >= cols``
and one value per stored entry (A_ij = A_ji = value for i != j). Forward: factorize A (cholespy
``CholeskySolverD``, float64; or scipy ``splu`` tuned for SPD) and solve A x = b. Backward
(adjoint, as in Liang et al. 2019 / paper 3.4.1), with the same factorization:

    lambda = A^-1 g                                 (A symmetric, so A^-T = A^-1)
    dL/db = lambda
    dL/dA_ij = -lambda_i x_j; a stored off-diagonal value stands for A_ij and A_ji, so
    dL/dvalue_ij = -(lambda_i x_j + lambda_j x_i), and dL/dvalue_ii = -lambda_i x_i.

Backends: ``"cholmod"`` (CHOLMOD through scikit-sparse, an optional extra: ``pip install
unsew[cholmod]`` against Debian's libsuitesparse-dev) analyses the sparsity pattern once (nested
dissection ordering) and keeps that symbolic factorization on the :class:`SparsePattern`, so a step
pays the numeric factorization only (simplicial LDL', :data:`CHOLMOD_MODE`); ``"cholespy"`` (a
hard dependency) redoes the analysis every factorization; ``"scipy"`` is splu tuned for SPD.
``"auto"`` (the default) is "cholmod" when scikit-sparse imports and "cholespy" otherwise.
``benchmarks/bench_sim.py`` measures them.

Round-off. The step's matrix is positive definite in exact arithmetic (masses plus PSD element
blocks: the membrane's stress term projected, Gauss-Newton bending, n n^T contact), but a
state with stiffness entries some 1e16 times a vertex mass can still meet a pivot <= 0 in floating
point. A failed factorization of a finite matrix is retried with its diagonal raised by
tau diag(|A|), tau in SHIFTS (1e-12 up to 1e-4): a step damped slightly along its stiffest
directions instead of no step. The forward and the adjoint solve both use that factor, and the
adjoint treats the shift as a constant (it is the exact derivative of x = (A + S)^-1 b for fixed
S). ``_Factor.shift`` says which tau was needed; a non-finite matrix, or one still failing at
the largest shift, raises SimulationError.
"""

from __future__ import annotations

import numpy as np
import torch

from unsew.errors import SimulationError

__all__ = ["SparsePattern", "sparse_solve", "BACKENDS", "resolve_backend"]

BACKENDS = ("auto", "cholmod", "cholespy", "scipy")

_HAS_CHOLMOD = None


def resolve_backend(backend: str) -> str:
    """The concrete backend for a name: "auto" is "cholmod" when scikit-sparse imports, else
    "cholespy". Raises ValueError on an unknown name, ImportError (with the install line) when
    "cholmod" is asked for explicitly and scikit-sparse is missing."""
    global _HAS_CHOLMOD
    if backend not in BACKENDS:
        raise ValueError(f"unknown solver backend {backend!r}; choose one of {BACKENDS}")
    if backend in ("auto", "cholmod"):
        if _HAS_CHOLMOD is None:
            try:
                import os
                import warnings

                # CHOLMOD's BLAS (OpenBLAS where Debian's libopenblas0 is installed) on one thread:
                # on 2 cores its spinning threads slow the other process (shared/STACK.md). Counts
                # only if the BLAS is not loaded yet; the CLI sets it at its start (unsew._threads)
                os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    import sksparse.cholmod  # noqa: F401
                _HAS_CHOLMOD = True
            except ImportError:
                _HAS_CHOLMOD = False
        if _HAS_CHOLMOD:
            return "cholmod"
        if backend == "cholmod":
            raise ImportError(
                "backend 'cholmod' needs scikit-sparse: apt-get install libsuitesparse-dev && "
                "pip install 'unsew[cholmod]' (or use backend='cholespy')"
            )
        return "cholespy"
    return backend


class SparsePattern:
    """Lower-triangle COO pattern of an (n x n) symmetric matrix.

    Args:
        n: size. rows, cols: (nnz,) int arrays/tensors with rows >= cols, no duplicates.
        device: where the index tensors ``rows``, ``cols`` and ``diag_half`` live (default: the
            CPU); the factorizations always run on the CPU from ``rows_np``, ``cols_np``.
    """

    def __init__(self, n: int, rows, cols, *, device=None):
        self.n = int(n)
        r = np.ascontiguousarray(np.asarray(rows.cpu() if torch.is_tensor(rows) else rows), dtype=np.int32)
        c = np.ascontiguousarray(np.asarray(cols.cpu() if torch.is_tensor(cols) else cols), dtype=np.int32)
        if np.any(r < c):
            raise ValueError("SparsePattern takes the lower triangle only (rows >= cols)")
        self.rows_np, self.cols_np = r, c
        self.rows = torch.from_numpy(r.astype(np.int64)).to(device or "cpu")
        self.cols = torch.from_numpy(c.astype(np.int64)).to(device or "cpu")
        self.diag_half = torch.where(self.rows == self.cols, 0.5, 1.0).to(torch.float64)
        self._csc = None  # (order, indices, indptr) of the lower triangle in CSC order
        self._cholmod_symbolic = {}  # CHOLMOD's analysis per mode, made at its first factorization

    def csc_lower(self, values: np.ndarray):
        """scipy CSC matrix of the lower triangle with these values (nnz,) (the COO order of
        the pattern is row-major; the column-major permutation is computed once)."""
        import scipy.sparse as sp

        if self._csc is None:
            order = np.lexsort((self.rows_np, self.cols_np))
            indptr = np.zeros(self.n + 1, np.int32)
            np.cumsum(np.bincount(self.cols_np, minlength=self.n), out=indptr[1:])
            self._csc = (order, self.rows_np[order].copy(), indptr)
        order, indices, indptr = self._csc
        A = sp.csc_matrix((values[order], indices, indptr), shape=(self.n, self.n))
        A.has_sorted_indices = True
        return A

    def dense(self, values: torch.Tensor) -> torch.Tensor:
        """The full symmetric matrix (n, n) from lower values (nnz,) (tests and small cases)."""
        A = values.new_zeros(self.n, self.n)
        A = A.index_put((self.rows, self.cols), values, accumulate=True)
        off = values * (self.rows != self.cols)
        return A.index_put((self.cols, self.rows), off, accumulate=True)


#: relative diagonal shifts tau tried, in order, when a Cholesky factorization of a finite matrix
#: fails: A + tau diag(|A|) (module docstring, "Round-off")
SHIFTS = (1e-12, 1e-10, 1e-8, 1e-6, 1e-4)


#: CHOLMOD's factorization: "simplicial" (LDL', column by column) or "supernodal" (dense blocks
#: through BLAS, on one thread here); simplicial is the faster at a garment's sizes
#: (docs/decisions/057-simplicial-cholmod.md).
DEFAULT_CHOLMOD_MODE = "simplicial"
CHOLMOD_MODE = DEFAULT_CHOLMOD_MODE


class _NotPositiveDefinite(Exception):
    """A Cholesky factorization met a pivot <= 0."""


class _Factor:
    """The factorization of the matrix with lower values ``values`` (nnz,) float64 on ``pattern``.

    ``shift`` is the relative diagonal shift tau that was needed (0.0 for none): the factor is that
    of A + tau diag(|A|) (module docstring, "Round-off")."""

    def __init__(self, pattern: SparsePattern, values: np.ndarray, backend: str):
        self.backend = backend
        self.n = pattern.n
        self.shift = 0.0
        if not np.all(np.isfinite(values)):
            bad = int(np.count_nonzero(~np.isfinite(values)))
            raise SimulationError(
                f"the system matrix holds {bad} NaN or infinite values; the state or material "
                "is not finite (lower dt, check the material stiffness and the initial state)"
            )
        try:
            self.solver = self._factorize(pattern, values)
            return
        except _NotPositiveDefinite as exc:
            first = exc
        diag = np.abs(values) * (pattern.rows_np == pattern.cols_np)
        for tau in SHIFTS:
            try:
                self.solver = self._factorize(pattern, values + tau * diag)
                self.shift = tau
                return
            except _NotPositiveDefinite:
                continue
        kind = "LU" if self.backend == "scipy" else "Cholesky"
        raise SimulationError(
            f"sparse {kind} factorization failed ({first}); the system is not positive definite, even with "
            f"its diagonal raised by {SHIFTS[-1]:g} of itself"
        ) from None

    def _factorize(self, pattern: SparsePattern, values: np.ndarray):
        backend = self.backend
        if backend == "cholmod":
            import warnings

            from sksparse.cholmod import CholmodError, analyze

            A = pattern.csc_lower(values)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # CholmodTypeConversionWarning never applies here
                mode = CHOLMOD_MODE
                if mode not in pattern._cholmod_symbolic:
                    pattern._cholmod_symbolic[mode] = analyze(A, mode=mode, ordering_method="nesdis")
                try:
                    factor = pattern._cholmod_symbolic[mode].cholesky(A)
                except CholmodError as exc:
                    raise _NotPositiveDefinite(str(exc)) from None
            if mode == "simplicial":
                # a simplicial factor is LDL', which CHOLMOD computes for indefinite matrices too:
                # A is positive definite exactly when every pivot in D is
                d = factor.D()
                if not np.all(d > 0.0):
                    raise _NotPositiveDefinite(f"pivot {float(np.min(d)):.3g} <= 0 in LDL'")
            return factor
        if backend == "cholespy":
            from cholespy import CholeskySolverD, MatrixType

            try:
                return CholeskySolverD(self.n, pattern.rows_np, pattern.cols_np, values, MatrixType.COO)
            except Exception as exc:  # cholespy raises a bare exception on a non-PD matrix
                raise _NotPositiveDefinite(str(exc)) from None
        if backend == "scipy":
            import scipy.sparse as sp
            import scipy.sparse.linalg as spla

            r, c = pattern.rows_np, pattern.cols_np
            off = r != c
            A = sp.csc_matrix(
                (
                    np.concatenate([values, values[off]]),
                    (np.concatenate([r, c[off]]), np.concatenate([c, r[off]])),
                ),
                shape=(self.n, self.n),
            )
            try:
                return spla.splu(
                    A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True)
                )
            except RuntimeError as exc:
                raise _NotPositiveDefinite(str(exc)) from None
        raise ValueError(f"unknown solver backend {backend!r}; choose one of {BACKENDS}")

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.ascontiguousarray(b, dtype=np.float64)
        if self.backend == "cholespy":
            x = np.empty_like(b)
            self.solver.solve(b, x)
            return x
        if self.backend == "cholmod":
            return self.solver.solve_A(b)
        return self.solver.solve(b)


class _SparseSolve(torch.autograd.Function):
    @staticmethod
    def forward(ctx, values, b, pattern, backend):
        fac = _Factor(pattern, values.detach().cpu().numpy().astype(np.float64, copy=False), backend)
        x = torch.from_numpy(fac.solve(b.detach().cpu().numpy())).to(b.device)
        ctx.fac = fac
        ctx.pattern = pattern
        ctx.backend = backend
        ctx.save_for_backward(x, values)
        return x

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, g):
        x, values = ctx.saved_tensors
        p = ctx.pattern
        fac = ctx.fac
        if fac is None:  # a second backward through a retained graph: factorize again
            fac = _Factor(p, values.detach().cpu().numpy().astype(np.float64, copy=False), ctx.backend)
        lam = torch.from_numpy(fac.solve(g.detach().cpu().numpy())).to(g.device)
        ctx.fac = None  # free the factor as soon as the adjoint solve is done
        gv = None
        if ctx.needs_input_grad[0]:
            r, c = p.rows.to(g.device), p.cols.to(g.device)
            gv = -(lam[r] * x[c] + lam[c] * x[r]) * p.diag_half.to(g.device)
        return gv, (lam if ctx.needs_input_grad[1] else None), None, None


def sparse_solve(values: torch.Tensor, b: torch.Tensor, pattern: SparsePattern, *, backend: str = "auto"):
    """Solve A x = b for SPD A given by lower-triangle values; differentiable in values and b.

    Args:
        values: (nnz,) float64 lower-triangle entries of A (units of the system).
        b: (n,) float64 right-hand side.
        pattern: the :class:`SparsePattern` of ``values``.
        backend: "auto" (default: "cholmod" if scikit-sparse is installed, else "cholespy"),
            "cholmod", "cholespy" or "scipy" (see the module docstring).

    Returns:
        x: (n,) float64.

    Raises:
        SimulationError: the factorization fails (A not positive definite).
    """
    if values.dtype != torch.float64 or b.dtype != torch.float64:
        raise TypeError("sparse_solve works in float64 (shared/STACK.md: float32 adjoints are useless)")
    return _SparseSolve.apply(values, b, pattern, resolve_backend(backend))
