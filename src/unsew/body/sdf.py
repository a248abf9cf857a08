"""Signed distance to the body, on a grid, queried differentiably in torch (paper 3.4.4).

Build (numpy/scipy, once per body, cached on disk):

1. Exact unsigned distance in a narrow band: every grid node within ``1.5 * voxel`` of a
   triangle's bounding box gets the exact point-triangle distance (closest point by Voronoi
   regions, Ericson, *Real-Time Collision Detection* 5.1.5), the smallest over triangles kept
   with its closest point.
2. Farther out, closest-point propagation: each node takes the surface closest point of the
   nearest band node (``scipy.ndimage.distance_transform_edt`` with indices), then two sweeps
   take the best closest point among the six neighbours'. The distance is the exact distance to
   that surface point, so it is exact wherever the nearest band node's closest point is the true
   one (away from the medial axis), and an upper bound elsewhere.
3. Sign: nodes farther than half a voxel from the surface are inside or outside by a 6-connected
   flood fill of the exterior from the grid's corner (the shell of nodes within half a voxel
   blocks every grid edge that crosses the surface); shell nodes take the sign of the
   angle-weighted pseudonormal at their closest point (Baerentzen & Aanaes 2005), reliable that
   close to a closed surface.
4. Floor: the body stands on the ground, the plane y = its lowest point (Y up): each node takes
   the smaller of its distance to the body and its height above that plane, so cloth long
   enough to reach the ground rests on it (``floor=False``: the body alone).

Query: ``sdf.query(x)`` trilinearly interpolates the distance grid and its gradient grid (central
differences, precomputed) by one gather of the 8 corners of each point's cell from a
channel-last table (faster than ``torch.nn.functional.grid_sample`` with 4 channels here): ``d`` is
differentiable in ``x`` (first and second derivatives, those of the trilinear interpolant), ``n`` is the
interpolated gradient normalised (continuous across cells, unlike autograd's gradient of ``d``).
Points outside the grid get the distance at the nearest grid point plus the distance to it.
Inside is negative. Any object with this ``query`` method is an SDF for the simulator.
"""

from __future__ import annotations

import hashlib
import math
import os
import time
from dataclasses import dataclass, field

import numpy as np

from unsew.body.body import mirror_plane
from unsew.errors import InputError
from unsew.geometry.topology import unique_edges
from unsew.io.atomic import atomic_write

__all__ = ["BodySDF", "closest_point_on_triangles", "mesh_distance", "default_cache_dir"]

#: Bump when the build changes, so cached grids are rebuilt.
_SDF_VERSION = 4
#: Node-triangle pairs the band step takes at once (its temporaries are ~20 (pairs, 3) float64
#: arrays: 1e6 pairs hold ~0.5 GB; ``python -m benchmarks sdf`` measures the peak).
_BAND_PAIRS = 1_000_000
#: Nodes closer than this to the surface get a neighbour sweep after propagation [m].
_SWEEP_RADIUS = 0.06


