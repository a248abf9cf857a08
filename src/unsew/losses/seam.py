"""Seam-consistency loss (paper eq. 8): the two sides of a stitch must have equal 2D lengths,
segment by segment::

    L_seam(U) = sum_stitches sum_j ( |u_a^j - u_a^{j+1}| - |u_b^j - u_b^{j+1}| )^2   [m^2]

with ``u_a^j`` the uv vertices along side a of the stitch and ``u_b^j`` those along side b
*reversed* (a stitch sews the start of side a to the end of side b, see
:mod:`unsew.pattern.model`), so segment j of a faces segment j of b. Both sides carry the same
number of vertices (``mesh_pattern`` guarantees it). The weight ``lambda_seam = 0.01`` is applied
by the caller.

The per-stitch index lists are turned once into a static (E, 4) index map
(:func:`seam_segment_pairs`); the loss is then one vectorised expression.
"""

from __future__ import annotations

import numpy as np

from unsew.errors import PatternError

__all__ = ["seam_segment_pairs", "loss_seam"]


def seam_segment_pairs(mesh, stitches) -> np.ndarray:
    """Facing segment pairs of every stitch: rows ``(a0, a1, b0, b1)`` of uv indices, shape (E, 4),
    int64, where segment a0->a1 of side a faces segment b0->b1 of side b.

    mesh: a GarmentMesh (only ``edge_verts[(panel_name, edge_index)] -> (k,) uv indices`` is used).
    stitches: sequence of :class:`unsew.pattern.model.Stitch` (``a``/``b`` with ``panel``, ``edge``).
    Raises PatternError if a stitched edge is missing from the mesh or the sides have different
    vertex counts.
    """
    rows = []
    for s in stitches:
        sides = []
        for side in (s.a, s.b):
            key = (side.panel, side.edge)
            if key not in mesh.edge_verts:
                raise PatternError(
                    f"stitch {s.label or ''} names edge {side.edge} of panel {side.panel!r}, which the "
                    "garment mesh does not have; re-mesh the pattern after editing its stitches"
                )
            sides.append(np.asarray(mesh.edge_verts[key], dtype=np.int64))
        ia, ib = sides
        ib = ib[::-1]  # a.start meets b.end
        if len(ia) != len(ib):
            raise PatternError(
                f"stitch {s.a.panel}:{s.a.edge} - {s.b.panel}:{s.b.edge} has {len(ia)} vs {len(ib)} vertices "
                "on its two sides; mesh the pattern so stitched edges get equal vertex counts"
            )
        if len(ia) < 2:
            continue
        rows.append(np.stack([ia[:-1], ia[1:], ib[:-1], ib[1:]], axis=1))
    if not rows:
        return np.zeros((0, 4), dtype=np.int64)
    return np.concatenate(rows, axis=0)


def loss_seam(uv, mesh=None, stitches=None, *, pairs=None):
    """Seam-consistency loss of eq. 8.

    uv: 2D rest positions [m], shape (Nu, 2), float64 torch tensor.
    mesh: the GarmentMesh whose ``edge_verts`` index ``uv``.
    stitches: the pattern's stitches; default ``mesh.stitches`` (or ``mesh.pattern.stitches``)
        when the mesh carries them.
    pairs: optional precomputed :func:`seam_segment_pairs` (E, 4) (then mesh/stitches are unused);
        pass it inside an optimisation loop.
    Returns: scalar tensor [m^2], differentiable w.r.t. ``uv``; 0 when there are no stitches.
    """
    import torch

    if pairs is None:
        if mesh is None:
            raise ValueError("loss_seam: give mesh (and stitches) or pairs")
        if stitches is None:
            stitches = getattr(mesh, "stitches", None)
            if stitches is None and getattr(mesh, "pattern", None) is not None:
                stitches = mesh.pattern.stitches
            if stitches is None:
                raise ValueError("loss_seam: mesh carries no stitches; pass the pattern's stitches")
        pairs = seam_segment_pairs(mesh, stitches)
    p = torch.as_tensor(pairs, dtype=torch.int64, device=uv.device)
    if p.shape[0] == 0:
        return uv.sum() * 0.0
    la = (uv[p[:, 1]] - uv[p[:, 0]]).norm(dim=1)  # (E,) [m]
    lb = (uv[p[:, 3]] - uv[p[:, 2]]).norm(dim=1)  # (E,) [m]
    return ((la - lb) ** 2).sum()
