"""Point-to-mesh queries on libigl's AABB tree: closest points, distances, ray hits, inside tests.

libigl was chosen over fcpw and embreex on the figures of ``python -m benchmarks geometry``:
exact in float64, memory that grows with the
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


def _spread_bits(x: np.ndarray) -> np.ndarray:
    """10-bit integers (N,) -> their bits spread to every third position (N,) uint64."""
    x = x.astype(np.uint64) & np.uint64(0x3FF)
    for shift, mask in ((16, 0x030000FF), (8, 0x0300F00F), (4, 0x030C30C3), (2, 0x09249249)):
        x = (x | (x << np.uint64(shift))) & np.uint64(mask)
    return x


def _spatial_order(p: np.ndarray) -> np.ndarray:
    """Permutation (P,) int64 putting points (P, 3) in Morton (Z-curve) order on a 1024^3 grid
    over their bounding box: neighbouring queries then walk the same tree nodes, which halves
    libigl's query time (python -m benchmarks geometry)."""
    lo, hi = p.min(0), p.max(0)
    g = ((p - lo) / np.maximum(hi - lo, 1e-300) * 1023.0).astype(np.int64)
    code = (
        _spread_bits(g[:, 0])
        | (_spread_bits(g[:, 1]) << np.uint64(1))
        | (_spread_bits(g[:, 2]) << np.uint64(2))
    )
    return np.argsort(code, kind="stable")


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
        order = _spatial_order(p) if len(p) > 256 else None
        q = p[order] if order is not None else p
        sq, fi, c = self._tree.squared_distance(self.verts, self.faces, q)
        c, d, fi = np.asarray(c), np.sqrt(np.maximum(sq, 0.0)), np.asarray(fi, dtype=np.int64)
        if order is not None:  # back to the caller's order
            inv = np.empty_like(order)
            inv[order] = np.arange(len(order))
            c, d, fi = c[inv], d[inv], fi[inv]
        return c, d, fi

    def distance(self, points) -> np.ndarray:
        """Unsigned distance (P,) float64 [m] from points (P, 3) [m] to the surface."""
        return self.closest(points)[1]

    def first_hit(self, origins, directions, *, max_distance: float = np.inf):
        """First intersection of rays with the surface.

        origins: (R, 3) float64 [m]; directions: (R, 3) (any length, normalised here).
        max_distance: ignore hits farther than this [m]. Returns (hit (R,) bool, distance (R,)
        float64 [m] along the ray, inf where no hit, face (R,) int64, -1 where no hit, point
        (R, 3) float64 [m], NaN where no hit).
        """
        o = _points(origins)
        d = _points(directions)
        if d.shape != o.shape:
            raise ValueError(f"directions {d.shape} must match origins {o.shape}")
        n = np.linalg.norm(d, axis=1, keepdims=True)
        if not (n > 0).all():
            raise ValueError("ray directions must be non-zero")
        d = np.ascontiguousarray(d / n)
        if len(o) == 0:
            return np.zeros(0, bool), np.zeros(0), np.zeros(0, np.int64), np.zeros((0, 3))
        fi, t, _ = self._tree.intersect_ray_first(self.verts, self.faces, o, d, float(max_distance))
        fi = np.asarray(fi, dtype=np.int64)
        hit = fi >= 0
        t = np.where(hit, np.asarray(t, dtype=np.float64), np.inf)
        p = np.where(hit[:, None], o + np.where(hit, t, 0.0)[:, None] * d, np.nan)
        return hit, t, np.where(hit, fi, -1), p


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
