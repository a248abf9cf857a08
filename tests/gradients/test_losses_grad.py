"""gradcheck (float64) of every loss on small inputs (STYLE.md habit 4)."""

import torch
from torch.autograd import gradcheck

from unsew.losses.chamfer import loss_chamfer

G = torch.Generator().manual_seed(0)


def _rand(*shape):
    return torch.rand(*shape, generator=G, dtype=torch.float64)


def test_gradcheck_chamfer_plain_and_weighted():
    x = _rand(7, 3).requires_grad_()
    t = _rand(9, 3).requires_grad_()
    wt = (_rand(9) + 0.5).requires_grad_()
    wx = (_rand(7) + 0.5).requires_grad_()
    assert gradcheck(lambda a, b: loss_chamfer(a, b), (x, t))
    assert gradcheck(lambda a, b, c, d: loss_chamfer(a, b, weights_t=c, weights_x=d), (x, t, wt, wx))
    assert gradcheck(lambda a, b: loss_chamfer(a, b, method="cdist"), (x, t))
