"""Gathered seams: a wide panel sewn to a narrow band is gathered, the band is not stretched."""

import numpy as np
import torch

from unsew.meshing import mesh_pattern
from unsew.meshing.gather import GATHER_BAND, gather_maps
from unsew.pattern.model import Panel, Pattern, Stitch, StitchSide
from unsew.sim import MATERIALS, Cloth, DrapeSettings, SimModel, SimState
from unsew.sim.drape import drape
from unsew.sim.sdf_analytic import CapsuleSDF

from .handmade_patterns import loop_edges, two_squares

BAND_W, SKIRT_W = 0.2, 0.4  # [m]


def _band_and_skirt(skirt_w: float = SKIRT_W) -> Pattern:
    """A 6 cm band whose bottom edge (edge 0) is sewn to the top edge (edge 2) of a skirt panel
    ``skirt_w`` wide and 30 cm long."""
    band = np.array([[0, 0], [BAND_W, 0], [BAND_W, 0.06], [0, 0.06]], float)
    skirt = np.array([[0, 0], [skirt_w, 0], [skirt_w, 0.3], [0, 0.3]], float)
    return Pattern(
        "gathered",
        {"band": Panel("band", band, loop_edges(4)), "skirt": Panel("skirt", skirt, loop_edges(4))},
        [Stitch(StitchSide("band", 0), StitchSide("skirt", 2), "waist")],
    )


def test_only_the_longer_side_of_an_unequal_stitch_is_gathered():
    mesh = mesh_pattern(_band_and_skirt(), edge_length=0.02)
    g = mesh.gather
    assert g is not None and g.shape == (len(mesh.faces_uv), 2, 2)
    skirt = mesh.panel_names.index("skirt")
    on_skirt = mesh.uv_panel[mesh.faces_uv[:, 0]] == skirt
    assert np.allclose(g[~on_skirt], np.eye(2))  # the band keeps its own rest shape
    # a skirt triangle on the seam is shortened along it (x) to the band's length, not across
    top = mesh.uv[mesh.faces_uv, 1].max(axis=1) > 0.3 - 1e-9
    seam = on_skirt & top
    assert np.allclose(g[seam][:, 0, 0], BAND_W / SKIRT_W) and np.allclose(g[seam][:, 1, 1], 1.0)
    # a band's width below the seam it is the skirt's own again
    low = on_skirt & (mesh.uv[mesh.faces_uv, 1].max(axis=1) < 0.3 - GATHER_BAND)
    assert low.any() and np.allclose(g[low], np.eye(2))
    # equal sides are sewn as they are
    assert mesh_pattern(two_squares(), edge_length=0.05).gather is None
    assert mesh_pattern(_band_and_skirt(BAND_W * 1.01), edge_length=0.02).gather is None
    assert gather_maps(mesh.uv, mesh.faces_uv, mesh.uv_panel, mesh.panel_names, mesh.edge_verts, []) is None


def _hang(mesh, gathered: bool, steps: int = 40):
    """The band held at its top, the skirt sewn below it, started flat and gathered to the band's
    width; returns the sewn positions (n_x, 3) [m] after ``steps`` steps."""
    uv = mesh.uv
    on_band = mesh.uv_panel == mesh.panel_names.index("band")
    skirt_at = np.c_[uv[:, 0] * BAND_W / SKIRT_W, uv[:, 1] - 0.3]
    x_uv = np.where(on_band[:, None], uv, skirt_at)
    x0 = np.zeros((mesh.n_x, 3))
    x0[mesh.x_of_u, :2] = x_uv
    pinned = np.zeros(mesh.n_x, bool)
    pinned[mesh.x_of_u[on_band & (uv[:, 1] > 0.06 - 1e-9)]] = True
    rest_map = mesh.gather if gathered else None
    model = SimModel.build(mesh.faces, mesh.faces_uv, pinned=pinned, rest_map=rest_map)
    far = CapsuleSDF((0.0, -5.0, 0.0), (0.1, -5.0, 0.0), 0.01)
    cloth = Cloth(torch.as_tensor(uv), MATERIALS["cotton"].gamma(), 0.12, friction=0.0)
    start = SimState.at_rest(torch.as_tensor(x0))
    return drape(model, start, far, cloth, settings=DrapeSettings(), steps=steps).x


def test_a_gathered_skirt_leaves_its_band_unstretched():
    mesh = mesh_pattern(_band_and_skirt(), edge_length=0.02)
    seam = mesh.x_of_u[mesh.edge_verts[("band", 0)]]

    def seam_stretch(x):
        return float((x[seam[1:]] - x[seam[:-1]]).norm(dim=1).sum()) / BAND_W

    gathered, plain = seam_stretch(_hang(mesh, True)), seam_stretch(_hang(mesh, False))
    assert gathered < 1.03  # the skirt eased in: the band keeps its length
    assert plain > 1.12  # sewn vertex to vertex, the skirt's top stretches the band


def test_a_gathered_triangle_rests_in_its_gathered_shape():
    from unsew.sim.energies.membrane import energy_membrane, membrane_rest

    uv = torch.tensor([[0.0, 0.0], [0.04, 0.0], [0.01, 0.03]], dtype=torch.float64)
    faces = torch.tensor([[0, 1, 2]])
    g = torch.tensor([[[0.5, 0.0], [0.0, 1.0]]], dtype=torch.float64)  # shortened along u by half
    area, B, _ = membrane_rest(uv, faces, g)
    assert float(area[0]) == float(membrane_rest(uv, faces)[0][0])  # the pattern's own area
    gamma = MATERIALS["cotton"].gamma()
    gathered = torch.cat([uv @ g[0].T, torch.zeros(3, 1, dtype=torch.float64)], 1)
    flat = torch.cat([uv, torch.zeros(3, 1, dtype=torch.float64)], 1)
    assert float(energy_membrane(gathered, faces, area, B, gamma, hessian=False)[0]) < 1e-20
    assert float(energy_membrane(flat, faces, area, B, gamma, hessian=False)[0]) > 1e-4
