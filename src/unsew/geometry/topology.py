"""Triangle-mesh connectivity: half-edges, unique edges, boundary edges and loops, adjacency,
connected components. Pure numpy/scipy, no Python loop over faces (the boundary-loop walk loops
over boundary vertices only).

Conventions (those of trimesh): face ``f = (a, b, c)`` has the half-edges ``(a, b), (b, c),
(c, a)``, stored face-major, so half-edge ``h`` belongs to face ``h // 3``. A unique edge is a
sorted vertex pair. An edge is a boundary edge when one face uses it, interior with two,
non-manifold with three or more. All index arrays are int64.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "half_edges",
    "unique_edges",
    "boundary_edges",
    "boundary_vertices",
    "boundary_loops",
    "edge_faces",
    "vertex_adjacency",
    "components",
]


def _faces(faces) -> np.ndarray:
    f = np.asarray(faces, dtype=np.int64)
    if f.size == 0:
        return f.reshape(0, 3)
    if f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"faces {f.shape} must be (F, 3)")
    return f


def half_edges(faces) -> np.ndarray:
    """Directed edges of every face, (3F, 2) int64, face-major: rows 3i..3i+2 are face i's
    (a, b), (b, c), (c, a)."""
    f = _faces(faces)
    return f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)


def unique_edges(faces) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Undirected edges of a triangle mesh.

    faces: (F, 3) int. Returns (edges (E, 2) int64 sorted rows (lo, hi) in lexicographic order,
    inverse (3F,) int64 the unique edge of each half-edge of :func:`half_edges`, count (E,) int64
    the number of faces on each edge).
    """
    he = np.sort(half_edges(faces), axis=1)
    if len(he) == 0:
        return np.zeros((0, 2), np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64)
    n = int(he.max()) + 1
    key = he[:, 0] * n + he[:, 1]
    uk, inv, cnt = np.unique(key, return_inverse=True, return_counts=True)
    edges = np.stack([uk // n, uk % n], axis=1)
    return edges, inv.reshape(-1).astype(np.int64), cnt.astype(np.int64)


def boundary_edges(faces) -> np.ndarray:
    """Half-edges used by exactly one face, (B, 2) int64, directed as in their face."""
    he = half_edges(faces)
    _, inv, cnt = unique_edges(faces)
    return he[cnt[inv] == 1]


def boundary_vertices(faces, n_verts: int) -> np.ndarray:
    """(n_verts,) bool: True at the ends of boundary edges."""
    out = np.zeros(int(n_verts), dtype=bool)
    out[boundary_edges(faces).ravel()] = True
    return out


def boundary_loops(faces) -> list[np.ndarray]:
    """Boundary loops as vertex index arrays (k,) int64, each oriented like its faces' half-edges
    (a -> b for a boundary half-edge (a, b)), longest first.

    Where a vertex has several outgoing boundary half-edges (two holes touching at a vertex),
    the walk takes them in turn and every time it comes back to a vertex already on its path
    the closed cycle is cut off as a loop of its own; cycles of fewer than 3 vertices are dropped.
    """
    b = boundary_edges(faces)
    if len(b) == 0:
        return []
    order = np.argsort(b[:, 0], kind="stable")
    starts = b[order, 0]
    targets = b[order, 1]
    used = np.zeros(len(b), dtype=bool)
    cursor = {}  # vertex -> next unused outgoing half-edge position

    def take(v: int) -> int:
        i = cursor.get(v)
        if i is None:
            i = int(np.searchsorted(starts, v, side="left"))
        while i < len(starts) and starts[i] == v and used[i]:
            i += 1
        cursor[v] = i
        return i if i < len(starts) and starts[i] == v else -1

    loops = []
    for e0 in range(len(b)):  # positions in the sorted order
        if used[e0]:
            continue
        path, pos = [int(starts[e0])], {int(starts[e0]): 0}
        e = e0
        while e >= 0:
            used[e] = True
            w = int(targets[e])
            if w in pos:  # closed a cycle: cut it off
                k = pos[w]
                if len(path) - k >= 3:
                    loops.append(np.array(path[k:], dtype=np.int64))
                for u in path[k + 1 :]:
                    del pos[u]
                path = path[: k + 1]
            else:
                pos[w] = len(path)
                path.append(w)
            e = take(w)
    loops.sort(key=len, reverse=True)
    return loops


def edge_faces(faces) -> tuple[np.ndarray, np.ndarray]:
    """Faces on each side of each interior edge (an edge with exactly two faces).

    Returns (edges (I, 2) int64 sorted vertex pairs, faces (I, 2) int64: the face whose half-edge
    comes first in :func:`half_edges` order, then the other).
    """
    edges, inv, cnt = unique_edges(faces)
    order = np.argsort(inv, kind="stable")
    first = np.searchsorted(inv[order], np.arange(len(edges)))
    two = np.flatnonzero(cnt == 2)
    h = np.stack([order[first[two]], order[first[two] + 1]], axis=1)  # (I, 2) half-edges
    return edges[two], h // 3


def vertex_adjacency(faces, n_verts: int):
    """Symmetric vertex adjacency, scipy CSR (n_verts, n_verts) bool, True where an edge joins
    two vertices."""
    import scipy.sparse as sp

    e = half_edges(faces)
    e = np.concatenate([e, e[:, ::-1]])
    n = int(n_verts)
    return sp.coo_matrix((np.ones(len(e), dtype=bool), (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()


def components(faces, n_verts: int, *, by: str = "edge") -> tuple[int, np.ndarray]:
    """Connected components of the faces.

    by: "edge" (faces sharing an edge are connected; two surfaces touching at a single vertex
    are separate) or "vertex" (sharing any vertex connects). Returns (count, label (F,) int64).
    """
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    f = _faces(faces)
    if len(f) == 0:
        return 0, np.zeros(0, np.int64)
    if by == "vertex":
        adj = vertex_adjacency(f, n_verts)
        _, lab = connected_components(adj, directed=False)
        n, lab = np.unique(lab[f[:, 0]], return_inverse=True)
        return len(n), lab.astype(np.int64)
    if by != "edge":
        raise ValueError(f"by must be 'edge' or 'vertex', got {by!r}")
    _, inv, _ = unique_edges(f)
    # bipartite graph face -- edge; components of faces through shared edges
    F, E = len(f), int(inv.max()) + 1
    fid = np.repeat(np.arange(F), 3)
    g = sp.coo_matrix((np.ones(3 * F, dtype=bool), (fid, F + inv)), shape=(F + E, F + E))
    _, lab = connected_components(g, directed=False)
    n, lab = np.unique(lab[:F], return_inverse=True)
    return len(n), lab.astype(np.int64)
