"""The step's system stays positive definite whatever the state: a sheet compressed to 60 % and
folded flat into a crushed accordion (triangles pressed onto their hinge edges), where the exact
membrane Hessian is indefinite and the bending blocks of crushed hinges are unbounded, still
factorizes, and its steps (backtracked on the step's incremental potential) open it without
tearing it; a matrix that is positive definite only in exact arithmetic is
factorized with a small diagonal shift; a non-finite or truly indefinite one is refused."""

import numpy as np
import pytest
import torch

from unsew.errors import SimulationError
from unsew.sim import MATERIALS, PlaneSDF, SimModel, SimState, sparse_solve
from unsew.sim.assembly import scatter_blocks
from unsew.sim.energies.membrane import energy_membrane
from unsew.sim.integrator import (
    StepParams,
    _pattern,
    forces,
    rest_data,
    step,
    total_energy,
)
from unsew.sim.meshes import grid_sheet
from unsew.sim.solve import SHIFTS, SparsePattern, _Factor, resolve_backend

MAT = MATERIALS["cotton"]
BACKENDS = sorted({resolve_backend("auto"), "cholespy"})


def _crushed_accordion(n=8, size=0.2, scale=0.6, crush=1e-8, fold=1e-10):
    """A size x size sheet (n x n quads) compressed to ``scale`` along u and crushed along v into
    a flat accordion: rows ``crush`` * row spacing apart, alternate rows ``fold`` * size out of
    the plane (every row line a fold)."""
    uv, f = grid_sheet(n, n, size, size)
    m = SimModel.build(f, f)
    u, v = uv[:, 0], uv[:, 1]
    row = np.rint(v / (size / n))
    x = np.c_[scale * u, crush * (size / n) * row, (row % 2) * fold * size]
    return m, torch.as_tensor(uv), torch.as_tensor(x)


def _system(m, rest, x, params):
    """The step's matrix (lower values) and pattern, as integrator.step assembles it (unfused)."""
    sdf = PlaneSDF((0, -1, 0))
    _, K, Hc, D, _ = forces(m, rest, SimState.at_rest(x), sdf, MAT.gamma(), params)
    dt = params.dt
    vblk = rest.mass[:, None, None] * torch.eye(3, dtype=x.dtype) + dt * D + dt * dt * Hc
    A = dt * dt * K + scatter_blocks(m.nnz, m.vert_src, m.vert_dst, vblk)
    pat = _pattern(m)
    return A * m.keep + pat.pin_diag, pat


@pytest.mark.parametrize("crush", [1e-7, 1e-8])
def test_crushed_fold_is_positive_definite_and_steps_soundly(crush):
    """Without the height floor of bending.py and the step's line search, the 1e-8 crush fails its
    Cholesky factorization at step 0 and the 1e-7 one throws vertices at 10 m/s."""
    m, uv, x = _crushed_accordion(crush=crush)
    rest = rest_data(m, uv, MAT.density)
    # the state is compressed: the exact (unprojected) membrane Hessian is indefinite there
    _, _, Hraw = energy_membrane(x, m.faces, rest.area, rest.B, MAT.gamma(), project=False)
    assert float(torch.linalg.eigvalsh(Hraw).min()) < 0.0
    params = StepParams(dt=0.05, fused=False)
    A, pat = _system(m, rest, x, params)
    # masses plus PSD blocks: no eigenvalue below the lightest vertex's mass (up to round-off)
    ev = torch.linalg.eigvalsh(pat.dense(A))
    assert float(ev.min()) >= 0.999 * float(rest.mass.min()), (float(ev.min()), float(rest.mass.min()))
    sdf = PlaneSDF((0, -1, 0))
    e = m.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    L0 = (uv[e[:, 0]] - uv[e[:, 1]]).norm(dim=1)
    for backend in BACKENDS:
        for fused in (True, False):
            # no gravity: the only motion is the crushed sheet springing back to its rest shape
            p = StepParams(dt=0.05, fused=fused, backend=backend, gravity=0.0)
            st = SimState.at_rest(x.clone())
            e_start = float(total_energy(m, rest, st.x, sdf, MAT.gamma(), p))
            for k in range(5):
                st = step(m, rest, st, sdf, MAT.gamma(), p, index=k)
                assert bool(torch.isfinite(st.x).all())
                # it opens without throwing a vertex or tearing an edge (the full linearized
                # steps tear edges to 15 times their length at the second step)
                L = (st.x[e[:, 0]] - st.x[e[:, 1]]).norm(dim=1)
                assert float((L / L0).max()) < 1.35, (backend, fused, k, float((L / L0).max()))
                assert float(st.v.norm(dim=1).max()) < 1.5, (backend, fused, k)
            kinetic = 0.5 * float((rest.mass[:, None] * st.v**2).sum())
            assert float(total_energy(m, rest, st.x, sdf, MAT.gamma(), p)) + kinetic < 0.1 * e_start


