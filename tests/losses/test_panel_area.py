"""The per-panel area loss (unsew.losses.panel_area): areas per panel, value, gradient."""

import pytest
import torch

from unsew.losses.panel_area import loss_panel_area, panel_areas

# two panels: a 2 x 1 rectangle (triangles 0, 1) and a unit square beside it (triangles 2, 3)
UV = torch.tensor(
    [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [3.0, 0.0], [4.0, 0.0], [4.0, 1.0], [3.0, 1.0]],
    dtype=torch.float64,
)
FACES = torch.tensor([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]], dtype=torch.int64)
PANEL = torch.tensor([0, 0, 1, 1], dtype=torch.int64)


def test_each_panels_area_whatever_the_winding():
    assert panel_areas(UV, FACES, PANEL, 2).tolist() == pytest.approx([2.0, 1.0], abs=1e-15)
    assert panel_areas(UV, FACES.flip(1), PANEL, 2).tolist() == pytest.approx([2.0, 1.0], abs=1e-15)


def test_zero_at_the_start_areas_and_relative_to_each_panel():
    a0 = torch.tensor([2.0, 1.0], dtype=torch.float64)
    assert loss_panel_area(UV, FACES, PANEL, a0).item() == pytest.approx(0.0, abs=1e-15)
    moved = UV.clone()
    moved[[5, 6], 0] += 0.1  # the square widened by 10 %: its term (0.1)^2, the rectangle's 0, mean over 2
    assert loss_panel_area(moved, FACES, PANEL, a0).item() == pytest.approx(0.01 / 2, rel=1e-12)
    shared = UV.clone()
    # the rectangle gives 0.1 m^2 (5 %) and the square takes it (10 %): the total is unchanged
    shared[[1, 2], 0] -= 0.1
    shared[[4, 7], 0] -= 0.1
    assert panel_areas(shared, FACES, PANEL, 2).sum().item() == pytest.approx(3.0, abs=1e-12)
    assert loss_panel_area(shared, FACES, PANEL, a0).item() == pytest.approx(
        (0.05**2 + 0.1**2) / 2, rel=1e-12
    )


def test_gradient_matches_finite_differences_and_shrinks_a_grown_panel():
    g = torch.Generator().manual_seed(0)
    uv = (UV + 0.05 * torch.randn(8, 2, dtype=torch.float64, generator=g)).requires_grad_(True)
    a0 = torch.tensor([1.5, 1.2], dtype=torch.float64)  # the rectangle has grown, the square shrunk
    assert torch.autograd.gradcheck(lambda u: loss_panel_area(u, FACES, PANEL, a0), (uv,))
    loss_panel_area(uv, FACES, PANEL, a0).backward()
    for idx, sign in (([0, 1, 2, 3], 1.0), ([4, 5, 6, 7], -1.0)):  # descent: rectangle in, square out
        centre = uv.detach()[idx].mean(0)
        assert (sign * (uv.grad[idx] * (uv.detach()[idx] - centre)).sum(1) > 0).all()


def test_bad_inputs():
    a0 = torch.tensor([2.0, 1.0], dtype=torch.float64)
    with pytest.raises(ValueError, match="must be \\(Nu, 2\\)"):
        loss_panel_area(torch.zeros(8, 3, dtype=torch.float64), FACES, PANEL, a0)
    with pytest.raises(ValueError, match="positive panel areas"):
        loss_panel_area(UV, FACES, PANEL, torch.tensor([2.0, 0.0], dtype=torch.float64))
