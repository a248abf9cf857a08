"""The implicit Euler system assembled, factorized and solved in one autograd Function, with a
structured adjoint (factor once, solve twice; no (nnz,) or (E, m, m) adjoint arrays).

    A = keep * (dt^2 (K_membrane + K_bending) + V + extra) + pinned identity,   A v' = b,

K_membrane = sum_f area_f P_f (G_f^T H G_f + Pgeo_f kron I3) P_f^T and K_bending =
sum_h s_h P_h (w kron 1_3 * g_h g_h^T) P_h^T (energies/membrane.py, energies/bending.py; w the
4x4 corner weights of the bending stencil, model.py), V the per-vertex 3x3 blocks (masses,
friction damping, contact stiffness), ``extra`` any other lower-triangle values (seam springs).

Adjoint. With lambda = A^-1 g and the free-dof masks applied (l = free * lambda,
y = free * v'), dL/dA = -l y^T, so every element block B_e gets dL/dB_e = -1/2 (l_e y_e^T +
y_e l_e^T) (its corners' slices), a rank-2 matrix that is never formed:

    membrane (a = area, Gl = G l_e, Gy = G y_e (3,)):
        dL/da = -dt^2 (Gl . H Gy + sum_kl Pgeo_kl l_k . y_l)
        dL/dG = -dt^2 a (H Gy l_e^T + H Gl y_e^T)            (3, 9)
        dL/dH = -dt^2/2 sum_f a (Gl Gy^T + Gy Gl^T)
        dL/dPgeo_kl = -dt^2/2 a (l_k . y_l + y_k . l_l)
    bending (p_a = g_a . l_a, q_a = g_a . y_a per corner a):
        dL/ds = -dt^2 p^T w q,   dL/dg_a = -dt^2 s (l_a (w q)_a + y_a (w p)_a)
    vertex blocks: dL/dV_i = -1/2 (l_i y_i^T + y_i l_i^T);  dL/db = lambda.

O(elements) work after the one adjoint solve, checked against the unfused path (separate
assembly + sparse_solve) in tests/gradients/test_sim_step_solve.py and gradchecked there.
"""

from __future__ import annotations

import torch

from unsew.sim.assembly import scatter_blocks
from unsew.sim.solve import SparsePattern, _Factor

__all__ = ["step_solve"]


def _values(membrane, bending, vblk, extra, st):
    """Forward assembly of A's lower values (no autograd). membrane: (G, H, P, area); bending: (g, s).
    Gathers use ``index_select`` and the membrane's G^T (H G) is summed from its three rank-one
    terms: both faster on CPU than tensor indexing and a batched 9x3 by 3x9 product."""
    G, H, P, area = membrane
    bg, bs = bending
    model, pat, dt2, w4 = st["model"], st["pattern"], st["dt2"], st["w4"]
    F = G.shape[0]
    HGa = torch.matmul(H, G) * area[:, None, None]  # (F, 3, 9)
    blocks = G[:, 0, :, None] * HGa[:, 0, None, :]
    blocks += G[:, 1, :, None] * HGa[:, 1, None, :]
    blocks += G[:, 2, :, None] * HGa[:, 2, None, :]  # (F, 9, 9)
    blocks.view(F, 3, 3, 3, 3).diagonal(dim1=2, dim2=4).add_(area[:, None, None, None] * P[..., None])
    K = blocks.new_zeros(model.nnz).index_add_(
        0, model.tri_dst, torch.index_select(blocks.reshape(-1), 0, model.tri_src)
    )
    if bg.shape[0]:
        sg = (bs[:, None] * bg).reshape(-1)
        picked = torch.index_select(sg, 0, model.hinge_rows) * torch.index_select(
            bg.reshape(-1), 0, model.hinge_cols
        )
        if w4 is not None:
            w12 = w4.repeat_interleave(3, 0).repeat_interleave(3, 1)
            picked = picked * torch.index_select(w12.reshape(-1), 0, model.hinge_w)
        K.index_add_(0, model.hinge_dst, picked)
    A = dt2 * K + scatter_blocks(model.nnz, model.vert_src, model.vert_dst, vblk)
    if extra is not None:
        A = A + extra
    return A * model.keep.to(A) + pat.pin_diag.to(A)


def _membrane_grads(need, membrane, L, Y, st):
    """dL/d(G, H, P, area) (module docstring; None where not needed) from the masked adjoint
    L and solution Y (N, 3)."""
    G, H, P, area = membrane
    model, dt2 = st["model"], st["dt2"]
    gG = gH = gP = ga = None
    if not any(need):
        return gG, gH, gP, ga
    Le = L[model.faces].reshape(-1, 9)  # (F, 9) corner-major
    Ye = Y[model.faces].reshape(-1, 9)
    Gl = torch.bmm(G, Le[:, :, None])[:, :, 0]  # (F, 3)
    Gy = torch.bmm(G, Ye[:, :, None])[:, :, 0]
    HGl, HGy = Gl @ H, Gy @ H  # H symmetric
    LY = torch.bmm(Le.view(-1, 3, 3), Ye.view(-1, 3, 3).transpose(1, 2))  # (F, 3, 3): l_k . y_l
    if need[0]:
        gG = (-dt2 * area)[:, None, None] * (
            HGy[:, :, None] * Le[:, None, :] + HGl[:, :, None] * Ye[:, None, :]
        )
    if need[1]:
        M = torch.einsum("f,fm,fn->mn", area, Gl, Gy)
        gH = (-0.5 * dt2) * (M + M.T)
    if need[2]:
        gP = (-0.5 * dt2) * area[:, None, None] * (LY + LY.transpose(1, 2))
    if need[3]:
        ga = -dt2 * ((Gl * HGy).sum(-1) + (P * LY).sum((1, 2)))
    return gG, gH, gP, ga


