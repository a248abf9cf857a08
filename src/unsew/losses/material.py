"""Material range penalty (paper 3.5, after eq. 9)::

    L_mat(Gamma) = sum_i relu(1e-6 - Gamma_i)

Gamma = (H00, H01, H11, H22 [N/m], k [N*m]) (``Material.gamma()``); the threshold 1e-6 is in
those units. The weight ``lambda_mat = 0.01`` is applied by the caller.
"""

from __future__ import annotations

__all__ = ["MATERIAL_FLOOR", "loss_material"]

#: Lower bound of every material parameter (N/m for H, N*m for k), paper 3.5.
MATERIAL_FLOOR = 1e-6


def loss_material(gamma, *, floor: float = MATERIAL_FLOOR):
    """Penalty ``sum relu(floor - gamma)``.

    gamma: material parameters, shape (5,) (any shape accepted), float64 torch tensor,
        units N/m (H00, H01, H11, H22) and N*m (k).
    Returns: scalar tensor (mixed units, as gamma), differentiable w.r.t. ``gamma`` (the
    gradient is -1 for entries below the floor, 0 above).
    """
    import torch

    return torch.relu(floor - gamma).sum()