def default_cache_dir() -> str:
    """``$UNSEW_CACHE`` or ``~/.cache/unsew`` (the folder SDF grids are cached in)."""
    return os.environ.get("UNSEW_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "unsew")


# -- exact point-triangle distance -----------------------------------------------------------


def closest_point_on_triangles(
    p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Closest point on triangle (a, b, c) to p, row by row (Ericson 5.1.5, Voronoi regions).

    p, a, b, c: (N, 3) float64 [m]. Returns (q (N, 3) float64 [m], region (N,) int8) with
    region 0 = face interior, 1/2/3 = vertex a/b/c, 4/5/6 = edge ab/bc/ca.
    """
    ab, ac, ap = b - a, c - a, p - a
    d1 = np.einsum("ij,ij->i", ab, ap)
    d2 = np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3 = np.einsum("ij,ij->i", ab, bp)
    d4 = np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5 = np.einsum("ij,ij->i", ab, cp)
    d6 = np.einsum("ij,ij->i", ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    tiny = 1e-30
    with np.errstate(divide="ignore", invalid="ignore"):
        den = va + vb + vc
        den = np.where(np.abs(den) < tiny, tiny, den)
        v = vb / den
        w = vc / den
        q = a + ab * v[:, None] + ac * w[:, None]
        region = np.zeros(len(p), dtype=np.int8)
        # overrides in reverse priority: the first matching test of Ericson's order wins last
        t = (d4 - d3) / np.maximum((d4 - d3) + (d5 - d6), tiny)
        q = _override(q, region, (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0), b + (c - b) * t[:, None], 5)
        t = d2 / np.where(np.abs(d2 - d6) < tiny, tiny, d2 - d6)
        q = _override(q, region, (vb <= 0) & (d2 >= 0) & (d6 <= 0), a + ac * t[:, None], 6)
        q = _override(q, region, (d6 >= 0) & (d5 <= d6), c, 3)
        t = d1 / np.where(np.abs(d1 - d3) < tiny, tiny, d1 - d3)
        q = _override(q, region, (vc <= 0) & (d1 >= 0) & (d3 <= 0), a + ab * t[:, None], 4)
        q = _override(q, region, (d3 >= 0) & (d4 <= d3), b, 2)
        q = _override(q, region, (d1 <= 0) & (d2 <= 0), a, 1)
    return q, region


def _override(q: np.ndarray, region: np.ndarray, m: np.ndarray, point: np.ndarray, code: int) -> np.ndarray:
    """Closest points (N, 3) with rows ``m`` replaced by ``point`` (N, 3) or (3,); ``region``
    (N,) int8 set to ``code`` there (in place)."""
    region[m] = code
    return np.where(m[:, None], point, q)


def mesh_distance(
    points: np.ndarray, verts: np.ndarray, faces: np.ndarray, *, chunk: int = 2_000_000
) -> tuple[np.ndarray, np.ndarray]:
    """Exact unsigned distance from points to a triangle mesh by brute force (a test oracle and
    for small meshes; O(N F)).

    points: (N, 3), verts: (V, 3) float64 [m]; faces: (F, 3) int. Returns (d (N,) [m],
    closest triangle (N,) int64).
    """
    points = np.asarray(points, np.float64)
    A, B, C = (verts[faces[:, k]] for k in range(3))
    F = len(faces)
    best = np.full(len(points), np.inf)
    arg = np.zeros(len(points), np.int64)
    step = max(1, chunk // F)
    for s in range(0, len(points), step):
        p = points[s : s + step]
        P = np.repeat(p, F, axis=0)
        q, _ = closest_point_on_triangles(
            P, np.tile(A, (len(p), 1)), np.tile(B, (len(p), 1)), np.tile(C, (len(p), 1))
        )
        d = np.linalg.norm(P - q, axis=1).reshape(len(p), F)
        arg[s : s + step] = d.argmin(axis=1)
        best[s : s + step] = d.min(axis=1)
    return best, arg


def _pseudonormals(verts: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Face normals (F,3), angle-weighted vertex normals (V,3), edge normals per (face, local
    edge ab/bc/ca) (F,3,3); unnormalised where only the sign of a dot product matters."""
    A, B, C = (verts[faces[:, k]] for k in range(3))
    fn = np.cross(B - A, C - A)
    fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-30)
    vn = np.zeros_like(verts)
    for k, (P, Q, R) in enumerate(((A, B, C), (B, C, A), (C, A, B))):
        e1, e2 = Q - P, R - P
        cos = np.einsum("ij,ij->i", e1, e2) / np.maximum(
            np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1), 1e-30
        )
        ang = np.arccos(np.clip(cos, -1.0, 1.0))
        np.add.at(vn, faces[:, k], fn * ang[:, None])

    _, inv, _ = unique_edges(faces)  # (3F,) edge of each (face, local edge ab/bc/ca)
    en_u = np.zeros((inv.max() + 1, 3))
    np.add.at(en_u, inv, np.repeat(fn, 3, axis=0))
    en = en_u[inv].reshape(-1, 3, 3)
    return fn, vn, en


