"""Small meshes for the geometry tests (tests/geometry)."""

import numpy as np


def grid_tube(nu: int = 12, nv: int = 6, *, radius: float = 0.2, height: float = 0.5, y0: float = 0.0):
    """An open cylinder (two boundary loops): verts (nu*(nv+1), 3) [m], faces (2*nu*nv, 3)."""
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    y = np.linspace(y0, y0 + height, nv + 1)
    T, Y = np.meshgrid(th, y)
    v = np.stack([radius * np.cos(T), Y, radius * np.sin(T)], -1).reshape(-1, 3)
    i = np.arange(nv)[:, None] * nu
    j = np.arange(nu)[None, :]
    a, b = (i + j).ravel(), (i + (j + 1) % nu).ravel()
    f = np.concatenate([np.stack([a, b, b + nu], 1), np.stack([a, b + nu, a + nu], 1)])
    return v, f.astype(np.int64)


def square():
    """Two triangles on the unit square, sharing the diagonal (0, 2)."""
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    f = np.array([[0, 1, 2], [0, 2, 3]])
    return v, f
