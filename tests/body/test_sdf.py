"""Signed distance grid: exact point-triangle distance, accuracy against exact point-to-mesh
distance, sign, differentiability, cache, and the default body."""

import numpy as np
import pytest
import torch
from helpers import assert_close

from unsew.body.body import Body, default_body
from unsew.body.sdf import BodySDF, closest_point_on_triangles, mesh_distance
from unsew.body.skeleton import Skeleton


def _sphere_body(r=0.1, subdiv=3):
    import trimesh

    m = trimesh.creation.icosphere(subdivisions=subdiv, radius=r)
    sk = Skeleton(["pelvis"], [-1], [[0.0, 0.0, 0.0]], ["torso"])
    return Body(np.asarray(m.vertices, float), np.asarray(m.faces, np.int64), sk)


def _winding_number(p, V, F):
    """Generalised winding number of point p (3,) for a closed mesh (Jacobson et al. 2013)."""
    A, B, C = (V[F[:, k]] - p for k in range(3))
    la, lb, lc = (np.linalg.norm(M, axis=1) for M in (A, B, C))
    det = np.einsum("ij,ij->i", A, np.cross(B, C))
    den = la * lb * lc + np.einsum("ij,ij->i", A, B) * lc + np.einsum("ij,ij->i", B, C) * la
    den += np.einsum("ij,ij->i", C, A) * lb
    return np.arctan2(det, den).sum() / (2 * np.pi)


def test_closest_point_on_triangle_matches_dense_sampling():
    rng = np.random.default_rng(0)
    n = 200
    a, b, c = (rng.normal(size=(n, 3)) for _ in range(3))
    p = rng.normal(size=(n, 3)) * 2
    q, region = closest_point_on_triangles(p, a, b, c)
    d = np.linalg.norm(p - q, axis=1)
    # dense barycentric samples: the true minimum is at most d and not much below
    s = np.linspace(0, 1, 121)
    u, v = np.meshgrid(s, s)
    keep = u + v <= 1
    u, v = u[keep], v[keep]
    pts = a[:, None] + u[None, :, None] * (b - a)[:, None] + v[None, :, None] * (c - a)[:, None]
    dmin = np.linalg.norm(pts - p[:, None], axis=2).min(axis=1)
    assert (d <= dmin + 1e-12).all()
    assert_close(d, dmin, atol=0.02, what="closest point distance vs sampling: ")
    # the closest point lies on the triangle: barycentric coordinates in [0, 1]
    n_ = np.cross(b - a, c - a)
    assert np.abs(np.einsum("ij,ij->i", q - a, n_)).max() < 1e-9 * np.abs(n_).max() * 10
    assert set(np.unique(region)) <= set(range(7))


def test_mesh_distance_matches_trimesh():
    import trimesh

    body = _sphere_body(subdiv=2)
    rng = np.random.default_rng(1)
    x = rng.uniform(-0.2, 0.2, size=(200, 3))
    d, _ = mesh_distance(x, body.verts, body.faces)
    _, d_tm, _ = trimesh.proximity.closest_point(body.to_trimesh(), x)
    assert_close(d, d_tm, atol=1e-9, what="brute force vs trimesh closest point: ")


@pytest.fixture(scope="module")
def sphere_sdf():
    body = _sphere_body()
    return body, BodySDF.build(body, voxel=0.005, margin=0.03, use_cache=False, floor=False)


