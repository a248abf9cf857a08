"""Point-to-mesh queries on libigl's AABB tree: closest points, distances, inside tests.

libigl was chosen over fcpw and embreex on the figures of ``python -m benchmarks geometry``
(docs/benchmarks.md, "Geometry core and memory"): exact in float64, memory that grows with the
queries and triangles only (never with their product, unlike the KD-tree-of-centroids search it
replaces), and one library for closest points, winding numbers and rays.

All positions are metres, float64; faces are int64 triangle indices. Nothing here needs the mesh
to be closed, manifold or evenly triangulated; degenerate triangles count as segments or points.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MeshQuery", "closest_points", "point_mesh_distance", "winding_number", "inside"]


def _arrays(verts, faces) -> tuple[np.ndarray, np.ndarray]:
    v = np.ascontiguousarray(verts, dtype=np.float64)
    f = np.ascontiguousarray(faces, dtype=np.int64)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"verts {v.shape} and faces {f.shape} must be (V, 3) and (F, 3)")
    if len(f) == 0:
        raise ValueError("the mesh has no triangles")
    if f.min() < 0 or f.max() >= len(v):
        raise ValueError(f"face indices must lie in 0..{len(v) - 1}")
    return v, f


def _points(points) -> np.ndarray:
    p = np.ascontiguousarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points {p.shape} must be (P, 3)")
    return p


class MeshQuery:
    """An AABB tree over a triangle mesh, built once and queried many times.

    verts: (V, 3) float64 [m]; faces: (F, 3) int64. Build time and memory are O(F log F) / O(F).
    """

    def __init__(self, verts, faces):
        import igl

        self.verts, self.faces = _arrays(verts, faces)
        self._tree = igl.AABB()
        self._tree.init(self.verts, self.faces)

    def closest(self, points) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Closest points on the surface.

        points: (P, 3) float64 [m]. Returns (closest (P, 3) float64 [m], distance (P,) float64
        [m], face index (P,) int64 of the triangle the closest point lies on).
        """
        p = _points(points)
        if len(p) == 0:
            return np.zeros((0, 3)), np.zeros(0), np.zeros(0, np.int64)
        sq, fi, c = self._tree.squared_distance(self.verts, self.faces, p)
        return np.asarray(c), np.sqrt(np.maximum(sq, 0.0)), np.asarray(fi, dtype=np.int64)

    def distance(self, points) -> np.ndarray:
        """Unsigned distance (P,) float64 [m] from points (P, 3) [m] to the surface."""
        return self.closest(points)[1]


def closest_points(points, verts, faces) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Closest points on a triangle mesh (one-off; use :class:`MeshQuery` to query a mesh often).

    points: (P, 3) float64 [m]; verts: (V, 3) float64 [m]; faces: (F, 3) int.
    Returns (closest (P, 3) float64 [m], distance (P,) float64 [m], face (P,) int64).
    """
    return MeshQuery(verts, faces).closest(points)


def point_mesh_distance(points, verts, faces) -> np.ndarray:
    """Unsigned distance (P,) float64 [m] from points (P, 3) [m] to the mesh (verts (V, 3) [m],
    faces (F, 3) int)."""
    return closest_points(points, verts, faces)[1]


def winding_number(points, verts, faces, *, exact: bool = False) -> np.ndarray:
    """Generalised winding number (P,) float64 [-] of the mesh around each point (P, 3) [m]:
    1 inside a closed outward-oriented surface, 0 outside, fractional near holes. ``exact=False``
    uses libigl's fast (Barnes-Hut) approximation, ``exact=True`` the exact sum of solid angles
    (O(P F), a test oracle)."""
    import igl

    v, f = _arrays(verts, faces)
    p = _points(points)
    if len(p) == 0:
        return np.zeros(0)
    w = igl.winding_number(v, f, p) if exact else igl.fast_winding_number(v, f, p)
    return np.asarray(w, dtype=np.float64)


def inside(points, verts, faces, *, exact: bool = False) -> np.ndarray:
    """Whether each point (P, 3) [m] lies inside the mesh: winding number above 1/2, shape (P,)
    bool. Works for closed and nearly closed (small holes) surfaces of either orientation."""
    return np.abs(winding_number(points, verts, faces, exact=exact)) > 0.5
