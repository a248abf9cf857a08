"""Sewing a seam whose copies start on either side of a limb: around it, not through it."""

import numpy as np
import torch

from unsew.sim import MATERIALS, Cloth, DrapeSettings, SimModel
from unsew.sim.drape import sew
from unsew.sim.meshes import two_panels
from unsew.sim.sdf_analytic import CapsuleSDF
from unsew.sim.seam_guide import GUIDE_CLEARANCE, through_pairs, waypoints

GAMMA = MATERIALS["cotton"].gamma()
R = 0.06  # the arm's radius [m]
ARM = CapsuleSDF((-0.3, 0.0, 0.0), (0.3, 0.0, 0.0), R)


def _over_arm(n=4, size=0.1, top=0.01):
    """Two panels hanging in front of and behind a horizontal arm (along x, at y = z = 0), their
    sewn edges at height ``top`` [m], 1 cm off its surface: a shoulder seam's start."""
    p = two_panels(n, size)
    uv = p["uv"]
    a = np.arange(len(uv)) < (n + 1) ** 2
    x = np.zeros((len(uv), 3))
    x[a] = np.c_[uv[a, 1] - size / 2, top - (size - uv[a, 0]), np.full(a.sum(), R + 0.01)]
    x[~a] = np.c_[uv[~a, 1] - size / 2, top - (uv[~a, 0] - 1.25 * size), np.full((~a).sum(), -(R + 0.01))]
    return p, x


def _sew(p, x, guide: bool, edge_contact: bool = False):
    mu = SimModel.build(p["faces_uv"], p["faces_uv"], springs=p["seam_pairs"])
    cloth = Cloth(torch.as_tensor(p["uv"]), GAMMA, 0.12, friction=0.3)
    settings = DrapeSettings(sew_steps=30, seam_guide=guide, edge_contact=edge_contact)
    return sew(mu, x, ARM, cloth, settings=settings)


def test_waypoint_lies_outside_the_arm_above_the_seam_line():
    p, x = _over_arm()
    xt = torch.as_tensor(x)
    sp = torch.as_tensor(p["seam_pairs"])
    assert bool(through_pairs(xt, sp, ARM).all())
    w = waypoints(xt, sp, ARM)
    d = ARM.query(w)[0]
    assert float((d - GUIDE_CLEARANCE).abs().max()) < 2e-3
    assert float(w[:, 1].min()) > R  # over the arm, the seam line's side of its axis
    # a pair whose line misses the body is pulled to its midpoint
    xt2 = xt + torch.tensor([0.0, 0.5, 0.0], dtype=torch.float64)
    mid = 0.5 * (xt2[sp[:, 0]] + xt2[sp[:, 1]])
    assert float((waypoints(xt2, sp, ARM) - mid).abs().max()) == 0.0


def test_seam_across_an_arm_closes_over_it():
    p, x = _over_arm()
    sp = p["seam_pairs"]
    xs = _sew(p, x, guide=True)
    gap = (xs[sp[:, 0]] - xs[sp[:, 1]]).norm(dim=1)
    assert float(gap.max()) < 2e-3  # closed
    assert float(xs[sp[:, 0], 1].min()) > R  # on top of the arm
    assert float(ARM.query(xs)[0].min()) > 0.0
    # pulled straight at itself, with the body repelling vertices only, it stays caught on the
    # arm, 12 cm open; with the edges' midpoints repelled too (dress()'s last fallback) it slides over it
    plain = _sew(p, x, guide=False)
    assert float((plain[sp[:, 0]] - plain[sp[:, 1]]).norm(dim=1).max()) > 0.05
    edges = _sew(p, x, guide=False, edge_contact=True)
    assert float((edges[sp[:, 0]] - edges[sp[:, 1]]).norm(dim=1).max()) < 2e-3
    assert float(edges[sp[:, 0], 1].min()) > R and float(ARM.query(edges)[0].min()) > 0.0


def test_base_tshirt_on_default_body_is_sewn_as_without_the_guide():
    """No seam of unsew's own t-shirt starts across the body: the guide changes nothing."""
    from unsew.body.body import default_body
    from unsew.body.placement import place_garment
    from unsew.body.sdf import BodySDF
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    body = default_body()
    sdf = BodySDF.build(body)
    pattern = make_base_pattern("tshirt")
    mesh = mesh_pattern(pattern, edge_length=0.04)
    x0 = place_garment(pattern, mesh, body, sdf=sdf)
    mu = SimModel.build(mesh.faces_uv, mesh.faces_uv, springs=mesh.seam_pairs)
    sp = torch.as_tensor(np.asarray(mesh.seam_pairs), dtype=torch.int64)
    assert not bool(through_pairs(torch.as_tensor(np.asarray(x0)), sp, sdf).any())
    cloth = Cloth(torch.as_tensor(np.asarray(mesh.uv)), GAMMA, 0.12, friction=0.3)
    run = [sew(mu, x0, sdf, cloth, settings=DrapeSettings(sew_steps=3, seam_guide=g)) for g in (True, False)]
    assert torch.equal(run[0], run[1])
