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


def test_gradcheck_open_contours():

    from losses._loss_meshes import open_cylinder

    from unsew.losses.contours import loss_open_contours, open_contours

    V, F = open_cylinder(nu=6, nv=3)
    cs = open_contours(V, F)
    t = torch.tensor(V).requires_grad_()
    x = (torch.tensor(V) + 0.02 * _rand(*V.shape)).requires_grad_()
    assert gradcheck(lambda a, b: loss_open_contours(a, cs, b, cs), (x, t))
    assert gradcheck(lambda a, b: loss_open_contours(a, cs, b, cs, pairs=[(0, 1), (1, 0)]), (x, t))


def test_gradcheck_seam():
    from types import SimpleNamespace

    from unsew.losses.seam import loss_seam
    from unsew.pattern.model import Stitch, StitchSide

    mesh = SimpleNamespace(
        edge_verts={("a", 0): [0, 1, 2], ("b", 2): [3, 4, 5], ("a", 1): [2, 6], ("b", 1): [7, 3]}
    )
    st = [Stitch(StitchSide("a", 0), StitchSide("b", 2)), Stitch(StitchSide("a", 1), StitchSide("b", 1))]
    uv = _rand(8, 2).requires_grad_()
    assert gradcheck(lambda u: loss_seam(u, mesh, st), (uv,))


def test_gradcheck_material():
    from unsew.losses.material import loss_material

    g = torch.tensor([0.3, -0.2, 0.5, -1e-3, 2.0], dtype=torch.float64, requires_grad=True)
    assert gradcheck(loss_material, (g,))
