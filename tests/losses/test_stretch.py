"""The stretch barrier (unsew.losses.stretch): zero within the bound, its value, its gradient."""

import pytest
import torch

from unsew.losses.stretch import STRETCH_BOUND, loss_stretch, triangle_edges

# a unit right triangle at rest, and the same triangle in 3D
UV = torch.tensor([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], dtype=torch.float64)
X = torch.tensor([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], dtype=torch.float64)
FACES = [[0, 1, 2]]


def test_triangle_edges_pair_each_edge_in_both_index_spaces():
    e, eu = triangle_edges([[0, 1, 2], [2, 1, 3]], [[5, 6, 7], [7, 6, 8]])
    assert e.tolist() == [[0, 1], [1, 2], [2, 0], [2, 1], [1, 3], [3, 2]]
    assert eu.tolist() == [[5, 6], [6, 7], [7, 5], [7, 6], [6, 8], [8, 7]]


def test_zero_at_rest_and_within_the_bound():
    e, eu = triangle_edges(FACES, FACES)
    assert loss_stretch(X, UV, e, eu).item() == 0.0
    grown = X * 1.4  # every edge at 1.4 < 1.5: free
    assert loss_stretch(grown, UV, e, eu).item() == 0.0
    assert STRETCH_BOUND == 1.5


def test_value_sums_the_squared_excess_of_each_edge():
    e, eu = triangle_edges(FACES, FACES)
    x = X.clone()
    # edge 0-1 at 2.0 (excess 0.5); edge 1-2 at sqrt(5)/sqrt(2) = 1.581 (excess 0.081); 2-0 at 1
    x[1, 0] = 2.0
    want = 0.5**2 + (5**0.5 / 2**0.5 - 1.5) ** 2
    assert loss_stretch(x, UV, e, eu).item() == pytest.approx(want, rel=1e-12)
    assert loss_stretch(x, UV, e, eu, bound=2.5).item() == 0.0
    assert loss_stretch(x, UV * 2, e, eu).item() == 0.0  # a longer rest shape is no stretch


def test_gradient_matches_finite_differences_and_lengthens_the_rest_edge():
    e, eu = triangle_edges(FACES, FACES)
    g = torch.Generator().manual_seed(1)
    x = (X * 1.8 + 0.05 * torch.randn(3, 3, dtype=torch.float64, generator=g)).requires_grad_(True)
    uv = (UV + 0.02 * torch.randn(3, 2, dtype=torch.float64, generator=g)).requires_grad_(True)
    assert torch.autograd.gradcheck(lambda a, b: loss_stretch(a, b, e, eu), (x, uv))
    loss_stretch(x, uv, e, eu).backward()
    # descent moves the rest vertices apart (every edge is stretched): the rest shape grows
    centre = uv.detach().mean(0)
    assert ((uv.grad * (uv.detach() - centre)).sum(1) < 0).all()


def test_bad_inputs():
    e, eu = triangle_edges(FACES, FACES)
    with pytest.raises(ValueError, match="x must be"):
        loss_stretch(UV, UV, e, eu)
    with pytest.raises(ValueError, match="matching"):
        loss_stretch(X, UV, e, eu[:2])
