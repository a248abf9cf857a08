"""The "ring" bending stencil (model.py): a smaller sparsity pattern, a system block that
dominates the full Gauss-Newton hinge block (so stays PSD and never less stiff), and the same
forces, hence the same equilibrium as the "full" stencil."""

import numpy as np
import torch
from helpers import assert_close

from unsew.sim import CapsuleSDF, Cloth, SimModel, SimState, drape
from unsew.sim.energies.bending import energy_bending
from unsew.sim.integrator import StepParams, _pattern, forces, rest_data
from unsew.sim.meshes import grid_sheet, two_panels

GAMMA = torch.tensor([800.0, 80.0, 600.0, 60.0, 6e-5], dtype=torch.float64)


def _sheet():
    uv, f = grid_sheet(3, 3, 0.1, 0.1)
    g = torch.Generator().manual_seed(0)
    x = torch.stack(
        [torch.as_tensor(uv[:, 0]), torch.zeros(len(uv), dtype=torch.float64), torch.as_tensor(uv[:, 1])], 1
    )
    x = x + 0.01 * torch.randn(x.shape, generator=g, dtype=torch.float64)
    return uv, f, x


def test_ring_pattern_drops_only_opposite_vertex_pairs():
    uv, f, _ = _sheet()
    full = SimModel.build(f, f, bending_stencil="full")
    ring = SimModel.build(f, f, bending_stencil="ring")
    kf = set(zip((full.rows // 3).tolist(), (full.cols // 3).tolist()))
    kr = set(zip((ring.rows // 3).tolist(), (ring.cols // 3).tolist()))
    edges = {
        (max(a, b), min(a, b)) for t in f.tolist() for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))
    }
    diag = {(i, i) for i in range(full.n)}
    assert kr == edges | diag  # the mesh's 1-ring exactly
    assert kr < kf and ring.nnz < full.nnz


def test_ring_system_dominates_full_and_is_psd():
    uv, f, x = _sheet()
    uvt = torch.as_tensor(uv)
    sdf = CapsuleSDF((0.0, -1.0, 0.0), (0.0, -1.0, 1.0), 0.01)  # far away: no contact
    K = {}
    for s in ("full", "ring"):
        m = SimModel.build(f, f, bending_stencil=s)
        rest = rest_data(m, uvt, 0.15)
        _, Kv, *_ = forces(m, rest, SimState.at_rest(x), sdf, GAMMA, StepParams())
        K[s] = _pattern(m).dense(Kv)
    diff = K["ring"] - K["full"]
    assert float(torch.linalg.eigvalsh(diff).min()) > -1e-9 * float(K["full"].abs().max())
    assert float(torch.linalg.eigvalsh(K["ring"]).min()) > -1e-9 * float(K["ring"].abs().max())
    # the difference is exactly the bending correction 2c (g2; -g3)(g2; -g3)^T per hinge
    m = SimModel.build(f, f)
    rest = rest_data(m, uvt, 0.15)
    _, _, Hb = energy_bending(x, m.hinges, rest.coef, GAMMA)
    assert_close(float(torch.trace(diff)), float(Hb[:, 6:, 6:].diagonal(dim1=1, dim2=2).sum()), rtol=1e-10)


def test_same_equilibrium_for_both_stencils():
    p = two_panels(3, 0.08)
    sdf = CapsuleSDF((0.0, -0.05, -0.3), (0.0, -0.05, 0.3), 0.05)
    uv = torch.as_tensor(p["uv"])
    xy = np.zeros((p["n_x"], 2))
    shift = np.where(np.arange(uv.shape[0]) >= uv.shape[0] // 2, 0.08 * 0.25, 0.0)
    xy[p["x_of_u"]] = p["uv"] - np.c_[shift, np.zeros_like(shift)]
    x0 = np.c_[xy[:, 0] - 0.08, np.full(p["n_x"], 0.003), xy[:, 1] - 0.04]
    out = {}
    with torch.no_grad():
        for s in ("full", "ring"):
            m = SimModel.build(p["faces"], p["faces_uv"], n=p["n_x"], bending_stencil=s)
            out[s] = drape(m, SimState.at_rest(x0), sdf, Cloth(uv, GAMMA, 0.15), steps=100).x
    assert_close(out["ring"], out["full"], atol=5e-5, what="equilibria (m) ")
