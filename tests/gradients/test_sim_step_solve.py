"""The fused step Function (step_solve.py): gradcheck in float64 on a tiny sewn model (pinned
vertex, seam springs as extra values, both bending stencils), and one implicit Euler step's
gradients equal to the unfused path (assembly Functions + sparse_solve)."""

import pytest
import torch
from helpers import assert_close

from unsew.sim import CapsuleSDF, SimModel, SimState
from unsew.sim.integrator import StepParams, _pattern, _ring_corner_weight, forces, rest_data, step
from unsew.sim.meshes import grid_sheet
from unsew.sim.solve import resolve_backend
from unsew.sim.step_solve import step_solve

GAMMA = torch.tensor([800.0, 80.0, 600.0, 60.0, 6e-5], dtype=torch.float64)
SDF = CapsuleSDF((-1.0, -0.052, 0.05), (1.0, -0.052, 0.05), 0.05)  # under the sheet: contact band


def _case(stencil):
    uv, f = grid_sheet(2, 2, 0.1, 0.1)
    m = SimModel.build(f, f, springs=[[0, 8]], pinned=[2], bending_stencil=stencil)
    g = torch.Generator().manual_seed(0)
    uvt = torch.as_tensor(uv)
    x = torch.stack(
        [uvt[:, 0] * 1.02, 0.003 * torch.randn(len(uv), generator=g, dtype=torch.float64), uvt[:, 1] * 0.99],
        1,
    )
    v = 0.1 * torch.randn(x.shape, generator=g, dtype=torch.float64)
    return m, uvt, x, v


@pytest.mark.parametrize("stencil", ["ring", "full"])
def test_gradcheck_step_solve(stencil):
    m, uv, x, v = _case(stencil)
    params = StepParams(dt=0.05)
    rest = rest_data(m, uv, 0.15)
    with torch.no_grad():
        _, (mem, bend, Ks), Hc, D, _ = forces(m, rest, SimState(x, v), SDF, GAMMA, params, parts=True)
    pat = _pattern(m)
    w4 = _ring_corner_weight(x) if stencil == "ring" else None
    vblk0 = rest.mass.detach()[:, None, None] * torch.eye(3, dtype=torch.float64) + 0.0025 * Hc
    inputs = [t.detach().clone().requires_grad_() for t in (*mem, *bend, vblk0, 0.0025 * Ks)]
    rhs = torch.randn(
        3 * m.n, generator=torch.Generator().manual_seed(1), dtype=torch.float64
    ).requires_grad_()

    def fn(*args):  # (G, H, P, area, g, s, vblk, extra, rhs), each an input gradcheck varies
        G, H, P, area, g, s, vb, extra, b = args
        return step_solve(
            m,
            pat,
            blocks=((G, H, P, area), (g, s), vb, extra),
            rhs=b,
            dt=0.05,
            w4=w4,
            backend=resolve_backend("auto"),
        )

    assert torch.autograd.gradcheck(fn, (*inputs, rhs), eps=1e-6, atol=1e-7, rtol=1e-5, fast_mode=True)


@pytest.mark.parametrize("stencil", ["ring", "full"])
def test_fused_step_matches_unfused(stencil):
    m, uv, x, v = _case(stencil)
    out = {}
    for fused in (True, False):
        uvp, gp = uv.clone().requires_grad_(), GAMMA.clone().requires_grad_()
        xp, vp = x.clone().requires_grad_(), v.clone().requires_grad_()
        s = step(m, rest_data(m, uvp, 0.15), SimState(xp, vp), SDF, gp, StepParams(fused=fused))
        w = torch.randn(s.x.shape, generator=torch.Generator().manual_seed(2), dtype=torch.float64)
        L = (w * s.x).sum() + (w * s.v).sum()
        out[fused] = (s.x.detach(), torch.autograd.grad(L, (uvp, gp, xp, vp)))
    assert_close(out[True][0], out[False][0], rtol=1e-13, atol=1e-15, what="positions ")
    for a, b, name in zip(out[True][1], out[False][1], ("uv", "gamma", "x", "v")):
        assert_close(a, b, rtol=1e-9, atol=1e-12 * float(b.abs().max()), what=f"d/d{name} ")
