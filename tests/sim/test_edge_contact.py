"""The body repels mesh edges' midpoints (DrapeSettings.edge_contact): rods thinner than the
cloth's edges, between two columns of vertices, catch the cloth only when edges are repelled."""

import torch

from unsew.sim import MATERIALS, CapsuleSDF, Cloth, DrapeSettings, SimModel, SimState, drape
from unsew.sim.integrator import StepParams, _terms, total_energy, rest_data
from unsew.sim.meshes import grid_sheet

GAMMA = MATERIALS["cotton"].gamma()
ROD = 0.008  # rod radius [m], under half the sheet's 5 cm edges


class _Rods:
    """Two parallel rods along z at x = -0.1 and 0.1 m, y = 0 (the SDF's query protocol)."""

    rods = tuple(CapsuleSDF((x, 0.0, -1.0), (x, 0.0, 1.0), ROD) for x in (-0.1, 0.1))

    def query(self, x):
        (d0, n0), (d1, n1) = (r.query(x) for r in self.rods)
        near = (d0 < d1)[:, None]
        return torch.minimum(d0, d1), torch.where(near, n0, n1)


def _sheet_over_rods():
    """A 0.35 m sheet of 5 cm cells, 3 mm above the rods, each rod between two columns of
    vertices (every vertex 2.5 cm from a rod's axis, seen from above)."""
    uv, f = grid_sheet(7, 7, 0.35, 0.35)
    m = SimModel.build(f, f)
    u, v = torch.as_tensor(uv[:, 0]), torch.as_tensor(uv[:, 1])
    x = torch.stack([u - 0.175, torch.full_like(u, ROD + 0.003), v - 0.175], 1)
    return m, torch.as_tensor(uv), SimState.at_rest(x)


def _dropped(edge_contact: bool):
    m, uv, st = _sheet_over_rods()
    rod = _Rods()
    settings = DrapeSettings(edge_contact=edge_contact)
    return drape(m, st, rod, Cloth(uv, GAMMA, 0.12), steps=20, settings=settings).x


def test_rods_between_vertices_catch_the_cloth_only_with_edge_contact():
    caught = _dropped(True)
    fallen = _dropped(False)
    assert float(caught[:, 1].max()) > 0.0  # hangs over the rods, its middle on top
    assert float(fallen[:, 1].max()) < -0.5  # fell past them: no vertex ever touched them


def test_edge_contact_forces_are_the_energy_gradient():
    m, uv, st = _sheet_over_rods()
    rod = _Rods()
    rest = rest_data(m, uv, 0.12)
    params = StepParams(edge_contact=True, gravity=0.0)
    x = st.x.clone()
    x[:, 1] -= 0.009  # the midpoints of the edges across the rods now 1 mm in them
    x = x.requires_grad_(True)
    e = total_energy(m, rest, x, rod, GAMMA, params)
    (g,) = torch.autograd.grad(e, x)
    f = _terms(m, rest, x.detach(), rod, GAMMA, params, hessian=False).f
    assert float(g.abs().max()) > 1e-3  # the midpoints are pushed
    assert torch.allclose(-g, f, rtol=1e-6, atol=1e-9)