# -- the grid --------------------------------------------------------------------------------


def _band(verts, faces, origin, h, shape, r):
    """Exact distance on nodes near triangles: flat node index -> (distance, triangle)."""
    nz, ny, nx = shape
    A, B, C = (verts[faces[:, k]] for k in range(3))
    lo = np.minimum(np.minimum(A, B), C) - r
    hi = np.maximum(np.maximum(A, B), C) + r
    i0 = np.clip(np.ceil((lo - origin) / h).astype(np.int64), 0, [nx - 1, ny - 1, nz - 1])
    i1 = np.clip(np.floor((hi - origin) / h).astype(np.int64), 0, [nx - 1, ny - 1, nz - 1])
    ext = np.maximum(i1 - i0 + 1, 0)  # (F, 3) nodes per axis (x, y, z)
    cnt = ext.prod(axis=1)
    best_d = np.full(nx * ny * nz, np.inf)
    best_t = np.full(nx * ny * nz, -1, dtype=np.int64)
    F = len(faces)
    budget = _BAND_PAIRS
    s = 0
    while s < F:
        # triangles s..e with at most `budget` node-triangle pairs
        cum = np.cumsum(cnt[s:])
        e = s + max(1, int(np.searchsorted(cum, budget, side="right")))
        tri = np.repeat(np.arange(s, e), cnt[s:e])
        start = np.repeat(np.cumsum(cnt[s:e]) - cnt[s:e], cnt[s:e])
        loc = np.arange(len(tri)) - start
        ex = ext[tri]
        ix = loc % ex[:, 0]
        iy = (loc // ex[:, 0]) % ex[:, 1]
        iz = loc // (ex[:, 0] * ex[:, 1])
        gx, gy, gz = i0[tri, 0] + ix, i0[tri, 1] + iy, i0[tri, 2] + iz
        p = origin + h * np.stack([gx, gy, gz], axis=1).astype(np.float64)
        q, _ = closest_point_on_triangles(p, A[tri], B[tri], C[tri])
        d = np.linalg.norm(p - q, axis=1)
        node = (gz * ny + gy) * nx + gx
        order = np.lexsort((d, node))
        node, d, tri = node[order], d[order], tri[order]
        first = np.ones(len(node), bool)
        first[1:] = node[1:] != node[:-1]
        node, d, tri = node[first], d[first], tri[first]
        better = d < best_d[node]
        best_d[node[better]] = d[better]
        best_t[node[better]] = tri[better]
        s = e
    return best_d, best_t


@dataclass
class BodySDF:
    """A signed distance grid.

    values: (nz, ny, nx) float64 [m] signed distance at node (ix, iy, iz), negative inside.
    origin: (3,) float64 [m], position of node (0, 0, 0) (the grid's min corner).
    voxel: node spacing [m].
    """

    values: np.ndarray
    origin: np.ndarray
    voxel: float
    build_seconds: float = 0.0
    _dev: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def shape(self) -> tuple[int, int, int]:
        """(nz, ny, nx) nodes."""
        return tuple(self.values.shape)

    @property
    def upper(self) -> np.ndarray:
        """(3,) float64 [m], the grid's max corner."""
        nz, ny, nx = self.values.shape
        return self.origin + self.voxel * np.array([nx - 1, ny - 1, nz - 1], dtype=np.float64)

    # -- building ---------------------------------------------------------------------------
    @classmethod
    def build(
        cls,
        body,
        *,
        voxel: float = 0.005,
        margin: float = 0.1,
        cache_dir: str | os.PathLike | None = None,
        use_cache: bool = True,
        floor: bool = True,
    ) -> "BodySDF":
        """Signed distance grid of a closed body surface over its bounding box plus ``margin``.

        body: a ``Body`` (or any object with ``verts`` (V,3) float64 [m] and ``faces`` (F,3)).
        voxel: node spacing [m] (<= 0.005 for accurate contact); margin [m].
        cache_dir: folder of cached grids (default ``default_cache_dir()``), keyed by a hash of
        verts, faces, voxel, margin and floor; ``use_cache=False`` neither reads nor writes it.
        floor: the ground under the body's lowest point is part of the solid (module docstring).
        """
        verts = np.ascontiguousarray(body.verts, dtype=np.float64)
        faces = np.ascontiguousarray(body.faces, dtype=np.int64)
        if not (voxel > 0 and margin >= 0):
            raise InputError(f"SDF voxel ({voxel}) must be > 0 and margin ({margin}) >= 0 [m]")
        n_nodes = np.prod(np.ceil((verts.max(0) - verts.min(0) + 2 * margin) / voxel) + 2)
        if n_nodes > 6e7:
            raise InputError(
                f"SDF grid of {n_nodes:.3g} nodes is too large (voxel {voxel} m over a "
                f"{np.ptp(verts, axis=0).round(2).tolist()} m body); is the body in metres?"
            )
        path = None
        if use_cache:
            hsh = hashlib.sha256()
            hsh.update(verts.tobytes())
            hsh.update(faces.tobytes())
            hsh.update(np.array([voxel, margin, _SDF_VERSION, float(floor)], dtype=np.float64).tobytes())
            folder = os.fspath(cache_dir) if cache_dir is not None else default_cache_dir()
            path = os.path.join(folder, f"sdf_{hsh.hexdigest()[:24]}.npz")
            if os.path.isfile(path):
                try:
                    with np.load(path) as z:
                        return cls(z["values"].astype(np.float64), z["origin"], float(z["voxel"]))
                except Exception:  # a corrupt cache entry is rebuilt
                    pass
        t0 = time.perf_counter()
        values, origin = _build_grid(verts, faces, voxel, margin)
        values = _on_ground(values, origin, voxel, float(verts[:, 1].min())) if floor else values
        # the cache stores float32: round a fresh grid the same way, so a run is reproducible
        # whether its grid was built or read (the drape of loose cloth amplifies the difference)
        values = values.astype(np.float32).astype(np.float64)
        sdf = cls(values, origin, float(voxel), build_seconds=time.perf_counter() - t0)
        if path is not None:
            try:
                os.makedirs(os.path.dirname(path), exist_ok=True)

                with atomic_write(path) as tmp:
                    with open(tmp, "wb") as fh:
                        np.savez(fh, values=values.astype(np.float32), origin=origin, voxel=np.float64(voxel))
            except OSError:
                pass  # an unwritable cache only costs a rebuild next time
        return sdf

    def inflated(self, by: float) -> "BodySDF":
        """The same grid for the body grown outward by ``by`` [m] (every distance lowered by it):
        contact then keeps cloth ``by`` farther from the body. ``by`` 0 returns
        this grid itself."""
        if by == 0.0:
            return self
        if not math.isfinite(by) or by < 0:
            raise InputError(f"a body can be inflated by a distance >= 0 [m], got {by}")
        return BodySDF(self.values - by, self.origin, self.voxel, build_seconds=self.build_seconds)

    # -- querying ---------------------------------------------------------------------------
    def _tensors(self, device, dtype):
        import torch

        key = (str(device), dtype)
        t = self._dev.get(key)
        if t is None:
            nz, ny, nx = self.values.shape
            t = dict(
                table=torch.as_tensor(self._table(), dtype=dtype, device=device),
                lo=torch.as_tensor(self.origin, dtype=dtype, device=device),
                hi=torch.as_tensor(self.upper, dtype=dtype, device=device),
                last=torch.tensor([nx - 2, ny - 2, nz - 2], device=device),
                stride=torch.tensor([1, nx, nx * ny], device=device),
            )
            bits = torch.tensor([[k & 1, (k >> 1) & 1, (k >> 2) & 1] for k in range(8)], device=device)
            t["corner_offsets"] = (bits * t["stride"]).sum(dim=1)  # (8,) flat offsets of the corners
            self._dev[key] = t
        return t

    def _table(self) -> np.ndarray:
        """(nodes, 4) float64 channel-last table: distance [m] and its gradient (d/dx, d/dy, d/dz)
        by central differences (one-sided at the faces, as ``np.gradient``), node (ix, iy, iz)
        at row ``(iz * ny + iy) * nx + ix``. Filled one channel at a time, so building it holds
        the table and one gradient component (not all three gradients and two stacked copies)."""
        table = np.empty(self.values.shape + (4,), dtype=np.float64)  # (nz, ny, nx, 4)
        table[..., 0] = self.values
        for ch, axis in ((1, 2), (2, 1), (3, 0)):  # x, y, z: the grid's axes 2, 1, 0
            table[..., ch] = np.gradient(self.values, self.voxel, axis=axis)
        return table.reshape(-1, 4)

    def query(self, x):
        """Signed distance and outward normal at points.

        x: torch (N, 3) float32/float64 [m], any device. Returns (d (N,) [m], n (N, 3) unit),
        same dtype and device; differentiable in x (d twice, via the trilinear interpolant).
        """
        import torch

        T = self._tensors(x.device, x.dtype)
        lo, hi = T["lo"], T["hi"]
        xc = torch.minimum(torch.maximum(x, lo), hi)  # (N, 3) clamped into the grid
        f = (xc - lo) / self.voxel  # (N, 3) continuous node coordinates (x, y, z)
        i0 = torch.minimum(f.detach().floor().long(), T["last"])  # (N, 3) cell's lower corner
        t = f - i0.to(f.dtype)  # (N, 3) in [0, 1], carries the gradient
        base = (i0 * T["stride"]).sum(dim=1)  # (N,)
        corners = (base[:, None] + T["corner_offsets"]).reshape(-1)  # index_select: faster than indexing
        vals = torch.index_select(T["table"], 0, corners).view(-1, 8, 4)  # (N, 8, 4) at the cell's corners
        w1 = torch.stack([1 - t, t], dim=2)  # (N, 3, 2) 1D weights per axis (x, y, z)
        # (N, 8) trilinear weights, corner k = 4 dz + 2 dy + dx
        w = (w1[:, 2, :, None, None] * w1[:, 1, None, :, None] * w1[:, 0, None, None, :]).reshape(-1, 8)
        s = (vals * w[:, :, None]).sum(dim=1)  # (N, 4): d, grad
        out = x - xc
        dist_out = torch.sqrt((out * out).sum(dim=1) + 1e-30) - 1e-15  # 0 inside the box
        d = s[:, 0] + dist_out
        grad = s[:, 1:]  # (N, 3)
        n = grad / torch.clamp(torch.linalg.norm(grad, dim=1, keepdim=True), min=1e-12)
        return d, n

    @classmethod
    def from_function(cls, fn, lo, hi, *, voxel: float) -> "BodySDF":
        """Grid of an analytic signed distance ``fn(points (M,3) float64 [m]) -> (M,) [m]`` over
        the box [lo, hi] (each (3,) [m]); for tests and simple bodies."""
        lo = np.asarray(lo, np.float64)
        n = np.ceil((np.asarray(hi, np.float64) - lo) / voxel).astype(int) + 1
        zs, ys, xs = (lo[k] + voxel * np.arange(n[k]) for k in (2, 1, 0))
        Z, Y, X = np.meshgrid(zs, ys, xs, indexing="ij")
        v = fn(np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)).reshape(Z.shape)
        return cls(np.asarray(v, np.float64), lo, float(voxel))


