"""A barrier against cloth stretched beyond what fabric allows (not in the paper; ``loss.stretch``)::

    L_stretch(X, U) = sum_e relu(|x_a - x_b| / |u_a - u_b| - s_max)^2   [-]

over the edges e = (a, b) of the draped triangles (X, (Nx, 3) [m]), each with its rest length
from the pattern's rest mesh (U, (Nu, 2) [m]); s_max [-] is the largest stretch a drape is
allowed without cost (:data:`STRETCH_BOUND`). The term is exactly zero while every edge is
within the bound, so a fit whose drapes never stretch that far is untouched by it.

Why: the Chamfer sees where the draped surface lies, not how hard the cloth is pulled to lie
there. In a soft fabric phase two can hold a dress up by shrinking an opening (a neckline) until
the drape hangs from it stretched two or three times its rest length: the distance falls while
the pattern stops being one a fabric could be sewn from, and a drape of it from scratch can tear
an edge further, failing the fit's last check (docs/decisions/006).
"""

from __future__ import annotations

import torch

__all__ = ["loss_stretch", "triangle_edges", "STRETCH_BOUND"]

#: Largest edge stretch (length over rest length) [-] that costs nothing: above the largest
#: stretch of every foreign target (1.03-1.40 by triangle, benchmarks/foreign/cases/*/meta.json)
#: and half way to the drape check's failure bound (unsew.sim.checks.STRETCH_MAX, 3).
STRETCH_BOUND = 1.5


def triangle_edges(faces, faces_uv) -> tuple[torch.Tensor, torch.Tensor]:
    """The edges of the triangles as index pairs into X and into U: two (3F, 2) int64 tensors
    (an edge shared by two triangles appears twice). faces: (F, 3) int into X; faces_uv:
    (F, 3) int, the same triangles into U."""
    f = torch.as_tensor(faces, dtype=torch.int64)
    fu = torch.as_tensor(faces_uv, dtype=torch.int64)
    cols = [0, 1, 1, 2, 2, 0]
    return f[:, cols].reshape(-1, 2), fu[:, cols].reshape(-1, 2)


def loss_stretch(x, uv, edges, edges_uv, *, bound: float = STRETCH_BOUND):
    """sum_e relu(|x_a - x_b| / |u_a - u_b| - bound)^2 [-], a 0-d tensor (module docstring).

    x: (Nx, 3) torch float64 [m]; uv: (Nu, 2) torch float64 [m] (both differentiable);
    edges, edges_uv: (E, 2) int64 index pairs into x and uv (:func:`triangle_edges`), every
    rest length > 0; bound: the stretch [-] below which an edge costs nothing. Same device
    throughout.
    """
    if x.ndim != 2 or x.shape[1] != 3 or uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"x must be (Nx, 3) and uv (Nu, 2), got {tuple(x.shape)} and {tuple(uv.shape)}")
    if edges.shape != edges_uv.shape or edges.ndim != 2 or edges.shape[1] != 2:
        raise ValueError(
            f"edges and edges_uv must be matching (E, 2), got {tuple(edges.shape)} and "
            f"{tuple(edges_uv.shape)}"
        )
    length = (x[edges[:, 0]] - x[edges[:, 1]]).norm(dim=1)  # (E,) [m]
    rest = (uv[edges_uv[:, 0]] - uv[edges_uv[:, 1]]).norm(dim=1)  # (E,) [m]
    return (torch.relu(length / rest - bound) ** 2).sum()
