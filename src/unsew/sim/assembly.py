"""Assembly of per-element forces and blocks into the global vectors and the sparse system
(paper 3.4.3's static mapping): fixed index maps from ``SimModel``, ``index_add`` only.
"""

from __future__ import annotations

import torch

__all__ = ["scatter_vertex", "scatter_blocks", "assemble_outer", "assemble_membrane", "outer_adjoint_map"]


def scatter_vertex(n: int, elems: torch.Tensor, per_elem: torch.Tensor) -> torch.Tensor:
    """Sum per-element, per-corner vectors into vertices.

    Args:
        n: number of vertices N.
        elems: (E, k) int64 vertex indices.
        per_elem: (E, k, 3) values (forces [N] or gradients).

    Returns:
        (N, 3) sums, same dtype as per_elem.
    """
    out = per_elem.new_zeros(n, 3)
    if elems.shape[0] == 0:
        return out
    return out.index_add(0, elems.reshape(-1), per_elem.reshape(-1, 3))


def scatter_blocks(nnz: int, src: torch.Tensor, dst: torch.Tensor, blocks: torch.Tensor) -> torch.Tensor:
    """Sum the lower-triangle entries of element blocks into the value array of the system.

    Args:
        nnz: number of stored values.
        src: (L,) int64 positions in ``blocks.reshape(-1)`` of entries with global row >= col.
        dst: (L,) int64 their positions in the value array (from ``SimModel``).
        blocks: (E, m, m) symmetric element blocks (dofs corner-major, xyz minor).

    Returns:
        (nnz,) values.
    """
    out = blocks.new_zeros(nnz)
    if src.numel() == 0:
        return out
    return out.index_add(0, dst, torch.index_select(blocks.reshape(-1), 0, src))


def _unscatter(gvals: torch.Tensor, src: torch.Tensor, dst: torch.Tensor, shape) -> torch.Tensor:
    """Adjoint of the lower-entry gather-scatter: (nnz,) -> blocks of ``shape``, zero off ``src``."""
    W = gvals.new_zeros(int(torch.Size(shape).numel()))
    W[src] = gvals[dst]
    return W.view(shape)


def outer_adjoint_map(nnz: int, src: torch.Tensor, dst: torch.Tensor, n_elem: int, m: int, weight=None):
    """Precomputed adjoint of the lower-entry scatter of symmetric (m x m) blocks.

    Returns fdst (E*m*m,) int64: the value index of every entry of every block (its own if
    stored, its transpose's otherwise, ``nnz`` -- a zero slot -- if neither is in the pattern),
    and h (E*m*m,) float64: 1 where the entry and its transpose are both stored (diagonal), 1/2
    where one of the two stands for both, 0 where none is, times ``weight``. Then, for symmetric
    blocks, dL/dblocks = (gvals ++ [0])[fdst] * h, a symmetric (E, m, m) array, in one gather."""
    EM = n_elem * m * m
    dev = src.device
    fdst = torch.full((EM,), nnz, dtype=torch.int64, device=dev)
    cnt = torch.zeros(EM, dtype=torch.float64, device=dev)
    e = torch.div(src, m * m, rounding_mode="floor")
    loc = src - e * (m * m)
    i, j = torch.div(loc, m, rounding_mode="floor"), loc % m
    tr = e * (m * m) + j * m + i  # the transposed entry
    fdst[src] = dst
    cnt[src] += 1.0
    has_own = torch.zeros(EM, dtype=torch.bool, device=dev)
    has_own[src] = True
    only_t = ~has_own[tr]
    fdst[tr[only_t]] = dst[only_t]
    cnt[tr[only_t]] += 1.0
    h = torch.where(
        has_own & torch.zeros(EM, dtype=torch.bool, device=dev).index_fill_(0, tr[~only_t], True), 1.0, 0.5
    )
    h = torch.where(cnt > 0, h, torch.zeros_like(h)).to(torch.float64)
    if weight is not None:
        h = (h.view(n_elem, m, m) * weight.to(h)).reshape(-1)
    return fdst, h


class _AssembleOuter(torch.autograd.Function):
    """values = scatter of s_e * w * (g_e g_e^T) (lower entries); hand-written backward."""

    @staticmethod
    def forward(ctx, g, s, weight, index):
        src, dst, nnz, fdst, h = index  # scatter maps and the adjoint map (not differentiated)
        sg = s[:, None] * g
        blocks = sg[:, :, None] * g[:, None, :]  # (E, m, m)
        picked = blocks.reshape(-1)[src]
        if weight is not None:
            m = g.shape[1]
            picked = picked * weight.reshape(-1)[src % (m * m)]
        ctx.save_for_backward(g, s)
        ctx.maps = (fdst, h)
        return blocks.new_zeros(nnz).index_add_(0, dst, picked)

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, gvals):
        g, s = ctx.saved_tensors
        E, m = g.shape
        fdst, h = ctx.maps
        W = (torch.cat([gvals, gvals.new_zeros(1)])[fdst] * h).view(E, m, m)  # symmetric
        Wg = torch.bmm(W, g[:, :, None])[:, :, 0]  # (E, m)
        grad_g = (2.0 * s[:, None]) * Wg if ctx.needs_input_grad[0] else None
        grad_s = (g * Wg).sum(-1) if ctx.needs_input_grad[1] else None
        return grad_g, grad_s, None, None


