"""Pull of each panel's rest area towards its area at phase two's start (not in the paper;
``loss.panel_area``, off by default)::

    L_panel(U) = 1/P sum_p (A_p(U) / A_p(U_0) - 1)^2   [-]

A_p(U) [m^2] is the summed area of panel p's rest triangles (U, (Nu, 2) [m]), U_0 the graded
pattern's rest mesh, P the number of panels. The Chamfer sees the draped surface, not where its
cloth comes from: a fold can be fed from the panel beside it as well as from its own, so phase
two moves area between panels at an unchanged total (with ``area: target`` it cannot change the
total at all) and the pattern drifts from the one grading sized panel by panel. The term resists
that drift, relative to each panel's size, so a 4 cm waistband weighs as much as a skirt panel
(how it trades against the Chamfer: docs/decisions/013).
"""

from __future__ import annotations

import torch

from unsew.losses.area import triangle_areas

__all__ = ["panel_areas", "loss_panel_area"]


def panel_areas(uv, faces_uv, face_panel, n_panels: int):
    """Rest area of each panel [m^2], a (P,) tensor.

    uv: (Nu, 2) torch float64 [m]; faces_uv: (F, 3) int64 tensor of rows of uv; face_panel:
    (F,) int64 tensor, the panel index of each triangle; n_panels: P. Same device throughout.
    """
    tri = triangle_areas(uv, faces_uv)
    return torch.zeros(n_panels, dtype=uv.dtype, device=uv.device).index_add(0, face_panel, tri)


def loss_panel_area(uv, faces_uv, face_panel, areas0):
    """1/P sum_p (A_p(U) / A_p(U_0) - 1)^2 [-], a 0-d tensor (module docstring).

    uv: (Nu, 2) torch float64 [m] (differentiable); faces_uv: (F, 3) int64; face_panel: (F,)
    int64 panel index per triangle; areas0: (P,) float64 tensor, every panel's area at the
    start [m^2], all > 0. Same device throughout.
    """
    if uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"uv must be (Nu, 2), got {tuple(uv.shape)}")
    if areas0.ndim != 1 or not bool((areas0 > 0).all()):
        raise ValueError("areas0 must be a (P,) tensor of positive panel areas")
    a = panel_areas(uv, faces_uv, face_panel, areas0.shape[0])
    return ((a / areas0 - 1.0) ** 2).mean()