def test_sphere_accuracy_and_sign(sphere_sdf):
    body, sdf = sphere_sdf
    rng = np.random.default_rng(2)
    dirs = rng.normal(size=(1500, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    x = dirs * rng.uniform(0.05, 0.15, size=(1500, 1))  # within 5 cm of the surface
    d_ex, _ = mesh_distance(x, body.verts, body.faces)
    inside = np.array([_winding_number(p, body.verts, body.faces) > 0.5 for p in x])
    s_ex = np.where(inside, -d_ex, d_ex)
    d, n = sdf.query(torch.tensor(x))
    err = d.numpy() - s_ex
    rms = np.sqrt(np.mean(err**2))
    assert rms <= 1e-3, f"RMS error {rms * 1e3:.3f} mm > 1 mm"
    far = d_ex > sdf.voxel
    assert (np.sign(d.numpy()[far]) == np.sign(s_ex[far])).all()
    # normals point away from the centre
    cos = (n.numpy() * dirs).sum(axis=1)
    assert cos.min() > 0.98


def test_the_ground_under_the_body_is_solid():
    """With the floor (the default), cloth beside the body at height h above its lowest point is
    h from the solid, and below that plane inside it; near the body the body stays nearer."""
    body = _sphere_body()
    sdf = BodySDF.build(body, voxel=0.005, margin=0.03, use_cache=False)
    bottom = float(body.verts[:, 1].min())
    x = torch.tensor(
        [[0.12, bottom + 0.02, 0.0], [0.12, bottom - 0.01, 0.0], [0.0, 0.105, 0.0]], dtype=torch.float64
    )
    d, n = sdf.query(x)
    assert_close(d[:2], torch.tensor([0.02, -0.01], dtype=torch.float64), atol=1e-3, what="ground: ")
    assert_close(n[0], torch.tensor([0.0, 1.0, 0.0], dtype=torch.float64), atol=1e-6, what="ground normal: ")
    assert abs(float(d[2]) - 0.005) < 1e-3  # the sphere's top: the body's own distance


def test_query_outside_grid_adds_distance_to_box(sphere_sdf):
    _, sdf = sphere_sdf
    x = torch.tensor([[0.5, 0.0, 0.0], [0.0, -0.4, 0.3]], dtype=torch.float64)
    d, _ = sdf.query(x)
    assert_close(d, x.norm(dim=1) - 0.1, atol=3e-3, what="far points: ")


def test_query_keeps_dtype_and_is_twice_differentiable(sphere_sdf):
    _, sdf = sphere_sdf
    x = torch.tensor([[0.103, 0.012, -0.02], [0.0, 0.0, 0.12]], dtype=torch.float64, requires_grad=True)
    d, n = sdf.query(x)
    assert d.dtype == torch.float64 and n.shape == (2, 3)
    (g,) = torch.autograd.grad(d.sum(), x, create_graph=True)
    # autograd's gradient of d (trilinear) agrees with the smooth normal near the surface
    cos = (g * n).sum(dim=1) / g.norm(dim=1)
    assert cos.min() > 0.99
    (h,) = torch.autograd.grad(g[:, 0].sum(), x)
    assert torch.isfinite(h).all()
    x32 = x.detach().float()
    d32, _ = sdf.query(x32)
    assert d32.dtype == torch.float32
    assert_close(d32, d, atol=1e-6, what="float32 vs float64 query: ")


def test_query_gradcheck_small_grid():
    sdf = BodySDF.from_function(lambda p: np.linalg.norm(p, axis=1) - 0.05, [-0.1] * 3, [0.1] * 3, voxel=0.01)
    x = torch.tensor(
        [[0.031, 0.012, -0.018], [0.003, -0.061, 0.044]], dtype=torch.float64, requires_grad=True
    )
    assert torch.autograd.gradcheck(lambda y: sdf.query(y)[0], (x,))
    assert torch.autograd.gradcheck(lambda y: sdf.query(y)[1], (x,))


def test_query_table_is_distance_and_central_differences():
    """The query's channel-last table, filled a channel at a time: the distance and np.gradient's
    d/dx, d/dy, d/dz, exactly (a node's row is (iz * ny + iy) * nx + ix)."""
    rng = np.random.default_rng(0)
    sdf = BodySDF(rng.standard_normal((5, 6, 7)), np.zeros(3), 0.01)
    t = sdf._table()
    gz, gy, gx = np.gradient(sdf.values, sdf.voxel)
    assert t.shape == (5 * 6 * 7, 4) and t.dtype == np.float64
    assert_close(t, np.stack([sdf.values, gx, gy, gz], axis=-1).reshape(-1, 4), atol=0)
    iz, iy, ix = 3, 2, 5
    assert t[(iz * 6 + iy) * 7 + ix, 0] == sdf.values[iz, iy, ix]


def test_cache_roundtrip(tmp_path):
    body = _sphere_body(subdiv=2)
    a = BodySDF.build(body, voxel=0.01, margin=0.02, cache_dir=tmp_path)
    files = list(tmp_path.glob("sdf_*.npz"))
    assert len(files) == 1
    b = BodySDF.build(body, voxel=0.01, margin=0.02, cache_dir=tmp_path)
    assert b.build_seconds == 0.0  # loaded, not rebuilt
    assert_close(b.values, a.values, atol=1e-6, what="cached grid: ")
    c = BodySDF.build(body, voxel=0.008, margin=0.02, cache_dir=tmp_path)  # another key
    assert c.values.shape != a.values.shape
    assert len(list(tmp_path.glob("sdf_*.npz"))) == 2


@pytest.mark.skipif(not torch.cuda.is_available(), reason="no CUDA device")
def test_query_on_cuda(sphere_sdf):  # pragma: no cover - no GPU on the dev machines
    _, sdf = sphere_sdf
    x = torch.tensor([[0.11, 0.0, 0.0]], dtype=torch.float64)
    d_cpu, _ = sdf.query(x)
    d_gpu, n_gpu = sdf.query(x.cuda())
    assert d_gpu.device.type == "cuda" and n_gpu.device.type == "cuda"
    assert_close(d_gpu.cpu(), d_cpu, atol=1e-9)


def test_default_body_accuracy_and_sign(default_sdf):
    """RMS <= 1 mm within 5 cm of the surface vs exact point-to-mesh
    distance; sign right (winding number) for every point farther than one voxel."""
    import trimesh

    body = default_body()
    m = body.to_trimesh()
    assert default_sdf.voxel <= 0.005
    pts, fi = trimesh.sample.sample_surface(m, 300, seed=3)
    rng = np.random.default_rng(3)
    x = pts + m.face_normals[fi] * rng.uniform(-0.05, 0.05, size=(len(pts), 1))
    d_ex, _ = mesh_distance(x, body.verts, body.faces)
    # the ground under the feet is part of the solid: points nearer to it than to the body are
    # its test's (test_the_ground_under_the_body_is_solid)
    keep = (d_ex < 0.05) & (x[:, 1] - body.verts[:, 1].min() > d_ex + default_sdf.voxel)
    x, d_ex = x[keep], d_ex[keep]
    d, _ = default_sdf.query(torch.tensor(x))
    d = d.numpy()
    far = d_ex > default_sdf.voxel
    wn = np.array([_winding_number(p, body.verts, body.faces) for p in x[far]])
    s_ex = np.where(wn > 0.5, -d_ex[far], d_ex[far])
    assert (np.sign(d[far]) == np.sign(s_ex)).all(), "sign wrong"
    err = np.abs(d) - d_ex
    rms = np.sqrt(np.mean(err**2))
    assert rms <= 1e-3, f"RMS error {rms * 1e3:.3f} mm > 1 mm"


def test_sdf_of_a_symmetric_body_is_symmetric(default_sdf):
    import torch

    rng = np.random.default_rng(3)
    b = default_body()
    x = np.asarray(b.verts)[rng.choice(len(b.verts), 2000)] + rng.normal(0, 0.01, (2000, 3))
    d1, n1 = default_sdf.query(torch.as_tensor(x))
    d2, n2 = default_sdf.query(torch.as_tensor(x * [-1.0, 1.0, 1.0]))
    assert float((d1 - d2).abs().max()) < 1e-9
    assert float((n1 * torch.tensor([-1.0, 1.0, 1.0], dtype=n1.dtype) - n2).abs().max()) < 1e-6


def test_inflated_grid_is_the_body_grown_outward(sphere_sdf):
    from unsew.errors import InputError

    _, sdf = sphere_sdf
    x = torch.tensor([[0.12, 0.0, 0.0], [0.0, 0.09, 0.02], [0.0, 0.0, -0.2]], dtype=torch.float64)
    d0, n0 = sdf.query(x)
    grown = sdf.inflated(0.003)
    d1, n1 = grown.query(x)
    assert_close(d1, d0 - 0.003, atol=1e-12, what="inflated distance: ")
    assert_close(n1, n0, atol=1e-12, what="inflated normals: ")
    assert sdf.inflated(0.0) is sdf
    d2, _ = sdf.query(x)  # the original grid is untouched
    assert_close(d2, d0, atol=0.0, what="original: ")
    for bad in (-0.001, float("nan")):
        with pytest.raises(InputError, match="inflated"):
            sdf.inflated(bad)