def _on_ground(values: np.ndarray, origin: np.ndarray, voxel: float, y0: float) -> np.ndarray:
    """The grid values (nz, ny, nx) [m] of the body standing on the plane y = y0 [m]: each node's
    smaller of its distance to the body and its height above that plane."""
    above = origin[1] + voxel * np.arange(values.shape[1]) - y0  # (ny,)
    return np.minimum(values, above[None, :, None])


def _build_grid(
    verts: np.ndarray, faces: np.ndarray, h: float, margin: float
) -> tuple[np.ndarray, np.ndarray]:
    """(values (nz, ny, nx) float64 [m], origin (3,) [m]) of the signed distance of a closed mesh.

    A mirror-symmetric body (:func:`unsew.body.body.mirror_plane`) gets a grid whose nodes are
    symmetric about its plane and values averaged with their mirror images, so the distance is
    exactly symmetric: grid alignment and interpolation would otherwise differ at mirror points
    and seed asymmetric folds of loose cloth.
    """
    origin, shape, plane = _grid_frame(verts, h, margin)
    near = _nearest_surface(verts, faces, origin, h, shape)
    sign = _grid_sign(verts, faces, near, h, shape)
    values = (sign * near.dist).reshape(shape)
    if plane is not None:
        values = 0.5 * (values + values[:, :, ::-1])
    return values, origin


