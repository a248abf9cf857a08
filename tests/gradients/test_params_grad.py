"""Gradients of the 2D rest mesh U and of the control points with respect to K (float64 gradcheck)."""

from __future__ import annotations

import torch
from meshing.handmade_patterns import mini_shirt, nonconvex_panel

from unsew.meshing import mesh_pattern
from unsew.pattern.params import PatternParams


def _params(make, h):
    pat = make()
    return PatternParams.build(pat, mesh_pattern(pat, edge_length=h))


def test_gradcheck_uv_wrt_K_symmetric_pattern():
    pp = _params(mini_shirt, 0.1)
    K = pp.K0.clone().requires_grad_(True)
    assert torch.autograd.gradcheck(pp.uv, (K,), eps=1e-6, atol=1e-8)
    assert torch.autograd.gradcheck(pp.control_points, (K,), eps=1e-6, atol=1e-8)


def test_gradcheck_uv_wrt_K_nonconvex_panel():
    pp = _params(nonconvex_panel, 0.08)
    K = (pp.K0 * 1.1).requires_grad_(True)
    assert torch.autograd.gradcheck(pp.uv, (K,), eps=1e-6, atol=1e-8)


def test_loss_gradient_reaches_every_effective_control_point():
    pp = _params(mini_shirt, 0.1)
    K = pp.K0.clone().requires_grad_(True)
    (pp.uv(K) ** 2).sum().backward()
    assert torch.isfinite(K.grad).all()
    assert (K.grad.abs().sum(dim=1) > 0).all()


def test_gradcheck_uv_wrt_K_tshirt():
    from unsew.pattern.base import make_base_pattern

    pat = make_base_pattern("tshirt")
    pp = PatternParams.build(pat, mesh_pattern(pat, edge_length=0.1))
    K = pp.K0.clone().requires_grad_(True)
    assert torch.autograd.gradcheck(pp.uv, (K,), eps=1e-6, atol=1e-8)
