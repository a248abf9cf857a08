"""Pull of the pattern's total area towards the target's surface area (not in the paper;
``loss.area``, off by default)::

    L_area(U) = (A(U) / A_T - 1)^2   [-]

A(U) [m^2] is the summed area of the rest triangles of every panel (U, (Nu, 2) [m]), A_T [m^2]
the summed area of the target's triangles. Cloth barely stretches, so a garment's surface area
is close to its pattern's area, while the Chamfer distance cannot see area hidden in folds
(docs/decisions/004 and 013). Only for a
target that is one whole garment surface: a scan with holes or a doubled layer gives a wrong A_T.
"""

from __future__ import annotations

__all__ = ["triangle_areas", "rest_area", "loss_area"]


def triangle_areas(uv, faces_uv):
    """Area [m^2] of each rest triangle whatever its winding, a (F,) tensor.

    uv: (Nu, 2) torch float64 [m]; faces_uv: (F, 3) int64 tensor of rows of uv, same device.
    """
    a, b, c = uv[faces_uv[:, 0]], uv[faces_uv[:, 1]], uv[faces_uv[:, 2]]
    e1, e2 = b - a, c - a
    return 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]).abs()


def rest_area(uv, faces_uv):
    """Summed area [m^2] of the rest triangles, a 0-d tensor.

    uv: (Nu, 2) torch float64 [m]; faces_uv: (F, 3) int64 tensor of rows of uv, same device.
    """
    return triangle_areas(uv, faces_uv).sum()


def loss_area(uv, faces_uv, area_target: float):
    """(A(U) / A_T - 1)^2 [-], a 0-d tensor (module docstring).

    uv: (Nu, 2) torch float64 [m] (differentiable); faces_uv: (F, 3) int64 tensor, same device;
    area_target: A_T [m^2], > 0.
    """
    if uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"uv must be (Nu, 2), got {tuple(uv.shape)}")
    if not area_target > 0:
        raise ValueError(f"area_target must be positive, got {area_target}")
    return (rest_area(uv, faces_uv) / area_target - 1.0) ** 2