def _grid_frame(verts: np.ndarray, h: float, margin: float):
    """Grid origin (3,) [m], shape (nz, ny, nx) and the body's mirror plane x [m] (or None);
    a mirrored body's nodes are placed symmetric about its plane."""
    origin = verts.min(axis=0) - margin
    n = np.ceil((verts.max(axis=0) + margin - origin) / h).astype(np.int64) + 1  # (nx, ny, nz)
    plane = mirror_plane(verts)
    if plane is not None:
        k = int(np.ceil(max(plane - origin[0], verts[:, 0].max() + margin - plane) / h))
        origin[0] = plane - k * h
        n[0] = 2 * k + 1
    nx, ny, nz = (int(v) for v in n)
    return origin, (nz, ny, nx), plane


#: Grid nodes handled at once where a step needs their positions (bounds the build's memory:
#: (chunk, 3) float64 temporaries instead of (nodes, 3)).
_NODE_CHUNK = 1 << 20


@dataclass
class _Nearest:
    """Closest surface point of every grid node: the grid (``origin`` (3,) [m], spacing ``h``
    [m], ``shape`` (nz, ny, nx)), band closest points ``Q`` (B, 3) [m] with their Voronoi
    ``region`` (B,) and triangle ``bt`` (B,), ``src`` (nnodes,) the band entry each node takes,
    ``dist`` (nnodes,) unsigned distance [m]."""

    origin: np.ndarray
    h: float
    shape: tuple
    Q: np.ndarray
    region: np.ndarray
    bt: np.ndarray
    src: np.ndarray
    dist: np.ndarray

    def points(self, nodes) -> np.ndarray:
        """(n, 3) float64 [m] positions of the flat node indices ``nodes`` (n,)."""
        return _node_points(nodes, self.origin, self.h, self.shape)


