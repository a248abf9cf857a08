"""Open contours of a garment mesh (hems, cuffs, neckline, waist) and their Chamfer loss (eq. 6).

An open contour is a boundary loop of the mesh: the edges used by exactly one triangle, chained
into closed cycles. The cycles follow the triangles' orientation (each boundary edge is walked
in the direction it has in its triangle). Where two loops touch at one vertex (a non-manifold
boundary vertex with four or more boundary edges), the walk leaves the vertex by the boundary
edge in the same triangle fan as the edge it arrived by, so the loops are separated rather
than merged into a figure eight; and whenever the walk comes back to a vertex already on it, the
closed part is cut off as its own loop, so every contour is a simple cycle (two holes that share
a corner vertex come out as two loops).

The loss (paper eq. 6, the ``L_CF(X_open, T_open)`` term) is the squared Chamfer distance between
the simulated and the target contour *vertices*. By default all contour points of each mesh are
pooled (no pairing is needed, and it works when the simulated and target meshes have different
numbers of loops); with ``pairs`` the loss is the sum of the Chamfer losses of paired contours.
The weight ``lambda_open = 0.1`` is applied by the caller.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.geometry.topology import extend_walk, unique_edges
from unsew.losses._arrays import mesh_arrays
from unsew.losses.chamfer import loss_chamfer

__all__ = ["Contour", "open_contours", "loss_open_contours"]


@dataclass
class Contour:
    """One boundary loop of a mesh.

    indices: vertex indices in walking order, shape (k,), int64, first not repeated at the end.
    length: perimeter of the closed polyline [m].
    centre: centroid of the polyline as a curve (length-weighted edge midpoints), shape (3,) [m].
    normal: unit normal of the least-squares plane through the points, shape (3,); its sign
        follows the walking direction (right-hand rule).
    """

    indices: np.ndarray
    length: float
    centre: np.ndarray
    normal: np.ndarray

    def points(self, verts):
        """Positions of the contour's vertices: ``verts[indices]``, shape (k, 3) [m] (numpy or torch)."""
        return verts[self.indices]


def _fan_component(v, face_start, faces_at_v, faces, interior_edges):
    """Faces around vertex v reachable from face_start through interior edges (v, w)."""
    seen = {face_start}
    stack = [face_start]
    while stack:
        f = stack.pop()
        for w in faces[f]:
            if w == v:
                continue
            key = (min(v, w), max(v, w))
            if key not in interior_edges:
                continue
            for g in interior_edges[key]:
                if g not in seen and g in faces_at_v:
                    seen.add(g)
                    stack.append(g)
    return seen


def _describe(verts, idx):
    p = verts[idx]  # (k, 3)
    q = np.roll(p, -1, axis=0)
    seg = np.linalg.norm(q - p, axis=1)  # (k,)
    length = float(seg.sum())
    mids = 0.5 * (p + q)
    centre = (mids * seg[:, None]).sum(0) / length if length > 0 else p.mean(0)
    _, _, vt = np.linalg.svd(p - centre, full_matrices=False)
    normal = vt[-1]
    area_vec = np.cross(p - centre, q - centre).sum(0)  # twice the vector area of the loop
    if normal @ area_vec < 0:
        normal = -normal
    return Contour(idx.astype(np.int64), length, centre, normal)


def _boundary_topology(f: np.ndarray, b_edges, und, he_face, bmask) -> dict:
    """Where the boundary walk may turn: ``at`` (vertex -> its boundary edges), the boundary
    vertices met by more than two of them (``nonmanifold``), and only around those the
    interior edges' faces (``interior_edges``, sorted pair -> faces) and each one's faces
    (``faces_at``)."""
    at = {}
    for e, (a, b) in enumerate(b_edges):
        at.setdefault(int(a), []).append(e)
        at.setdefault(int(b), []).append(e)
    nonmanifold = {vv for vv, es in at.items() if len(es) > 2}
    interior_edges = {}
    faces_at = {}
    if nonmanifold:
        nm = np.array(sorted(nonmanifold))
        sel = np.isin(und, nm).any(axis=1) & ~bmask
        for (a, b), fi in zip(und[sel], he_face[sel]):
            interior_edges.setdefault((int(a), int(b)), []).append(int(fi))
        for fi in np.nonzero(np.isin(f, nm).any(axis=1))[0]:
            for vv in f[fi]:
                if int(vv) in nonmanifold:
                    faces_at.setdefault(int(vv), set()).add(int(fi))
    return dict(at=at, nonmanifold=nonmanifold, interior_edges=interior_edges, faces_at=faces_at)