def assemble_outer(
    nnz: int, src, dst, g: torch.Tensor, s: torch.Tensor, weight=None, *, maps=None
) -> torch.Tensor:
    """System values (nnz,) of rank-one element blocks s_e w * g_e g_e^T, differentiable in g, s.

    Equal to ``scatter_blocks(nnz, src, dst, s[:, None, None] * g[:, :, None] * g[:, None, :] * weight)``
    with a backward of one gather and one small batched product, no autograd graph of blocks.

    Args:
        g: (E, m) element vectors (e.g. bending d theta/dx flattened). s: (E,) scales.
        weight: (m, m) constant symmetric entry weights or None. src/dst: as :func:`scatter_blocks`.
        maps: :func:`outer_adjoint_map` output for these src/dst/weight (computed if None;
            cache it per topology).
    """
    if maps is None:
        maps = outer_adjoint_map(nnz, src, dst, g.shape[0], g.shape[1], weight)
    return _AssembleOuter.apply(g, s, weight, (src, dst, nnz, *maps))


class _AssembleMembrane(torch.autograd.Function):
    """values = scatter of area_f (G_f^T H G_f + kron(P_f, I3)) with H, P symmetrised;
    hand-written backward (symmetric adjoint blocks from one gather, two batched products)."""

    @staticmethod
    def forward(ctx, G, H, P, area, index):
        src, dst, nnz, fdst, h = index  # scatter maps and the adjoint map (not differentiated)
        F = G.shape[0]
        H = 0.5 * (H + H.T)
        P = 0.5 * (P + P.transpose(1, 2))
        HGa = torch.matmul(H, G) * area[:, None, None]  # (F, 3, 9)
        blocks = torch.bmm(G.transpose(1, 2), HGa)  # (F, 9, 9) area G^T H G
        # + area P kron I3
        blocks.view(F, 3, 3, 3, 3).diagonal(dim1=2, dim2=4).add_(area[:, None, None, None] * P[..., None])
        ctx.save_for_backward(G, H, P, area)
        ctx.maps = (fdst, h)
        return blocks.new_zeros(nnz).index_add_(0, dst, blocks.reshape(-1)[src])

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, gvals):
        G, H, P, area = ctx.saved_tensors
        F = G.shape[0]
        fdst, h = ctx.maps
        W = (torch.cat([gvals, gvals.new_zeros(1)])[fdst] * h).view(F, 9, 9)  # symmetric adjoint
        GW = torch.bmm(G, W)  # (F, 3, 9)
        GWG = torch.bmm(GW, G.transpose(1, 2))  # (F, 3, 3) = G W G^T
        # (F, 3, 3): sum_c W[(k,c),(l,c)]
        wgeo = torch.diagonal(W.view(F, 3, 3, 3, 3), dim1=2, dim2=4).sum(-1)
        grad_G = grad_H = grad_P = grad_area = None
        if ctx.needs_input_grad[0]:
            grad_G = (2.0 * area[:, None, None]) * torch.matmul(H, GW)
        if ctx.needs_input_grad[1]:
            grad_H = (area[:, None, None] * GWG).sum(0)
            grad_H = 0.5 * (grad_H + grad_H.T)
        if ctx.needs_input_grad[2]:
            grad_P = area[:, None, None] * 0.5 * (wgeo + wgeo.transpose(1, 2))
        if ctx.needs_input_grad[3]:
            grad_area = (GWG * H).sum((1, 2)) + (wgeo * P).sum((1, 2))
        return grad_G, grad_H, grad_P, grad_area, None


def assemble_membrane(
    nnz: int, src, dst, G: torch.Tensor, H: torch.Tensor, P: torch.Tensor, area: torch.Tensor, *, maps=None
):
    """System values (nnz,) of membrane element blocks area (G^T H G + P kron I3).

    Args:
        G: (F, 3, 9) strain Jacobians [1] (energies/membrane.py). H: (3, 3) [N/m].
        P: (F, 3, 3) [N/m^3] the geometric term B S+ B^T. area: (F,) [m^2].
        src/dst: the triangle maps of :class:`~unsew.sim.model.SimModel`.
        maps: :func:`outer_adjoint_map` of src/dst for (F, 9, 9) blocks (computed if None;
            cache it per topology). H and P enter through their symmetric parts.

    Returns:
        (nnz,) [N/m], differentiable in G, H, P and area with a hand-written backward.
    """
    if maps is None:
        maps = outer_adjoint_map(nnz, src, dst, G.shape[0], 9)
    return _AssembleMembrane.apply(G, H, P, area, (src, dst, nnz, *maps))