def _node_points(nodes, origin, h: float, shape) -> np.ndarray:
    """(n, 3) float64 [m] positions of flat node indices (n,) int, node (ix, iy, iz) at
    ``(iz * ny + iy) * nx + ix``."""
    _, ny, nx = shape
    gz, rem = np.divmod(np.asarray(nodes, dtype=np.int64), ny * nx)
    gy, gx = np.divmod(rem, nx)
    return origin + h * np.stack([gx, gy, gz], axis=1).astype(np.float64)


def _nearest_surface(verts, faces, origin, h: float, shape) -> _Nearest:
    """Exact closest points in a band of 1.5 h about the surface, propagated to every node by a
    Euclidean distance transform and corrected by one neighbour sweep near the surface.
    Per-node arrays are at most (nodes,) 8-byte wide; positions are made chunk by chunk."""
    from scipy import ndimage

    nz, ny, nx = shape
    r = 1.5 * h
    best_d, best_t = _band(verts, faces, origin, h, shape, r)
    band = best_d <= r  # exact there: every triangle within r of such a node was visited
    del best_d
    # closest points of band nodes
    bidx = np.flatnonzero(band)
    bt = best_t[bidx]
    del best_t
    Q, region = closest_point_on_triangles(
        _node_points(bidx, origin, h, shape), verts[faces[bt, 0]], verts[faces[bt, 1]], verts[faces[bt, 2]]
    )
    # propagate: every node takes the closest point of its nearest band node
    ind = ndimage.distance_transform_edt(~band.reshape(shape), return_distances=False, return_indices=True)
    del band
    src = ind[0].astype(np.int64).ravel()  # the nearest band node's flat index, built in place
    src *= ny
    src += ind[1].ravel()
    src *= nx
    src += ind[2].ravel()
    del ind
    lut = np.full(nx * ny * nz, -1, dtype=np.int64)
    lut[bidx] = np.arange(len(bidx))
    src = lut[src]  # (nnodes,) index into band arrays
    del lut

    def sqdist(cand, nodes):
        v = _node_points(nodes, origin, h, shape) - Q[cand]
        return np.einsum("ij,ij->i", v, v)

    n_nodes = nx * ny * nz
    dist2 = np.empty(n_nodes)
    for s in range(0, n_nodes, _NODE_CHUNK):
        e = min(s + _NODE_CHUNK, n_nodes)
        dist2[s:e] = sqdist(src[s:e], np.arange(s, e))
    in_band = np.zeros(n_nodes, dtype=bool)
    in_band[bidx] = True
    # one sweep near the surface (where contact happens): take a neighbour's closest point
    # when it is closer
    act = np.flatnonzero((dist2 < _SWEEP_RADIUS**2) & ~in_band)
    del in_band
    for ax in range(3):
        for sh in (1, -1):
            cand = np.roll(src.reshape(shape), sh, axis=ax).ravel()[act]
            dc = sqdist(cand, act)
            m = dc < dist2[act]
            dist2[act[m]] = dc[m]
            src[act[m]] = cand[m]
    np.sqrt(dist2, out=dist2)
    return _Nearest(origin=origin, h=h, shape=shape, Q=Q, region=region, bt=bt, src=src, dist=dist2)


