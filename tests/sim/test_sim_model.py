"""SimModel: hinges, sparsity pattern and index maps."""

import numpy as np
import pytest
import torch

from unsew.errors import InputError
from unsew.sim.assembly import scatter_blocks
from unsew.sim.meshes import grid_sheet, two_panels
from unsew.sim.model import SimModel
from unsew.sim.solve import SparsePattern


def test_hinges_of_grid():
    uv, f = grid_sheet(3, 2, 0.3, 0.2)
    m = SimModel.build(f, f)
    # interior edges of a 3x2 quad grid with diagonals: 3F/2 - boundary/2
    n_edges_boundary = 2 * (3 + 2)
    assert m.hinges.shape[0] == (3 * f.shape[0] - n_edges_boundary) // 2
    # hinge edge vertices belong to both faces; opposite vertices are not on the edge
    for h, (fa, fb) in zip(m.hinges.numpy(), m.hinge_faces.numpy()):
        assert {h[0], h[1], h[2]} == set(f[fa]) and {h[0], h[1], h[3]} == set(f[fb])


def test_seam_hinges_cross_the_seam():
    p = two_panels(3, 0.1)
    m_sewn = SimModel.build(p["faces"], p["faces_uv"])
    m_unsewn = SimModel.build(p["faces_uv"], p["faces_uv"])
    assert m_sewn.hinges.shape[0] - m_unsewn.hinges.shape[0] == 3  # one hinge per seam segment


def test_index_maps_reproduce_dense_assembly():
    uv, f = grid_sheet(2, 2, 0.2, 0.2)
    m = SimModel.build(f, f, springs=[[0, 8]])
    g = torch.Generator().manual_seed(0)
    blocks = torch.randn(f.shape[0], 9, 9, generator=g, dtype=torch.float64)
    blocks = blocks + blocks.transpose(1, 2)
    vals = scatter_blocks(m.nnz, m.tri_src, m.tri_dst, blocks)
    dense = SparsePattern(3 * m.n, m.rows, m.cols).dense(vals)
    ref = torch.zeros(3 * m.n, 3 * m.n, dtype=torch.float64)
    for e in range(f.shape[0]):  # plain loop: the reference
        dof = (3 * torch.as_tensor(f[e])[:, None] + torch.arange(3)).reshape(-1)
        ref[dof[:, None], dof[None, :]] += blocks[e]
    assert torch.allclose(dense, ref, atol=1e-12)
    assert bool((m.rows >= m.cols).all())


def test_pinned_keep_mask():
    uv, f = grid_sheet(2, 2, 0.2, 0.2)
    m = SimModel.build(f, f, pinned=[0])
    r, c = m.rows.long(), m.cols.long()
    touches = (r < 3) | (c < 3)
    assert torch.all(m.keep[touches] == 0) and torch.all(m.keep[~touches] == 1)


def test_bad_faces_raise():
    with pytest.raises(InputError):
        SimModel.build(np.zeros((0, 3), int), np.zeros((0, 3), int))
    with pytest.raises(InputError):
        SimModel.build([[0, 1, 1]], [[0, 1, 2]])
    with pytest.raises(InputError):
        SimModel.build([[0, 1, 2]], [[0, 1]])
