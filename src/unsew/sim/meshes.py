"""Small test/benchmark meshes: triangulated rectangles and two panels sewn along an edge."""

from __future__ import annotations

import numpy as np

__all__ = ["grid_sheet", "two_panels"]


def grid_sheet(nx: int, ny: int, width: float, height: float):
    """A width x height [m] rectangle with (nx+1)(ny+1) vertices, counter-clockwise triangles.

    Returns uv (V, 2) float64 [m] (u along width, v along height, origin at a corner) and
    faces (F, 3) int64 (alternating diagonals)."""
    xs = np.linspace(0.0, width, nx + 1)
    ys = np.linspace(0.0, height, ny + 1)
    U, V = np.meshgrid(xs, ys, indexing="xy")
    uv = np.stack([U.ravel(), V.ravel()], 1)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
    i, j = i.ravel(), j.ravel()
    a = j * (nx + 1) + i
    b, c, d = a + 1, a + nx + 2, a + nx + 1
    flip = (i + j) % 2 == 1
    t1 = np.where(flip[:, None], np.stack([a, b, d], 1), np.stack([a, b, c], 1))
    t2 = np.where(flip[:, None], np.stack([b, c, d], 1), np.stack([a, c, d], 1))
    return uv, np.concatenate([t1, t2]).astype(np.int64)


def two_panels(n: int, size: float):
    """Two size x size [m] panels (n x n quads each) sewn along one edge.

    Panel A occupies u in [0, size], panel B sits beside it in the uv plane at u in
    [size + gap, 2 size + gap]; A's right edge is sewn to B's left edge.

    Returns dict with uv (Nu, 2) [m], faces_uv (F, 3), faces (F, 3) into sewn vertices,
    x_of_u (Nu,), n_x, seam_pairs (S, 2) uv index pairs (the GarmentMesh fields)."""
    uv_a, f_a = grid_sheet(n, n, size, size)
    uv_b = uv_a + np.array([size * 1.25, 0.0])
    nv = uv_a.shape[0]
    uv = np.concatenate([uv_a, uv_b])
    faces_uv = np.concatenate([f_a, f_a + nv])
    rows = np.arange(n + 1)
    right_a = rows * (n + 1) + n
    left_b = nv + rows * (n + 1)
    seam = np.stack([right_a, left_b], 1)
    x_of_u = np.arange(2 * nv)
    x_of_u[left_b] = right_a
    uniq, x_of_u = np.unique(x_of_u, return_inverse=True)
    return dict(
        uv=uv,
        faces_uv=faces_uv,
        faces=x_of_u[faces_uv],
        x_of_u=x_of_u,
        n_x=int(uniq.shape[0]),
        seam_pairs=seam.astype(np.int64),
    )
