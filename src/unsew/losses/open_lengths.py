"""Pull of the pattern's open edges' lengths towards their graded lengths (not in the paper;
``LossWeights.lengths``)::

    L_lengths(U) = sum_e (l_e(U) - l_e(U_0))^2 / sum_e l_e(U_0)^2   [-]

over the panels' open edges e (hems, necklines, cuffs, a waist: edges sewn to nothing), l_e the
length [m] of the rest mesh's polyline along e, U (Nu, 2) [m] the rest vertices, U_0 the graded
pattern's. Grading sets these lengths from the target's open contours (a length and a girth per
contour, paper 3.4), so where the target's contours already agree with the graded pattern, a step
of phase two that widens a neckline or a hem to move cloth about is a move the target did not ask
for; the Chamfer alone does not see it (a fold can be fed from any edge).
"""

from __future__ import annotations

import numpy as np

__all__ = ["open_edge_segments", "open_edge_lengths", "loss_open_lengths"]


def open_edge_segments(pattern, edge_verts: dict) -> tuple[np.ndarray, np.ndarray, int]:
    """The rest mesh's boundary segments along every open edge of ``pattern`` (an edge in no
    stitch): (S, 2) int64 uv index pairs, (S,) int64 the open edge each belongs to, and the
    number of open edges E. ``edge_verts``: (panel name, edge index) -> uv indices along that
    edge, start to end (unsew.meshing's GarmentMesh.edge_verts)."""
    sewn = {(s.a.panel, s.a.edge) for s in pattern.stitches} | {
        (s.b.panel, s.b.edge) for s in pattern.stitches
    }
    segs, ids, e = [], [], 0
    for name in pattern.panel_order:
        for i in range(len(pattern.panels[name].edges)):
            if (name, i) in sewn or (name, i) not in edge_verts:
                continue
            v = np.asarray(edge_verts[(name, i)], dtype=np.int64)
            if len(v) < 2:
                continue
            segs.append(np.stack([v[:-1], v[1:]], axis=1))
            ids.append(np.full(len(v) - 1, e, dtype=np.int64))
            e += 1
    if not segs:
        return np.zeros((0, 2), np.int64), np.zeros(0, np.int64), 0
    return np.concatenate(segs), np.concatenate(ids), e


def open_edge_lengths(uv, segments, edge_of, n_edges: int):
    """(E,) lengths [m] of the open edges' polylines. uv: (Nu, 2) torch float64 [m];
    segments: (S, 2) int64 tensor; edge_of: (S,) int64 tensor; n_edges: E."""
    seg = (uv[segments[:, 1]] - uv[segments[:, 0]]).norm(dim=1)  # (S,) [m]
    return uv.new_zeros(n_edges).index_add(0, edge_of, seg)


def loss_open_lengths(uv, segments, edge_of, lengths0):
    """sum_e (l_e - l0_e)^2 / sum_e l0_e^2 [-], a 0-d tensor (module docstring); 0 without open
    edges. uv: (Nu, 2) torch float64 [m] (differentiable); segments, edge_of: from
    :func:`open_edge_segments` as int64 tensors; lengths0: (E,) float64 tensor [m]."""
    if lengths0.numel() == 0:
        return uv.sum() * 0.0
    d = open_edge_lengths(uv, segments, edge_of, lengths0.shape[0]) - lengths0
    return (d**2).sum() / (lengths0**2).sum()
