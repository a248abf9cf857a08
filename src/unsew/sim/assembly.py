"""Assembly of per-element forces and blocks into the global vectors and the sparse system
(paper 3.4.3's static mapping): fixed index maps from ``SimModel``, ``index_add`` only.
"""

from __future__ import annotations

import torch

__all__ = ["scatter_vertex", "scatter_blocks"]


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
    return out.index_add(0, dst, blocks.reshape(-1)[src])