def test_crushed_fold_gradient_is_finite():
    """The drape's adjoint goes through the crushed state's factor: finite gradients in uv and Gamma."""
    m, uv, x = _crushed_accordion()
    uv = uv.clone().requires_grad_()
    g = MAT.gamma().clone().requires_grad_()
    rest = rest_data(m, uv, MAT.density)
    st = step(m, rest, SimState.at_rest(x.clone()), PlaneSDF((0, -1, 0)), g, StepParams(dt=0.05))
    gu, gg = torch.autograd.grad(st.x[:, 0].sum() + st.x[:, 1].pow(2).sum(), (uv, g))
    assert bool(torch.isfinite(gu).all()) and bool(torch.isfinite(gg).all())
    assert float(gu.abs().max()) > 0.0


def _near_singular(big=1e20, small=1e-4):
    """A 2x2 matrix [[big + small, big], [big, big + small]]: eigenvalues `small` and 2 big + small
    in exact arithmetic, singular once big + small rounds to big."""
    pat = SparsePattern(2, [0, 1, 1], [0, 0, 1])
    return pat, np.array([big + small, big, big + small])


@pytest.mark.parametrize("backend", BACKENDS)
def test_round_off_indefinite_matrix_is_factorized_with_a_shift(backend):
    pat, vals = _near_singular()
    fac = _Factor(pat, vals, backend)
    assert fac.shift in SHIFTS
    # (1, -1) is an eigenvector of A + tau diag(A), with eigenvalue tau big (+ small, lost to round-off)
    b = np.array([1.0, -1.0])
    x = fac.solve(b)
    assert np.allclose(x, b / (fac.shift * 1e20), rtol=1e-3)
    # a well-posed matrix is factorized as it is
    assert _Factor(pat, np.array([2.0, -1.0, 2.0]), backend).shift == 0.0
    xs = sparse_solve(torch.tensor(vals), torch.tensor(b), pat, backend=backend)
    assert bool(torch.isfinite(xs).all())


@pytest.mark.parametrize("backend", BACKENDS)
def test_non_finite_or_indefinite_matrix_is_refused(backend):
    pat = SparsePattern(2, [0, 1, 1], [0, 0, 1])
    with pytest.raises(SimulationError, match="NaN or infinite"):
        _Factor(pat, np.array([1.0, np.nan, 1.0]), backend)
    with pytest.raises(SimulationError, match="not positive definite"):
        _Factor(pat, np.array([1.0, 0.0, -1.0]), backend)  # eigenvalue -1: no small shift hides it


def test_crushed_hinge_gradient_is_bounded_and_exact_above_the_floor():
    """d theta/dx2 of a hinge is 1/h (h the height of x2 over the edge): exact (autograd of theta)
    for a triangle flat but not crushed, bounded by 1/(HEIGHT_FLOOR * its size) when crushed."""
    from unsew.sim.energies.bending import HEIGHT_FLOOR, dihedral_angle

    hinge = torch.tensor([[0, 1, 2, 3]])
    for h, exact in ((1e-2, True), (1e-9, False)):
        x = torch.tensor(
            [[0.0, 0.0, 0.0], [0.02, 0.0, 0.0], [0.01, 0.02 * h, 0.0], [0.01, -0.01, 0.01]],
            dtype=torch.float64,
            requires_grad=True,
        )
        theta, dth = dihedral_angle(x, hinge)
        size = float(((x[2] - x[0]).pow(2).sum() + (x[2] - x[1]).pow(2).sum() + 0.02**2) / 3.0) ** 0.5
        if exact:
            (auto,) = torch.autograd.grad(theta.sum(), x)
            assert torch.allclose(dth[0], auto, rtol=1e-9, atol=1e-9)
            assert float(dth[0, 2].norm()) == pytest.approx(1.0 / (0.02 * h), rel=1e-9)
        else:
            assert float(dth[0, 2].norm()) <= 1.0 / (HEIGHT_FLOOR * size) * (1 + 1e-9)
