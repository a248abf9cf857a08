"""Gathered seams: the longer side of a stitch of unequal lengths eased in to the shorter one.

A pattern may sew an edge to a shorter one on purpose (a puffed sleeve's cap into its armhole, a
full skirt into its waistband, a sleeve's end into its cuff: GarmentCode's designs gather up to
2.5 times). Sewn vertex to vertex, both sides end one length, so a membrane that resists
compression as it resists stretch stretches the shorter side. A tailor gathers the longer side
instead: its fabric is bunched along the seam, shorter there, and fans out to its own width away
from it. Commercial simulators model this as an elastic line shrinking the seam's rest length.

Here each triangle of the longer side's panel near the edge gets a rest shape shortened along the
edge: its rest corners are mapped by ``G = I - (1 - s) t t^T`` (t the unit tangent of the edge's
nearest segment, in the panel's frame), with ``s = r + (1 - r) * min(d / GATHER_BAND, 1)``, r the
ratio of the shorter side's length to the longer's and d the triangle's nearest corner's distance
to the edge. A triangle on the edge is shortened to the shorter side's length, one a band away
keeps its own. Only the membrane's rest shape (its strain measure) uses G; areas, masses and
bending keep the pattern's own.
"""

from __future__ import annotations

import numpy as np

__all__ = ["gather_maps", "GATHER_BAND", "GATHER_FROM"]

#: Width [m] over which a gathered edge's shortening fades out into its panel (gathers of a
#: dress or sleeve spread over a few centimetres of fabric).
GATHER_BAND = 0.1

#: A stitch whose longer side exceeds the shorter by more than this ratio is gathered (below it,
#: the sides differ by sampling and drafting noise and are sewn as they are).
GATHER_FROM = 1.03


def _polyline_length(p: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def _nearest_segments(points: np.ndarray, poly: np.ndarray):
    """Distance [m] (n,) from each 2D point to the polyline ``poly`` (k+1, 2) and the unit
    tangent (n, 2) of its nearest segment."""
    a, b = poly[:-1], poly[1:]  # (k, 2)
    ab = b - a
    ll = np.einsum("kd,kd->k", ab, ab).clip(1e-300)
    t = np.clip(np.einsum("nkd,kd->nk", points[:, None, :] - a[None], ab) / ll, 0.0, 1.0)
    foot = a[None] + t[..., None] * ab[None]  # (n, k, 2)
    dist = np.linalg.norm(points[:, None, :] - foot, axis=-1)  # (n, k)
    j = dist.argmin(axis=1)
    tangent = ab[j] / np.sqrt(ll[j])[:, None]
    return dist[np.arange(len(points)), j], tangent


def _gathered_sides(stitches, edge_verts: dict, uv: np.ndarray):
    """(long side's (panel, edge), ratio short/long) of every stitch gathered (GATHER_FROM)."""
    out = []
    for s in stitches:
        ka, kb = (s.a.panel, s.a.edge), (s.b.panel, s.b.edge)
        la, lb = _polyline_length(uv[edge_verts[ka]]), _polyline_length(uv[edge_verts[kb]])
        long_, short, key = (la, lb, ka) if la >= lb else (lb, la, kb)
        if short > 0.0 and long_ > GATHER_FROM * short:
            out.append((key, short / long_))
    return out


def gather_maps(uv, faces_uv, uv_panel, panel_names, edge_verts: dict, stitches):
    """Per-triangle maps of the rest corners that gather the longer side of unequal stitches.

    Args:
        uv: 2D rest positions [m], (Nu, 2) float64.
        faces_uv: (F, 3) int64 triangles into uv.
        uv_panel: (Nu,) int64 panel index of each uv vertex (into ``panel_names``).
        panel_names: panel names in order.
        edge_verts: (panel name, edge index) -> uv indices along the edge, (k,) int64.
        stitches: the pattern's stitches (``a``/``b`` sides with ``panel`` and ``edge``).

    Returns:
        (F, 2, 2) float64 maps G (rest corner u -> G u, the identity away from a gathered
        edge), or None when no stitch is gathered.
    """
    sides = _gathered_sides(stitches, edge_verts, uv)
    if not sides:
        return None
    faces_uv = np.asarray(faces_uv, dtype=np.int64)
    panel_of_face = uv_panel[faces_uv[:, 0]]
    scale = np.ones(len(faces_uv))
    tangent = np.zeros((len(faces_uv), 2))
    index = {name: p for p, name in enumerate(panel_names)}
    for (panel, edge), r in sides:
        f = np.nonzero(panel_of_face == index[panel])[0]
        poly = uv[edge_verts[(panel, edge)]]
        corners = uv[faces_uv[f]].reshape(-1, 2)  # (3 |f|, 2)
        d_corner, _ = _nearest_segments(corners, poly)
        d = d_corner.reshape(-1, 3).min(axis=1)
        _, t = _nearest_segments(uv[faces_uv[f]].mean(axis=1), poly)
        s = r + (1.0 - r) * np.minimum(d / GATHER_BAND, 1.0)
        stronger = s < scale[f]  # a triangle near two gathered edges takes the stronger
        scale[f[stronger]], tangent[f[stronger]] = s[stronger], t[stronger]
    g = np.broadcast_to(np.eye(2), (len(faces_uv), 2, 2)).copy()
    g -= (1.0 - scale)[:, None, None] * np.einsum("fi,fj->fij", tangent, tangent)
    return g
