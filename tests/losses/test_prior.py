"""The pulls towards the starting pattern: value, gradient, shape check."""

import math

import numpy as np
import pytest
import torch

from unsew.losses.prior import loss_prior


def test_value_is_the_mean_squared_move():
    uv0 = torch.rand(10, 2, dtype=torch.float64)
    t = torch.tensor([0.03, -0.04], dtype=torch.float64)
    assert abs(float(loss_prior(uv0 + t, uv0)) - 0.05**2) < 1e-15  # a rigid move of 5 cm
    uv = uv0.clone()
    uv[3] += torch.tensor([0.1, 0.0], dtype=torch.float64)  # one vertex of ten moves 10 cm
    assert abs(float(loss_prior(uv, uv0)) - 0.01 / 10) < 1e-15
    assert float(loss_prior(uv0, uv0)) == 0.0


def test_gradient_matches_finite_differences():
    rng = np.random.default_rng(0)
    uv0 = torch.as_tensor(rng.random((7, 2)), dtype=torch.float64)
    uv = (uv0 + 0.01 * torch.as_tensor(rng.normal(size=(7, 2)))).requires_grad_(True)
    assert torch.autograd.gradcheck(lambda u: loss_prior(u, uv0), (uv,))
    loss_prior(uv, uv0).backward()
    np.testing.assert_allclose(uv.grad.numpy(), (2 * (uv - uv0) / 7).detach().numpy(), atol=1e-15)


def test_shapes_must_agree():
    with pytest.raises(ValueError, match="must both be"):
        loss_prior(torch.zeros(4, 2, dtype=torch.float64), torch.zeros(5, 2, dtype=torch.float64))


def test_moves_term_is_l1_near_the_start_and_fades_beyond_its_scale():
    """loss_moves: zero at the start; a move r of one point costs w s log(1 + r/s): within 10 % of
    w r at r = s / 10, and a 10 cm move less than a fifth of what an L1 distance would charge; its
    gradient (gradcheck) matches moves_pull's size and direction."""
    from unsew.losses.prior import MOVE_SCALE, loss_moves, moves_pull

    K0 = torch.zeros(3, 2, dtype=torch.float64)
    w = torch.tensor([0.5, 0.25, 0.25], dtype=torch.float64)
    assert float(loss_moves(K0, K0, w)) == 0.0
    small = K0.clone()
    small[0] = torch.tensor([3e-4, 4e-4])  # 0.5 mm
    assert 0.9 < float(loss_moves(small, K0, w)) / (0.5 * 5e-4) < 1.0
    big = K0.clone()
    big[1, 0] = 0.1
    assert float(loss_moves(big, K0, w)) < 0.2 * 0.25 * 0.1
    assert abs(float(loss_moves(big, K0, w)) - 0.25 * MOVE_SCALE * math.log1p(0.1 / MOVE_SCALE)) < 1e-6
    K = (K0 + torch.as_tensor(np.random.default_rng(2).normal(size=(3, 2)) * 0.01)).requires_grad_(True)
    assert torch.autograd.gradcheck(lambda k: loss_moves(k, K0, w), (K,))
    loss_moves(K, K0, w).backward()
    size, u = moves_pull(K.detach(), K0, w)
    torch.testing.assert_close(K.grad, size * u, rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError):
        loss_moves(K, K0, w[:2])


def test_open_lengths_term_sees_only_the_open_edges():
    """loss_open_lengths on the base t-shirt's rest mesh: zero at the graded pattern; the open
    edges' polylines are as long as the pattern's edges (the mesh follows curves to within 2 %);
    a move of a vertex on no open edge costs nothing; widening every panel 10 % costs
    sum (l - l0)^2 / sum l0^2."""
    from unsew.losses.open_lengths import loss_open_lengths, open_edge_lengths, open_edge_segments
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.curves import edge_length

    p = make_base_pattern("tshirt")
    mesh = mesh_pattern(p, edge_length=0.03)
    seg, edge_of, n = open_edge_segments(p, mesh.edge_verts)
    sewn = {(s.a.panel, s.a.edge) for s in p.stitches} | {(s.b.panel, s.b.edge) for s in p.stitches}
    open_edges = [
        (nm, i) for nm in p.panel_order for i in range(len(p.panels[nm].edges)) if (nm, i) not in sewn
    ]
    assert n == len(open_edges) > 0
    uv0 = torch.as_tensor(np.asarray(mesh.uv), dtype=torch.float64)
    seg_t, of_t = torch.as_tensor(seg), torch.as_tensor(edge_of)
    l0 = open_edge_lengths(uv0, seg_t, of_t, n)
    want = np.array([edge_length(p.panels[nm], i) for nm, i in open_edges])
    np.testing.assert_allclose(l0.numpy(), want, rtol=0.02)  # a 3 cm mesh cuts a neckline curve short
    assert float(loss_open_lengths(uv0, seg_t, of_t, l0)) == 0.0
    on_open = set(seg.ravel().tolist())
    inner = [v for v in range(len(uv0)) if v not in on_open]
    uv1 = uv0.clone()
    uv1[inner[0]] += 0.01
    assert float(loss_open_lengths(uv1, seg_t, of_t, l0)) == 0.0
    uv2 = uv0 * torch.tensor([1.1, 1.0], dtype=torch.float64)  # every panel 10 % wider
    d = open_edge_lengths(uv2, seg_t, of_t, n) - l0
    assert float(d.abs().max()) > 1e-3
    assert abs(float(loss_open_lengths(uv2, seg_t, of_t, l0)) - float((d**2).sum() / (l0**2).sum())) < 1e-15
