"""Zero-length springs joining seam vertices during the sewing phase:
W = ks/2 |x_a - x_b|^2, gradient ks (x_a - x_b), -ks (x_a - x_b), Hessian ks [[I, -I], [-I, I]]."""

from __future__ import annotations

import torch

__all__ = ["energy_spring"]


def energy_spring(x, springs, stiffness, *, hessian: bool = True):
    """x: (N, 3) [m]; springs: (S, 2) int64; stiffness ks [N/m] (float or (S,)).

    Returns energy [J], grad (S, 2, 3) [N], hess (S, 6, 6) [N/m] or None."""
    d = x[springs[:, 0]] - x[springs[:, 1]]  # (S, 3)
    ks = torch.as_tensor(stiffness, dtype=x.dtype, device=x.device)
    ks = ks.expand(springs.shape[0]) if ks.dim() == 0 else ks
    energy = 0.5 * (ks * (d * d).sum(-1)).sum()
    grad = torch.stack([ks[:, None] * d, -ks[:, None] * d], 1)
    if not hessian:
        return energy, grad, None
    eye = torch.eye(3, dtype=x.dtype, device=x.device)
    blk = torch.cat([torch.cat([eye, -eye], 1), torch.cat([-eye, eye], 1)], 0)  # (6, 6)
    return energy, grad, ks[:, None, None] * blk
