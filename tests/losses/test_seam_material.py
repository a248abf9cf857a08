"""Seam-consistency loss (eq. 8) and material range penalty."""

from types import SimpleNamespace

import numpy as np
import pytest
import torch

from helpers import assert_close
from unsew.errors import PatternError
from unsew.losses.material import loss_material
from unsew.losses.seam import loss_seam, seam_segment_pairs
from unsew.pattern.model import Stitch, StitchSide


def _two_strips(scale_b=1.0):
    """Two panels with one stitched edge each: a's edge 0 runs up x=0, b's edge 1 runs down x=1.

    uv: a's edge vertices 0..3 at y = 0, .1, .3, .6; b's edge vertices 4..7 (b runs from top to
    bottom, so reversed it faces a).
    """
    ya = np.array([0.0, 0.1, 0.3, 0.6])
    yb = (ya * scale_b)[::-1]
    uv = np.concatenate([np.c_[np.zeros(4), ya], np.c_[np.ones(4), yb]])
    mesh = SimpleNamespace(edge_verts={("a", 0): np.arange(4), ("b", 1): np.arange(4, 8)})
    stitches = [Stitch(StitchSide("a", 0), StitchSide("b", 1))]
    return torch.tensor(uv), mesh, stitches


def test_zero_when_lengths_match_and_known_value_otherwise():
    uv, mesh, st = _two_strips()
    assert loss_seam(uv, mesh, st).item() == pytest.approx(0.0, abs=1e-30)
    uv, mesh, st = _two_strips(scale_b=2.0)
    # segment lengths a: .1 .2 .3 ; b (reversed): .2 .4 .6 -> sum of squares .01 + .04 + .09
    assert_close(loss_seam(uv, mesh, st), 0.14, rtol=1e-12)


def test_direction_convention_a_start_meets_b_end():
    uv, mesh, st = _two_strips()
    p = seam_segment_pairs(mesh, st)
    assert p.tolist()[0] == [0, 1, 7, 6]
    # if b were not reversed the non-uniform spacing would not cancel
    wrong = [Stitch(StitchSide("a", 0), StitchSide("b", 1))]
    mesh_rev = SimpleNamespace(edge_verts={("a", 0): np.arange(4), ("b", 1): np.arange(4, 8)[::-1]})
    assert loss_seam(uv, mesh_rev, wrong).item() > 1e-3


def test_pairs_and_stitches_from_mesh():
    uv, mesh, st = _two_strips(scale_b=2.0)
    mesh.stitches = st
    assert_close(loss_seam(uv, mesh), loss_seam(uv, pairs=seam_segment_pairs(mesh, st)), rtol=0)


def test_errors():
    uv, mesh, st = _two_strips()
    with pytest.raises(PatternError, match="does not have"):
        seam_segment_pairs(mesh, [Stitch(StitchSide("a", 0), StitchSide("c", 0))])
    mesh.edge_verts[("b", 1)] = np.arange(4, 7)
    with pytest.raises(PatternError, match="vertices"):
        seam_segment_pairs(mesh, st)


def test_material_penalty():
    g = torch.tensor([1.0, -2e-6, 0.0, 1e-6, 5.0], dtype=torch.float64, requires_grad=True)
    loss = loss_material(g)
    assert_close(loss, 3e-6 + 1e-6, rtol=1e-12)
    loss.backward()
    assert g.grad.tolist() == [0.0, -1.0, -1.0, 0.0, 0.0]


def test_real_garment_mesh_seams():
    """Against meshing's GarmentMesh: stitched sides of a base skirt have equal lengths, and
    scaling the uv of one side of every stitch by s gives (1 - s)^2 sum |e|^2."""
    base = pytest.importorskip("unsew.pattern.base")
    sew = pytest.importorskip("unsew.meshing.sew")
    pattern = base.make_base_pattern("skirt")
    mesh = sew.mesh_pattern(pattern, edge_length=0.03)
    uv = torch.tensor(mesh.uv)
    pairs = seam_segment_pairs(mesh, pattern.stitches)
    assert len(pairs) > 0
    la = (uv[pairs[:, 1]] - uv[pairs[:, 0]]).norm(dim=1)
    lb = (uv[pairs[:, 3]] - uv[pairs[:, 2]]).norm(dim=1)
    assert_close(la, lb, atol=1e-6)  # facing segments of equal length: sewing vertex to vertex
    assert loss_seam(uv, mesh, pattern.stitches).item() < 1e-10
    s = 1.05
    side_b = torch.zeros(len(uv), dtype=torch.bool)
    side_b[torch.as_tensor(pairs[:, 2:]).ravel()] = True
    assert not side_b[torch.as_tensor(pairs[:, :2]).ravel()].any()
    uv2 = torch.where(side_b[:, None], uv * s, uv)
    assert_close(loss_seam(uv2, mesh, pattern.stitches), ((la - s * lb) ** 2).sum(), rtol=1e-12)
