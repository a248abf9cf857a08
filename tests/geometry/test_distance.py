"""Point-to-mesh queries against brute force, and inside tests."""

import numpy as np
import pytest
import trimesh
from helpers import assert_close
from geometry_meshes import grid_tube

from unsew.body.sdf import mesh_distance
from unsew.geometry.distance import MeshQuery, closest_points, inside, point_mesh_distance, winding_number


def test_closest_points_match_brute_force_near_and_far():
    v, f = grid_tube()
    rng = np.random.default_rng(0)
    p = np.concatenate([rng.uniform(-0.3, 0.6, (300, 3)), rng.normal(0, 1.0, (100, 3)) * 0.5 + [0, 0, 0.3]])
    q, d, fi = closest_points(p, v, f)
    d_ref, _ = mesh_distance(p, v, f)
    assert_close(d, d_ref, atol=1e-12, what="distance ")
    assert_close(np.linalg.norm(q - p, axis=1), d, atol=1e-12, what="|closest - p| ")
    # the closest point lies on the face reported
    d_face, _ = mesh_distance(q, v, f)
    assert_close(d_face, 0.0, atol=1e-12)
    per_face = np.array([mesh_distance(q[i : i + 1], v, f[fi[i] : fi[i] + 1])[0][0] for i in range(len(q))])
    assert_close(per_face, 0.0, atol=1e-12, what="on reported face ")
    assert_close(point_mesh_distance(p, v, f), d, atol=0)


def test_tree_reuse_and_degenerate_triangle():
    v, f = grid_tube()
    v = np.concatenate([v, [[1.0, 0, 0], [2.0, 0, 0]]])
    f = np.concatenate([f, [[len(v) - 2, len(v) - 1, len(v) - 1]]])  # a segment, as a triangle
    mq = MeshQuery(v, f)
    q, d, fi = mq.closest(np.array([[1.5, 0.1, 0.0], [2.5, 0.0, 0.0]]))
    assert_close(d, [0.1, 0.5], atol=1e-12)
    assert (fi == len(f) - 1).all()
    assert mq.closest(np.zeros((0, 3)))[1].shape == (0,)
    with pytest.raises(ValueError):
        mq.closest(np.zeros((3, 2)))
    with pytest.raises(ValueError):
        MeshQuery(v, np.array([[0, 1, len(v)]]))


@pytest.mark.parametrize("exact", [False, True])
def test_inside_sphere_either_orientation(exact):
    m = trimesh.creation.icosphere(3, radius=0.3)
    rng = np.random.default_rng(1)
    dirs = rng.normal(size=(400, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    r = rng.uniform(0, 0.6, 400)
    r = r[np.abs(r - 0.3) > 0.02]
    p = dirs[: len(r)] * r[:, None]
    want = r < 0.3
    assert (inside(p, m.vertices, m.faces, exact=exact) == want).all()
    assert (inside(p, m.vertices, m.faces[:, ::-1], exact=exact) == want).all()
    w = winding_number(p, m.vertices, m.faces, exact=exact)
    assert_close(w[want], 1.0, atol=0.02) if exact else None


def test_many_queries_keep_their_order():
    """More than 256 queries are answered in a spatial order inside: results come back in the
    caller's order, equal to answering them one chunk at a time."""
    v, f = grid_tube()
    p = np.random.default_rng(3).uniform(-0.4, 0.6, (2000, 3))
    mq = MeshQuery(v, f)
    q, d, fi = mq.closest(p)
    parts = [mq.closest(p[i : i + 200]) for i in range(0, 2000, 200)]
    assert_close(q, np.concatenate([x[0] for x in parts]), atol=0)
    assert_close(d, np.concatenate([x[1] for x in parts]), atol=0)
    assert (fi == np.concatenate([x[2] for x in parts])).all()
    assert_close(np.linalg.norm(q - p, axis=1), d, atol=1e-12)


def test_first_hit_on_a_sphere():
    m = trimesh.creation.icosphere(4, radius=0.3)
    mq = MeshQuery(m.vertices, m.faces)
    o = np.array([[0, 0, -1.0], [0, 0, -1.0], [1.0, 1.0, 1.0], [0, 0, 0.0]])
    d = np.array([[0, 0, 2.0], [0, 0, 1.0], [1.0, 0, 0], [1.0, 0, 0]])
    hit, t, fi, p = mq.first_hit(o, d)
    assert hit.tolist() == [True, True, False, True]
    assert_close(t[[0, 1, 3]], [0.7, 0.7, 0.3], atol=2e-3)  # the tessellation sags inside the sphere
    assert np.isinf(t[2]) and fi[2] == -1 and np.isnan(p[2]).all()
    assert_close(np.linalg.norm(p[hit], axis=1), 0.3, atol=2e-3)
    assert (fi[hit] >= 0).all()
    hit2, _, _, _ = mq.first_hit(o, d, max_distance=0.5)
    assert hit2.tolist() == [False, False, False, True]
    with pytest.raises(ValueError):
        mq.first_hit(o, np.zeros_like(o))