def _next_edges(v_now: int, cur: int, used, b_edges, b_face, f, topo: dict) -> list[int]:
    """The unused boundary edges the walk may take on from vertex v_now after edge cur: those
    leaving v_now (any touching it when the orientation is inconsistent), at a non-manifold
    vertex those of cur's fan of faces when there are such."""
    at = topo["at"]
    cands = [e for e in at[v_now] if not used[e] and int(b_edges[e, 0]) == v_now]
    if not cands:  # inconsistent orientation: accept an edge walked backwards
        cands = [e for e in at[v_now] if not used[e]]
    if len(cands) > 1 and v_now in topo["nonmanifold"]:
        fan = _fan_component(v_now, int(b_face[cur]), topo["faces_at"][v_now], f, topo["interior_edges"])
        same = [e for e in cands if int(b_face[e]) in fan]
        cands = same or cands
    return cands


def open_contours(verts, faces) -> list[Contour]:
    """Boundary loops of a triangle mesh, longest first.

    verts: (V, 3) float64 [m] (numpy or torch, read only for the contour geometry).
    faces: (F, 3) int.
    Returns: list of :class:`Contour`; empty for a closed mesh.
    """
    v, f = mesh_arrays(verts, faces)
    if len(f) == 0:
        return []

    he = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])  # (3F, 2) directed, edge-major
    he_face = np.tile(np.arange(len(f)), 3)
    und = np.sort(he, axis=1)
    _, inv, count = unique_edges(f)  # inv is face-major: reorder it to he's edge-major rows
    inv = inv.reshape(-1, 3).T.ravel()
    bmask = count[inv] == 1
    b_edges = he[bmask]  # (B, 2) directed boundary edges
    b_face = he_face[bmask]
    if len(b_edges) == 0:
        return []
    topo = _boundary_topology(f, b_edges, und, he_face, bmask)

    used = np.zeros(len(b_edges), dtype=bool)
    loops = []
    for e0 in range(len(b_edges)):
        if used[e0]:
            continue
        used[e0] = True
        path = [int(b_edges[e0, 0])]  # vertices of the walk not yet closed into a loop
        pos = {path[0]: 0}
        cur = e0
        v_now = int(b_edges[e0, 1])
        while True:
            cycle = extend_walk(path, pos, v_now)  # a return to a vertex on the walk closes a cycle
            if cycle is not None and len(cycle) >= 3:
                loops.append(_describe(v, np.array(cycle)))
            cands = _next_edges(v_now, cur, used, b_edges, b_face, f, topo)
            if not cands:
                break  # nothing left here (an open chain remaining is not a loop and is dropped)
            cur = cands[0]
            used[cur] = True
            a, b = int(b_edges[cur, 0]), int(b_edges[cur, 1])
            v_now = b if a == v_now else a
    loops.sort(key=lambda c: -c.length)
    return loops


def loss_open_contours(x, contours_x, t, contours_t, *, pairs=None, method: str = "auto"):
    """Squared Chamfer distance between simulated and target contour points (eq. 6's open term).

    x: simulated vertices [m], shape (N, 3), float64 torch tensor.
    contours_x: contours of the simulated mesh (indices into ``x``), from :func:`open_contours`
        on the garment topology (computed once).
    t: target vertices [m], shape (M, 3), float64 torch tensor.
    contours_t: contours of the target (indices into ``t``).
    pairs: optional list of (i, j): contour i of X is compared with contour j of T, and the
        loss is the sum over pairs; default: all contour points of X against all of T.
    Returns: scalar tensor [m^2]; zero-dimensional 0 if either side has no contour.
    """
    import torch

    if not contours_x or not contours_t:
        return (x.sum() + t.sum()) * 0.0
    if pairs is None:
        ix = torch.as_tensor(np.concatenate([c.indices for c in contours_x]), device=x.device)
        it = torch.as_tensor(np.concatenate([c.indices for c in contours_t]), device=t.device)
        return loss_chamfer(x[ix], t[it], method=method)
    total = (x.sum() + t.sum()) * 0.0
    for i, j in pairs:
        ix = torch.as_tensor(contours_x[i].indices, device=x.device)
        it = torch.as_tensor(contours_t[j].indices, device=t.device)
        total = total + loss_chamfer(x[ix], t[it], method=method)
    return total
