"""Open contours (boundary loops) and the open-contour Chamfer loss."""

import numpy as np
import torch

from helpers import assert_close
from unsew.losses.contours import loss_open_contours, open_contours
from losses._loss_meshes import open_cylinder


def _bowtie():
    """Two unit squares sharing the corner vertex 0: a non-manifold boundary vertex."""
    V = np.array(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [-1, 0, 0], [-1, -1, 0], [0, -1, 0]], dtype=float
    )
    F = np.array([[0, 1, 2], [0, 2, 3], [0, 4, 5], [0, 5, 6]])
    return V, F


def test_cylinder_has_two_rims():
    r, h, nu = 0.2, 0.5, 64
    V, F = open_cylinder(r=r, h=h, nu=nu)
    cs = open_contours(V, F)
    assert len(cs) == 2
    poly_len = nu * 2 * r * np.sin(np.pi / nu)
    ys = sorted(c.centre[1] for c in cs)
    assert_close(ys, [0.0, h], atol=1e-12)
    for c in cs:
        assert len(c.indices) == nu and len(set(c.indices.tolist())) == nu
        assert_close(c.length, poly_len, rtol=1e-12)
        assert_close(c.centre[[0, 2]], [0.0, 0.0], atol=1e-12)
        assert_close(np.abs(c.normal), [0.0, 1.0, 0.0], atol=1e-12)
        # consecutive indices are mesh neighbours on the rim
        p = V[c.indices]
        assert_close(np.linalg.norm(np.roll(p, -1, 0) - p, axis=1), 2 * r * np.sin(np.pi / nu), rtol=1e-12)
    # the two rims are walked in opposite directions along +Y
    assert cs[0].normal[1] * cs[1].normal[1] < 0


def test_nonmanifold_vertex_splits_loops():
    V, F = _bowtie()
    cs = open_contours(V, F)
    assert len(cs) == 2
    assert sorted(sorted(c.indices.tolist()) for c in cs) == [[0, 1, 2, 3], [0, 4, 5, 6]]
    for c in cs:
        assert_close(c.length, 4.0, rtol=1e-14)


def test_closed_mesh_has_none_and_orientation_follows_faces():
    import trimesh

    m = trimesh.creation.icosphere(subdivisions=1)
    assert open_contours(m.vertices, m.faces) == []
    # a single CCW triangle seen from +Z: its loop's normal is +Z
    c = open_contours(
        np.eye(3)[[0, 1, 2]] * 0 + np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]])
    )
    assert len(c) == 1 and c[0].normal[2] > 0.99


def test_loss_open_contours_known_offset_and_pairs():
    V, F = open_cylinder()
    cs = open_contours(V, F)
    t = torch.tensor(V)
    x = t + torch.tensor([0.0, 0.01, 0.0], dtype=torch.float64)
    # all points pooled: each rim point's nearest is its own shifted copy (rings 0.5 m apart)
    assert_close(loss_open_contours(x, cs, t, cs), 2e-4, rtol=1e-12)
    assert_close(loss_open_contours(x, cs, t, cs, pairs=[(0, 0), (1, 1)]), 4e-4, rtol=1e-12)
    assert loss_open_contours(x, [], t, cs).item() == 0.0


def test_two_holes_touching_at_a_vertex():
    """A 6x6 grid with two diagonal quads removed: the holes share one corner vertex."""
    n = 6
    s = np.arange(n, dtype=float)
    X, Y = np.meshgrid(s, s)
    V = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], 1) * 0.1
    F = []
    for j in range(n - 1):
        for i in range(n - 1):
            if (i, j) in ((2, 2), (3, 3)):
                continue
            a = j * n + i
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    cs = open_contours(V, np.array(F))
    assert len(cs) == 3
    assert_close(cs[0].length, 2.0, rtol=1e-12)  # outer boundary, 4 x 0.5 m
    shared = 3 * n + 3
    holes = cs[1:]
    for c in holes:
        assert len(c.indices) == 4 and shared in c.indices.tolist()
        assert_close(c.length, 0.4, rtol=1e-12)
    # the holes are walked against the outer loop (their normals oppose it)
    assert all(c.normal[2] * cs[0].normal[2] < 0 for c in holes)
