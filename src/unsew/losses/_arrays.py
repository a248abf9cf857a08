"""Shared input handling of the losses' mesh helpers."""

from __future__ import annotations

import numpy as np


def mesh_arrays(verts, faces) -> tuple[np.ndarray, np.ndarray]:
    """(verts (V, 3) float64, faces (F, 3) int64) as numpy from numpy or torch inputs; an empty
    face list gives shape (0, 3). Raises ValueError for other shapes."""
    try:
        import torch

        if isinstance(verts, torch.Tensor):
            verts = verts.detach().cpu().numpy()
        if isinstance(faces, torch.Tensor):
            faces = faces.detach().cpu().numpy()
    except ImportError:  # pragma: no cover
        pass
    v = np.asarray(verts, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    if f.size == 0:
        f = f.reshape(0, 3)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"verts {v.shape} and faces {f.shape} must be (V, 3) and (F, 3)")
    return v, f
