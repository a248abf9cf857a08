"""Small cases shared by the sim tests (import as ``from _simcases import ...`` in tests/sim)."""

from __future__ import annotations

import torch


def random_rotation(seed: int = 0) -> torch.Tensor:
    g = torch.Generator().manual_seed(seed)
    q, r = torch.linalg.qr(torch.randn(3, 3, generator=g, dtype=torch.float64))
    q = q * torch.sign(torch.diagonal(r))
    if torch.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def flat_embed(uv) -> torch.Tensor:
    """(V, 2) -> (V, 3) in the XZ plane (y = 0)."""
    uv = torch.as_tensor(uv, dtype=torch.float64)
    return torch.stack([uv[:, 0], torch.zeros_like(uv[:, 0]), uv[:, 1]], 1)


def perturbed(x, scale: float, seed: int = 1) -> torch.Tensor:
    g = torch.Generator().manual_seed(seed)
    return x + scale * torch.randn(x.shape, generator=g, dtype=torch.float64)
