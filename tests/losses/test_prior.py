"""The pull towards the starting pattern: value, gradient, shape check."""

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
