"""Small meshes for the report tests (numpy only, world frame: Y up, front +Z)."""

import numpy as np
import pytest


def box(extents, center=(0.0, 0.0, 0.0), n=4):
    """Closed box, each side a grid of n x n quads (outward CCW faces).

    Returns (verts (V, 3) float64 [m], faces (F, 3) int64)."""
    ext = np.asarray(extents, dtype=np.float64) / 2
    c = np.asarray(center, dtype=np.float64)
    verts, faces = [], []
    t = np.linspace(-1.0, 1.0, n + 1)
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            if sign < 0:
                u_ax, v_ax = v_ax, u_ax  # keep the faces counter-clockwise seen from outside
            if axis == 1:
                u_ax, v_ax = v_ax, u_ax
            U, V = np.meshgrid(t, t, indexing="ij")
            p = np.zeros((n + 1, n + 1, 3))
            p[..., axis] = sign
            p[..., u_ax] = U
            p[..., v_ax] = V
            base = sum(len(x) for x in verts)
            verts.append(p.reshape(-1, 3) * ext + c)
            idx = np.arange((n + 1) ** 2).reshape(n + 1, n + 1) + base
            a, b, cc, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
            faces.append(np.stack([a, b, cc], -1).reshape(-1, 3))
            faces.append(np.stack([a, cc, d], -1).reshape(-1, 3))
    return np.concatenate(verts), np.concatenate(faces).astype(np.int64)


def plane(width, height, n=20, z=0.0):
    """A flat grid in the XY plane at depth z, facing +Z; returns (verts (V, 3) [m], faces)."""
    x = np.linspace(-width / 2, width / 2, n + 1)
    y = np.linspace(-height / 2, height / 2, n + 1)
    X, Y = np.meshgrid(x, y, indexing="ij")
    verts = np.stack([X, Y, np.full_like(X, z)], -1).reshape(-1, 3)
    idx = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return verts, faces


def read_png(path):
    """RGB pixels (H, W, 3) float in [0, 1]."""
    import matplotlib.image as mpimg

    return mpimg.imread(str(path))[..., :3]


def ink_mask(img, *, tol=0.04):
    """Pixels that are not the white background."""
    return (1.0 - img).max(axis=2) > tol


@pytest.fixture
def meshes():
    class M:
        pass

    m = M()
    m.box, m.plane, m.read_png, m.ink_mask = box, plane, read_png, ink_mask
    return m
