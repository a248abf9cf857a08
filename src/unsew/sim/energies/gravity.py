"""Gravity: W = sum_i m_i g y_i (Y up, FORMATS.md); constant force -m_i g e_y, zero Hessian.

Lumped masses m_i = density * sum over incident triangles of A_rest/3 (mass_lumped)."""

from __future__ import annotations

import torch

__all__ = ["mass_lumped", "energy_gravity"]


def mass_lumped(n: int, faces: torch.Tensor, area: torch.Tensor, density) -> torch.Tensor:
    """Lumped vertex masses [kg], shape (n,), float64, from rest areas [m^2] (F,) and areal
    density [kg/m^2] (float or 0-d tensor). faces: (F, 3) int64 into the n vertices."""
    m = area.new_zeros(n)
    m = m.index_add(0, faces.reshape(-1), (area / 3.0).repeat_interleave(3))
    return m * density


def energy_gravity(x: torch.Tensor, mass: torch.Tensor, g: float = 9.81):
    """Energy [J] scalar and gradient dW/dx [N] (N, 3) of gravity along -Y.

    x: positions [m] (N, 3); mass: [kg] (N,); g: [m/s^2]."""
    energy = g * (mass * x[:, 1]).sum()
    grad = torch.zeros_like(x)
    grad[:, 1] = g * mass
    return energy, grad
