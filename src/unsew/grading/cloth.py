"""Cloth lengths: how much cloth lies between an open contour and the garment's top opening.

Algorithm 2 moves an open curve by the axial distance between the paired contours along the
bone. Where the cloth hangs along the bone (a sleeve, a straight hem) the two agree; where it
does not (a flared skirt whose waist rides up the hips), the drape answers a pattern change
only in part and the axial distance under-reads the pattern (``python -m benchmarks grading
--drape sim``, the skirt's ``axial cm`` column; docs/decisions/003). The cloth length reads the change in the
cloth itself: the mean, over a contour's vertices, of the shortest path *along the surface* to the garment's
top contour (the neckline of a top or a dress, the waist of trousers or a skirt). A path that runs across
folds and flare follows them, so trousers whose longer legs fold on the feet still read their length.
bench_grading prints, per contour, the drapes' cloth-length difference (``cloth cm``) beside the true
patterns' own at rest (``rest cm``).

Shortest paths are graph distances (Dijkstra) on the mesh's edges plus, for every pair of
triangles sharing an edge, the straight path between their two opposite vertices across that edge
with the two triangles unfolded flat (across a fold the chord would jump it): edges alone
zig-zag and read straight paths several percent long, the opposite-vertex segments cut that
excess (``tests/grading/test_cloth.py`` bounds it). The excess depends on the direction of the path across the
triangles, much the same on two meshes of one garment, so it largely cancels in the difference grading uses.

The same lengths measured at rest (the pattern's 2D edge lengths, seams joined) are what grading
edits: ``rest_cloth_lengths`` on a :class:`~unsew.meshing.sew.GarmentMesh`.
"""

from __future__ import annotations

import numpy as np

from unsew.geometry.topology import unique_edges

__all__ = ["distance_graph", "cloth_distance", "top_contour", "cloth_lengths", "rest_cloth_lengths"]