def _bending_grads(need, bending, L, Y, st):
    """dL/d(g, s) of the bending factors (module docstring; None where not needed)."""
    bg, bs = bending
    model, dt2, w4 = st["model"], st["dt2"], st["w4"]
    if not (need[0] or need[1]):
        return None, None
    if not bg.shape[0]:
        return torch.zeros_like(bg), torch.zeros_like(bs)
    Lh = L[model.hinges]  # (Hn, 4, 3)
    Yh = Y[model.hinges]
    g4 = bg.view(-1, 4, 3)
    p = (g4 * Lh).sum(-1)  # (Hn, 4)
    q = (g4 * Yh).sum(-1)
    wq = q @ w4 if w4 is not None else q.sum(-1, keepdim=True).expand_as(q)
    wp = p @ w4 if w4 is not None else p.sum(-1, keepdim=True).expand_as(p)
    gbg = gbs = None
    if need[0]:
        gbg = ((-dt2 * bs)[:, None, None] * (Lh * wq[..., None] + Yh * wp[..., None])).reshape(-1, 12)
    if need[1]:
        gbs = -dt2 * (p * wq).sum(-1)
    return gbg, gbs


class _StepSolve(torch.autograd.Function):
    @staticmethod
    def forward(ctx, st, *inputs):
        # inputs: G, H, P, area, bg, bs, vblk, extra, rhs (each an argument so autograd sees it)
        G, H, P, area, bg, bs, vblk, extra, rhs = inputs
        H = 0.5 * (H + H.T)  # symmetric parts: the adjoint below is that of symmetric blocks
        P = 0.5 * (P + P.transpose(1, 2))
        vblk = 0.5 * (vblk + vblk.transpose(1, 2))
        A = _values((G, H, P, area), (bg, bs), vblk, extra, st)
        fac = _Factor(st["pattern"], A.detach().cpu().numpy(), st["backend"])
        x = torch.from_numpy(fac.solve(rhs.detach().cpu().numpy())).to(rhs.device)
        ctx.fac, ctx.st = fac, st
        ctx.has_extra = extra is not None
        ctx.save_for_backward(
            G, H, P, area, bg, bs, vblk, extra if extra is not None else vblk.new_zeros(0), x
        )
        return x

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, g):
        G, H, P, area, bg, bs, vblk, extra, x = ctx.saved_tensors
        st = ctx.st
        model = st["model"]
        fac = ctx.fac
        if fac is None:  # a second backward through a retained graph: factorize again
            A = _values((G, H, P, area), (bg, bs), vblk, extra if ctx.has_extra else None, st)
            fac = _Factor(st["pattern"], A.cpu().numpy(), st["backend"])
        lam = torch.from_numpy(fac.solve(g.detach().cpu().numpy())).to(g.device)
        ctx.fac = None
        free = (~model.pinned).to(lam.dtype).repeat_interleave(3)
        L = (lam * free).view(-1, 3)  # (N, 3)
        Y = (x * free).view(-1, 3)
        need = ctx.needs_input_grad[1:]  # after st
        gmem = _membrane_grads(need[:4], (G, H, P, area), L, Y, st)
        gbend = _bending_grads(need[4:6], (bg, bs), L, Y, st)
        gV = gE = None
        if need[6]:
            LYv = L[:, :, None] * Y[:, None, :]  # (N, 3, 3)
            gV = -0.5 * (LYv + LYv.transpose(1, 2))
        if ctx.has_extra and need[7]:
            r, c = model.rows.long(), model.cols.long()
            lt, yt = L.reshape(-1), Y.reshape(-1)
            gE = -(lt[r] * yt[c] + lt[c] * yt[r]) * st["pattern"].diag_half
        return None, *gmem, *gbend, gV, gE, lam


def step_solve(model, pattern: SparsePattern, *, blocks, rhs, dt: float, w4, backend: str):
    """Solve the implicit Euler system of one step (module docstring); differentiable.

    Args:
        model: :class:`~unsew.sim.model.SimModel`. pattern: its :class:`SparsePattern` (with ``pin_diag``).
        blocks: the matrix's parts (membrane, bending, vblk, extra): membrane (G (F, 3, 9),
            H (3, 3) [N/m], Pgeo (F, 3, 3), area (F,) [m^2]); bending (g (Hn, 12) [rad/m],
            s (Hn,) [N*m]); vblk (N, 3, 3) vertex blocks [kg]; extra (nnz,) more lower values
            [kg] (e.g. dt^2 * springs) or None.
        rhs: (3N,) [kg m/s]. dt: time step [s]. w4: (4, 4) bending corner weights or None (all ones).
        backend: a concrete solver backend (solve.resolve_backend).

    Returns:
        v': (3N,) float64 [m/s].
    """
    membrane, bending, vblk, extra = blocks
    st = dict(model=model, pattern=pattern, dt2=dt * dt, w4=w4, backend=backend)
    G, H, P, area = membrane
    return _StepSolve.apply(st, G, H, P, area, bending[0], bending[1], vblk, extra, rhs)