def _grid_sign(verts, faces, near: _Nearest, h: float, shape) -> np.ndarray:
    """(nnodes,) float64 sign (+1 outside, -1 inside): flood fill of the exterior outside the
    half-voxel shell, a pseudonormal vote for enclosed regions, pseudonormals on the shell."""
    from scipy import ndimage

    dist, src, bt, region, Q = near.dist, near.src, near.bt, near.region, near.Q
    shell = (dist <= 0.5 * h * 1.05).reshape(shape)
    lab, nlab = ndimage.label(~shell)  # 6-connected by default
    lab = lab.ravel()
    outside_label = lab[0]
    fn, vn, en = _pseudonormals(verts, faces)

    def pseudo_sign(nodes):
        k = src[nodes]
        tri, reg = bt[k], region[k]
        N = fn[tri].copy()
        for rr, col in ((1, 0), (2, 1), (3, 2)):
            m = reg == rr
            N[m] = vn[faces[tri[m], col]]
        for rr, col in ((4, 0), (5, 1), (6, 2)):
            m = reg == rr
            N[m] = en[tri[m], col]
        dot = np.einsum("ij,ij->i", near.points(nodes) - Q[k], N)
        return np.where(dot < 0, -1.0, 1.0)

    sign = np.where(lab == outside_label, 1.0, -1.0)
    # enclosed regions are inside unless the surface around them faces into them: a cavity sealed
    # at grid resolution (a mouth) is outside. Vote with the pseudonormal sign of the nodes of
    # each region lying between half a voxel and two voxels from the surface.
    layer = np.flatnonzero((lab != outside_label) & (lab > 0) & (dist < 2.0 * h))
    if len(layer):
        votes = np.bincount(lab[layer], weights=pseudo_sign(layer), minlength=nlab + 1)
        cavity = votes > 0
        cavity[outside_label] = False
        cavity[0] = False
        sign[cavity[lab]] = 1.0
    # shell nodes: angle-weighted pseudonormal at the closest point
    sidx = np.flatnonzero(shell.ravel())
    sign[sidx] = pseudo_sign(sidx)
    return sign
