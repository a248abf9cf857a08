"""Height anchors: vertices held at a height by vertical springs, as GarmentCode's garments hang
from a waistband or a strapless top held at the body (unsew.dress.attached_vertices).

W = ka/2 sum_i (y_i - h_i)^2 over the anchored vertices i (Y up); gradient ka (y_i - h_i) along Y;
Hessian ka on each vertex's (Y, Y) entry. The vertices stay free to slide round the body."""

from __future__ import annotations

import torch

__all__ = ["energy_anchor"]


def energy_anchor(x, idx, height, stiffness: float, *, hessian: bool = True):
    """x: (N, 3) [m]; idx: (A,) int64 anchored vertices; height: (A,) [m] their heights; stiffness
    ka [N/m] per vertex.

    Returns energy [J], grad (A, 3) [N] (rows of idx), hess (A, 3, 3) [N/m] or None."""
    dy = x[idx, 1] - height.to(x.dtype)
    energy = 0.5 * stiffness * (dy * dy).sum()
    grad = torch.zeros(len(idx), 3, dtype=x.dtype, device=x.device)
    grad[:, 1] = stiffness * dy
    if not hessian:
        return energy, grad, None
    hess = torch.zeros(len(idx), 3, 3, dtype=x.dtype, device=x.device)
    hess[:, 1, 1] = stiffness
    return energy, grad, hess
