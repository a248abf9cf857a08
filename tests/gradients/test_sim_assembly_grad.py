"""The assembly Functions with hand-written backwards (assembly.py): gradcheck in float64 on a
tiny mesh, and agreement with plain autograd through the element blocks + scatter_blocks."""

import torch
from helpers import assert_close

from unsew.sim.assembly import assemble_membrane, assemble_outer, scatter_blocks
from unsew.sim.energies.bending import energy_bending
from unsew.sim.energies.membrane import energy_membrane, membrane_rest
from unsew.sim.integrator import _ring_weight
from unsew.sim.meshes import grid_sheet
from unsew.sim.model import SimModel

GAMMA = torch.tensor([800.0, 80.0, 600.0, 60.0, 6e-5], dtype=torch.float64)


def _case(stencil="ring"):
    uv, f = grid_sheet(2, 2, 0.1, 0.1)
    m = SimModel.build(f, f, bending_stencil=stencil)
    g = torch.Generator().manual_seed(0)
    uvt = torch.as_tensor(uv)
    x = torch.stack(
        [uvt[:, 0] * 1.05, 0.01 * torch.randn(len(uv), generator=g, dtype=torch.float64), uvt[:, 1] * 0.97], 1
    )
    return m, uvt, x, g


def test_gradcheck_assemble_membrane():
    m, uv, x, g = _case()
    F = m.faces.shape[0]
    G = torch.randn(F, 3, 9, generator=g, dtype=torch.float64, requires_grad=True)
    A = torch.randn(3, 3, generator=g, dtype=torch.float64)
    H = A.requires_grad_()  # any: the Function uses its symmetric part
    P = torch.randn(F, 3, 3, generator=g, dtype=torch.float64)
    P = P.requires_grad_()  # any: the Function uses its symmetric part (B S+ B^T is symmetric)
    area = torch.rand(F, generator=g, dtype=torch.float64).add(0.5).requires_grad_()

    def fn(G_, H_, P_, a_):
        return assemble_membrane(m.nnz, m.tri_src, m.tri_dst, G_, H_, P_, a_)

    assert torch.autograd.gradcheck(fn, (G, H, P, area), eps=1e-6, atol=1e-8, rtol=1e-6)


def test_gradcheck_assemble_outer():
    m, uv, x, g = _case()
    E = m.hinges.shape[0]
    gv = torch.randn(E, 12, generator=g, dtype=torch.float64, requires_grad=True)
    s = torch.rand(E, generator=g, dtype=torch.float64).add(0.5).requires_grad_()
    w = _ring_weight(gv)

    def fn(g_, s_):
        return assemble_outer(m.nnz, m.hinge_src, m.hinge_dst, g_, s_, w)

    assert torch.autograd.gradcheck(fn, (gv, s), eps=1e-6, atol=1e-8, rtol=1e-6)


def test_matches_plain_autograd_through_blocks():
    for stencil in ("ring", "full"):
        m, uv, x, g = _case(stencil)
        x = x.requires_grad_()
        uvp = uv.clone().requires_grad_()
        gam = GAMMA.clone().requires_grad_()
        area, B, _ = membrane_rest(uvp, m.faces_uv)
        coef = (
            (torch.rand(m.hinges.shape[0], generator=g, dtype=torch.float64) + 1.0)
            * area.mean()
            / area.mean().detach()
        )
        w = torch.randn(m.nnz, generator=g, dtype=torch.float64)
        Hm = energy_membrane(x, m.faces, area, B, gam)[2]
        Hb = energy_bending(x, m.hinges, coef, gam)[2]
        if stencil == "ring":
            Hb = Hb * _ring_weight(Hb)
        ref = scatter_blocks(m.nnz, m.tri_src, m.tri_dst, Hm) + scatter_blocks(
            m.nnz, m.hinge_src, m.hinge_dst, Hb
        )
        gref = torch.autograd.grad((ref * w).sum(), (x, uvp, gam), retain_graph=True)
        pm = energy_membrane(x, m.faces, area, B, gam, parts=True)[2]
        pb = energy_bending(x, m.hinges, coef, gam, parts=True)[2]
        wr = _ring_weight(x) if stencil == "ring" else None
        ours = assemble_membrane(m.nnz, m.tri_src, m.tri_dst, *pm, area) + assemble_outer(
            m.nnz, m.hinge_src, m.hinge_dst, *pb, wr
        )
        gours = torch.autograd.grad((ours * w).sum(), (x, uvp, gam))
        assert_close(ours, ref, rtol=1e-12, atol=1e-9, what=f"{stencil} values ")
        for a, b, name in zip(gours, gref, ("x", "uv", "gamma")):
            assert_close(a, b, rtol=1e-10, atol=1e-10 * float(b.abs().max()), what=f"{stencil} d/d{name} ")
