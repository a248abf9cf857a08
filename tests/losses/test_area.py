"""The total-area loss (unsew.losses.area): value, sign-free areas, gradient."""

import pytest
import torch

from unsew.losses.area import loss_area, rest_area

SQUARE = torch.tensor([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], dtype=torch.float64)
FACES = torch.tensor([[0, 1, 2], [0, 2, 3]], dtype=torch.int64)


def test_area_of_a_triangulated_rectangle_whatever_the_winding():
    assert rest_area(SQUARE, FACES).item() == pytest.approx(2.0, abs=1e-15)
    assert rest_area(SQUARE, FACES.flip(1)).item() == pytest.approx(2.0, abs=1e-15)


def test_loss_value_and_zero_at_the_target_area():
    assert loss_area(SQUARE, FACES, 2.0).item() == pytest.approx(0.0, abs=1e-15)
    assert loss_area(SQUARE, FACES, 1.0).item() == pytest.approx(1.0, abs=1e-15)  # twice too large
    assert loss_area(SQUARE * 0.9, FACES, 2.0).item() == pytest.approx((0.81 - 1) ** 2, rel=1e-12)


def test_gradient_matches_finite_differences_and_pushes_outwards_when_too_small():
    uv = (
        SQUARE + 0.05 * torch.randn(4, 2, dtype=torch.float64, generator=torch.Generator().manual_seed(0))
    ).requires_grad_(True)
    assert torch.autograd.gradcheck(lambda u: loss_area(u, FACES, 3.0), (uv,))
    loss_area(uv, FACES, 3.0).backward()
    centre = uv.detach().mean(0)
    assert ((uv.grad * (uv.detach() - centre)).sum(1) < 0).all()  # descent moves every corner outwards


def test_bad_inputs():
    with pytest.raises(ValueError, match="must be \\(Nu, 2\\)"):
        loss_area(torch.zeros(4, 3, dtype=torch.float64), FACES, 1.0)
    with pytest.raises(ValueError, match="must be positive"):
        loss_area(SQUARE, FACES, 0.0)
