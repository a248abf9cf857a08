"""Chamfer losses and nearest neighbours (paper eq. 7)."""

import numpy as np
import pytest
import torch

from helpers import assert_close
from unsew.losses.chamfer import loss_chamfer
from unsew.losses.curvature import curvature_weights
from unsew.losses.nn import nearest_indices


def _grid(n=12, size=0.5):
    s = np.linspace(0.0, size, n)
    X, Y = np.meshgrid(s, s)
    return np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)


def _brute_chamfer(x, t, wt=None):
    d = ((x[:, None, :] - t[None, :, :]) ** 2).sum(-1)  # (N, M)
    dx, ix = d.min(dim=1)
    dt = d.min(dim=0).values
    if wt is not None:
        dx = dx * wt[ix]
        dt = dt * wt
    return dx.mean() + dt.mean()


@pytest.mark.parametrize("d", [0.0, 0.003, 0.04])
def test_parallel_planes_known_distance(d):
    p = _grid()
    x = torch.tensor(p)
    t = torch.tensor(p + [0.0, 0.0, d])
    assert_close(loss_chamfer(x, t), 2 * d * d, atol=1e-18, rtol=1e-12)


def test_matches_bruteforce_value_and_gradient():
    g = torch.Generator().manual_seed(1)
    x = torch.rand(300, 3, generator=g, dtype=torch.float64, requires_grad=True)
    t = torch.rand(200, 3, generator=g, dtype=torch.float64)
    w = torch.rand(200, generator=g, dtype=torch.float64) + 0.5
    for method in ("kdtree", "cdist"):
        for wt in (None, w):
            a = loss_chamfer(x, t, weights_t=wt, method=method)
            (ga,) = torch.autograd.grad(a, x)
            b = _brute_chamfer(x, t, wt)
            (gb,) = torch.autograd.grad(b, x)
            assert_close(a, b, rtol=1e-13)
            assert_close(ga, gb, rtol=1e-12, atol=1e-18)


def test_kdtree_and_cdist_agree():
    g = torch.Generator().manual_seed(2)
    q = torch.rand(2000, 3, generator=g, dtype=torch.float64)
    p = torch.rand(1500, 3, generator=g, dtype=torch.float64)
    a = nearest_indices(q, p, method="kdtree")
    b = nearest_indices(q, p, method="cdist")
    # indices may differ only at exact ties; distances must agree
    assert_close(((q - p[a]) ** 2).sum(1), ((q - p[b]) ** 2).sum(1), rtol=1e-14)
    assert a.dtype == torch.int64 and not a.requires_grad


def test_flat_target_weighted_equals_plain_exactly():
    from scipy.spatial import Delaunay

    rng = np.random.default_rng(0)
    uv = rng.random((150, 2))
    faces = Delaunay(uv).simplices
    # a tilted plane in 3D
    R = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    verts = np.c_[uv, np.zeros(len(uv))] @ R.T + [0.1, 1.2, -0.3]
    t = torch.tensor(verts)
    w = curvature_weights(t, torch.tensor(faces))
    assert torch.equal(w, torch.ones(len(verts), dtype=torch.float64))
    x = t + 0.01 * torch.randn(t.shape, dtype=torch.float64, generator=torch.Generator().manual_seed(0))
    assert loss_chamfer(x, t, weights_t=w).item() == loss_chamfer(x, t).item()


def test_weights_x_scale_first_term():
    p = torch.tensor(_grid(5))
    t = p + torch.tensor([0.0, 0.0, 0.01], dtype=torch.float64)
    wx = torch.full((len(p),), 3.0, dtype=torch.float64)
    assert_close(loss_chamfer(p, t, weights_x=wx), 4 * 1e-4, rtol=1e-12)


def test_bad_shapes_raise():
    with pytest.raises(ValueError):
        loss_chamfer(torch.zeros(0, 3, dtype=torch.float64), torch.zeros(4, 3, dtype=torch.float64))
    with pytest.raises(ValueError):
        loss_chamfer(torch.zeros(3, 3, dtype=torch.float64), torch.zeros(4, 2, dtype=torch.float64))
    with pytest.raises(ValueError):
        loss_chamfer(
            torch.zeros(3, 3, dtype=torch.float64),
            torch.zeros(4, 3, dtype=torch.float64),
            weights_t=torch.ones(3),
        )