def distance_graph(points: np.ndarray, faces: np.ndarray):
    """The surface graph of a triangle mesh as a symmetric scipy CSR matrix.

    points: (N, D) float64 vertex positions (D = 2 or 3) [m]; faces: (F, 3) int.
    Weights [m]: every edge's length and, for two triangles sharing an edge, the straight path
    between their opposite vertices *across the shared edge with the two triangles unfolded
    flat* (the surface path, not the chord: across a fold the chord would jump the fold), kept
    only where that path does cross the shared edge.
    """
    import scipy.sparse as sp

    x = np.asarray(points, dtype=np.float64)
    if x.shape[1] == 2:
        x = np.c_[x, np.zeros(len(x))]
    f = np.asarray(faces, dtype=np.int64)
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    opp = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    key = np.sort(e, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    k, o = key[order], opp[order]
    same = np.flatnonzero(np.all(k[1:] == k[:-1], axis=1))
    a, b, c, d = k[same, 0], k[same, 1], o[same], o[same + 1]
    # unfold: a at 0, b on the first axis; c above it, d below it
    ab = x[b] - x[a]
    lab = np.linalg.norm(ab, axis=1)
    ok = lab > 0
    u = ab / np.where(ok, lab, 1.0)[:, None]

    def plane(p):
        along = np.einsum("ij,ij->i", x[p] - x[a], u)
        off = np.linalg.norm(x[p] - x[a] - along[:, None] * u, axis=1)
        return along, off

    (cx, cy), (dx, dy) = plane(c), plane(d)
    cross = cx + (dx - cx) * cy / np.maximum(cy + dy, 1e-300)
    ok &= (cy + dy > 0) & (cross > 0) & (cross < lab) & (c != d)
    across = np.stack([c[ok], d[ok]], axis=1)
    w_across = np.hypot(cx - dx, cy + dy)[ok]

    edges = unique_edges(f)[0]  # (E, 2) sorted, as np.unique(key, axis=0)
    pairs = np.concatenate([edges, np.sort(across, axis=1)])
    w = np.concatenate([np.linalg.norm(x[edges[:, 0]] - x[edges[:, 1]], axis=1), w_across])
    pairs, w = _shortest_once(pairs, w)
    n = len(x)
    return sp.coo_matrix(
        (np.r_[w, w], (np.r_[pairs[:, 0], pairs[:, 1]], np.r_[pairs[:, 1], pairs[:, 0]])), shape=(n, n)
    ).tocsr()


def _shortest_once(pairs: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each unordered pair (sorted, (E, 2) int64) once, with its smallest weight (E,) [m]; self
    pairs dropped (a sparse matrix would add repeated entries up)."""
    keep = pairs[:, 0] != pairs[:, 1]
    pairs, w = pairs[keep], w[keep]
    order = np.lexsort((w, pairs[:, 1], pairs[:, 0]))
    pairs, w = pairs[order], w[order]
    first = np.r_[True, np.any(pairs[1:] != pairs[:-1], axis=1)] if len(pairs) else np.zeros(0, dtype=bool)
    return pairs[first], w[first]


def cloth_distance(graph, sources: np.ndarray) -> np.ndarray:
    """(N,) float64 [m]: the surface distance of every vertex to the nearest of ``sources``
    (inf where no path exists). graph: :func:`distance_graph`; sources: vertex indices."""
    from scipy.sparse.csgraph import dijkstra

    src = np.unique(np.asarray(sources, dtype=np.int64))
    if len(src) == 0:
        return np.full(graph.shape[0], np.inf)
    return np.asarray(dijkstra(graph, directed=False, indices=src, min_only=True), dtype=np.float64)


def top_contour(placed: list):
    """The garment's top opening: the contour whose centre is highest (+y, FORMATS.md), the
    neckline of a top or a dress, the waist of trousers or a skirt. None for no contours."""
    if not placed:
        return None
    return max(placed, key=lambda c: float(c.centre[1]))


def cloth_lengths(points: np.ndarray, faces: np.ndarray, placed: list) -> tuple[object, dict]:
    """(top, {contour index: cloth length [m]}) of every contour but the top one.

    points: (N, 3) float64 [m]; faces: (F, 3) int; placed: the mesh's
    :class:`~unsew.grading.contours.PlacedContour` list. A contour's cloth length is the mean of
    its vertices' surface distances to the top contour; contours with no path to it are left out.
    """
    top = top_contour(placed)
    if top is None:
        return None, {}
    d = cloth_distance(distance_graph(points, faces), top.rim)
    out = {}
    for c in placed:
        if c is top:
            continue
        v = d[c.rim]  # a slit's climb is no cloth length (grading.contours.slits)
        if len(v) and np.all(np.isfinite(v)):
            out[c.index] = float(v.mean())
    return top, out


def rest_cloth_lengths(mesh, curves: dict, top_edges: list) -> dict:
    """{key: cloth length at rest [m]} on a garment mesh, from the pattern's 2D edge lengths.

    mesh: :class:`~unsew.meshing.sew.GarmentMesh`; curves: key -> list of (panel name, edge
    index) forming a contour; top_edges: the (panel name, edge index) of the top contour.
    The graph is each panel's own (in uv) joined at the seams (sewn vertices); a contour's length
    is the mean over the sewn vertices of its edges of the distance to the top's. Keys with no
    path are left out.
    """
    import scipy.sparse as sp

    g = distance_graph(mesh.uv, mesh.faces_uv).tocoo()
    xi, xj = mesh.x_of_u[g.row], mesh.x_of_u[g.col]
    # a seam edge is in both panels: each sewn pair once, at its shorter reading
    pairs, w = _shortest_once(np.stack([np.minimum(xi, xj), np.maximum(xi, xj)], axis=1), g.data)
    n = mesh.n_x
    graph = sp.coo_matrix(
        (np.r_[w, w], (np.r_[pairs[:, 0], pairs[:, 1]], np.r_[pairs[:, 1], pairs[:, 0]])), shape=(n, n)
    ).tocsr()

    def verts(edges):
        if not edges:
            return np.zeros(0, dtype=np.int64)
        return np.unique(np.concatenate([mesh.x_of_u[mesh.edge_verts[pe]] for pe in edges]))

    d = cloth_distance(graph, verts(top_edges))
    out = {}
    for key, edges in curves.items():
        v = d[verts(edges)]
        if len(v) and np.all(np.isfinite(v)):
            out[key] = float(v.mean())
    return out
