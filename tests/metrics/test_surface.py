"""Chamfer [mm] and normal error on meshes with known answers."""

import numpy as np
import pytest
import trimesh

from helpers import assert_close
from unsew.errors import InputError
from unsew.body.sdf import closest_point_on_triangles
from unsew.metrics.surface import (
    chamfer_mm,
    closest_points,
    normal_error,
    sample_surface,
    surface_metrics,
)


def _closest_on_triangles(p, a, b, c):
    return closest_point_on_triangles(p, a, b, c)[0]


def _square(z=0.0, n=6):
    s = np.linspace(0, 1, n)
    X, Y = np.meshgrid(s, s)
    V = np.stack([X.ravel(), Y.ravel(), np.full(X.size, z)], 1)
    F = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return V, np.array(F)


@pytest.mark.parametrize("d", [0.001, 0.02])
def test_parallel_planes(d):
    va, fa = _square(0.0)
    vb, fb = _square(d, n=9)  # different tessellation, same surface shifted by d
    r = chamfer_mm(va, fa, vb, fb, n_samples=5000)
    for x in (r.mean_mm, r.p95_mm, r.hausdorff_mm, r.a_to_b_mm, r.b_to_a_mm):
        assert_close(x, d * 1e3, rtol=1e-10)
    assert normal_error(va, fa, vb, fb, n_samples=2000).mean_deg < 1e-5


def test_tilted_plane_normal_angle():
    va, fa = _square()
    ang = np.radians(10.0)
    R = np.array([[1, 0, 0], [0, np.cos(ang), -np.sin(ang)], [0, np.sin(ang), np.cos(ang)]])
    vb = va @ R.T
    ne = normal_error(va, fa, vb, fa, n_samples=3000)
    assert_close(ne.mean_deg, 10.0, rtol=1e-9)
    assert_close(ne.cosine_distance, 1 - np.cos(ang), rtol=1e-9)
    # flipped orientation: unsigned comparison ignores it, oriented sees 180 degrees
    assert normal_error(va, fa, va, fa[:, ::-1], n_samples=500).mean_deg < 1e-5
    assert_close(
        normal_error(va, fa, va, fa[:, ::-1], n_samples=500, oriented=True).mean_deg, 180.0, rtol=1e-9
    )


def test_closest_points_match_bruteforce():
    m = trimesh.creation.icosphere(subdivisions=2, radius=0.3)
    rng = np.random.default_rng(0)
    P = rng.normal(size=(400, 3)) * 0.4
    _, d, f = closest_points(P, m.vertices, m.faces)
    v, F = m.vertices, m.faces
    brute = np.array(
        [
            np.linalg.norm(
                _closest_on_triangles(np.repeat(p[None], len(F), 0), v[F[:, 0]], v[F[:, 1]], v[F[:, 2]]) - p,
                axis=1,
            ).min()
            for p in P
        ]
    )
    assert_close(d, brute, atol=1e-15)


def test_point_triangle_regions_against_dense_sampling():
    rng = np.random.default_rng(1)
    a, b, c = rng.normal(size=(3, 3))
    g = np.linspace(0, 1, 601)
    U, W = np.meshgrid(g, g)
    keep = U + W <= 1
    S = a + U[keep][:, None] * (b - a) + W[keep][:, None] * (c - a)
    P = rng.normal(size=(60, 3)) * 2
    q = _closest_on_triangles(P, np.tile(a, (60, 1)), np.tile(b, (60, 1)), np.tile(c, (60, 1)))
    exact = np.linalg.norm(q - P, axis=1)
    dense = np.array([np.linalg.norm(S - p, axis=1).min() for p in P])
    assert (exact <= dense + 1e-12).all()
    assert (dense - exact).max() < 5e-3


def test_concentric_spheres_and_seed():
    a = trimesh.creation.icosphere(subdivisions=4, radius=0.3)
    b = trimesh.creation.icosphere(subdivisions=4, radius=0.31)
    r = surface_metrics(a.vertices, a.faces, b.vertices, b.faces, n_samples=4000)
    assert 9.0 < r["chamfer_mm"] < 10.0  # 10 mm less the tessellation sag
    assert r["hausdorff_mm"] <= 10.0 + 1e-9
    assert r == surface_metrics(a.vertices, a.faces, b.vertices, b.faces, n_samples=4000)
    pts, fi = sample_surface(a.vertices, a.faces, 1000, seed=3)
    assert pts.shape == (1000, 3) and fi.dtype == np.int64


def test_bad_meshes_raise_input_error():
    v, f = _square()
    with pytest.raises(InputError, match="no vertices"):
        chamfer_mm(np.zeros((0, 3)), f, v, f)
    with pytest.raises(InputError, match="no triangles"):
        chamfer_mm(v, np.zeros((0, 3), int), v, f)
    vn = v.copy()
    vn[3, 1] = np.nan
    with pytest.raises(InputError, match="NaN"):
        chamfer_mm(v, f, vn, f)
    with pytest.raises(InputError, match="zero surface area"):
        chamfer_mm(v, f, np.zeros_like(v), f)
