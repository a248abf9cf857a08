"""PatternParams: K -> control points -> U as one precomputed affine map (paper 3.3)."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from helpers import assert_close
from meshing.handmade_patterns import curved_panel, mini_shirt, nonconvex_panel, pentagon, two_squares

from unsew.meshing import mesh_pattern
from unsew.pattern.curves import sample_edge
from unsew.pattern.params import PatternParams, check_inverted
from unsew.tolerances import REBUILD_ATOL

ALL = [two_squares, curved_panel, pentagon, nonconvex_panel, mini_shirt]


def _build(make, h=0.03):
    pat = make()
    m = mesh_pattern(pat, edge_length=h)
    return pat, m, PatternParams.build(pat, m)


@pytest.mark.parametrize("make", ALL)
def test_unchanged_K_gives_unchanged_mesh(make):
    pat, m, pp = _build(make)
    assert pp.K0.shape == (pp.n_k, 2) and pp.K0.dtype == torch.float64
    assert_close(pp.uv(pp.K0), m.uv, atol=1e-12, rtol=0)
    assert_close(pp.control_points(pp.K0), pp.controls.positions, atol=REBUILD_ATOL, rtol=0)
    assert len(check_inverted(pp.uv(pp.K0), m.faces_uv)) == 0
    # control points sit on their mesh vertices
    assert_close(m.uv[pp.control_uv], pp.controls.positions, atol=0)


def _similarity(p, s, th, t):
    r = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    return s * p @ r.T + t


def test_scaled_and_rotated_K_moves_the_mesh_the_same_way():
    # a panel without symmetry: K holds every control point, so any similarity of K is allowed
    pat, m, pp = _build(nonconvex_panel, h=0.02)
    assert pp.n_k == len(pp.controls)
    K = _similarity(pp.K0.numpy(), 1.3, 0.4, [0.1, -0.2])
    assert_close(pp.uv(torch.as_tensor(K)), _similarity(m.uv, 1.3, 0.4, [0.1, -0.2]), atol=1e-12, rtol=0)
    assert_close(pp.uv(1.5 * pp.K0), 1.5 * m.uv, atol=1e-12, rtol=0)


def test_curve_frames_keep_outline_vertices_relative():
    # stretch one curve: its outline vertices stay at the same fractions along its chord frame
    pat, m, pp = _build(nonconvex_panel, h=0.02)
    K = pp.K0.clone()
    K[1] += torch.tensor([0.1, 0.0], dtype=torch.float64)  # move control point 1 (the (0.5, 0) corner) right
    uv = pp.uv(K).numpy()
    e0 = m.edge_verts[("L", 0)]  # straight edge (0,0)->(0.5,0) now (0,0)->(0.6,0)
    assert_close(uv[e0], np.c_[np.linspace(0, 0.6, len(e0)), np.zeros(len(e0))], atol=1e-12, rtol=0)
    # the far edges did not move
    e4 = m.edge_verts[("L", 4)]
    assert_close(uv[e4], m.uv[e4], atol=1e-15, rtol=0)
    assert len(check_inverted(uv, m.faces_uv)) == 0


def test_symmetric_edit_keeps_symmetry_in_the_mesh():
    pat, m, pp = _build(pentagon, h=0.03)
    rng = np.random.default_rng(3)
    K = pp.K0 + torch.as_tensor(rng.normal(scale=0.02, size=(pp.n_k, 2)))
    uv = pp.uv(K).numpy()
    mir = pp.symmetry.mirrors[0]
    d = mir.direction
    H = 2 * np.outer(d, d) - np.eye(2)
    # the mirror image of the deformed outline is the deformed outline
    loop = uv[m.boundary_loop(0)]
    refl = (loop - mir.point) @ H.T + mir.point
    dist = np.linalg.norm(refl[:, None] - loop[None], axis=-1).min(axis=1)
    assert dist.max() < 1e-12


def test_inverted_triangles_are_detected():
    pat, m, pp = _build(nonconvex_panel, h=0.05)
    K = pp.K0.clone()
    assert len(check_inverted(pp.uv(K), m.faces_uv)) == 0
    # drag the (0.5, 0) corner across the panel to the far side: triangles fold over
    K[1] = torch.tensor([-0.3, 0.3], dtype=torch.float64)
    bad = check_inverted(pp.uv(K), torch.as_tensor(m.faces_uv))
    assert len(bad) > 0 and bad.dtype == np.int64
    uv = m.uv.copy()
    f = m.faces_uv[5]
    uv[f[0]], uv[f[1]] = m.uv[f[1]], m.uv[f[0]]  # swapping two corners inverts that triangle
    assert 5 in check_inverted(uv, m.faces_uv)


def test_to_pattern_moves_vertices_and_follows_curves():
    pat, m, pp = _build(curved_panel, h=0.02)
    K = 1.2 * pp.K0
    new = pp.to_pattern(K)
    uv = pp.uv(K).numpy()
    panel = new.panels["P"]
    for i in range(len(panel.edges)):
        ev = m.edge_verts[("P", i)]
        # the moved pattern's edges, resampled, are the moved mesh outline (scaling is a similarity)
        assert_close(sample_edge(panel, i, len(ev) - 1), uv[ev], atol=1e-9, rtol=0, what=f"edge {i}: ")
    assert pat.panels["P"].edges[2].curvature.params[0] == 0.3  # the original is untouched


def test_k_from_control_points_projects_edits():
    pat, m, pp = _build(mini_shirt, h=0.05)
    C0 = pp.control_points(pp.K0)
    assert_close(pp.k_from_control_points(C0), pp.K0, atol=1e-10, rtol=0)
    rng = np.random.default_rng(0)
    K = pp.K0 + torch.as_tensor(rng.normal(scale=0.01, size=(pp.n_k, 2)))
    C = pp.control_points(K)
    assert_close(pp.k_from_control_points(C), K, atol=1e-10, rtol=0)
    # an asymmetric edit is projected: the result is symmetric and closer to the wish than K0
    wish = C0.clone()
    wish[0] += torch.tensor([0.05, 0.0], dtype=torch.float64)
    Kp = pp.k_from_control_points(wish)
    Cp = pp.control_points(Kp)
    assert (Cp - wish).norm() < (C0 - wish).norm()
    assert_close(pp.k_from_control_points(Cp), Kp, atol=1e-10, rtol=0)


def test_mismatched_symmetry_is_rejected():
    from unsew.errors import PatternError
    from unsew.pattern.symmetry import detect_symmetry

    pat = pentagon()
    sym = detect_symmetry(pat)
    pat.panels["H"].vertices[3, 1] += 0.1
    with pytest.raises(PatternError):
        PatternParams.build(pat, mesh_pattern(pat, edge_length=0.05), symmetry=sym)


def test_tshirt_params():
    from unsew.pattern.base import make_base_pattern

    pat = make_base_pattern("tshirt")
    m = mesh_pattern(pat, edge_length=0.03)
    pp = PatternParams.build(pat, m)
    assert 2 * pp.n_k <= len(pp.controls)
    assert_close(pp.uv(pp.K0), m.uv, atol=1e-12, rtol=0)
    # widen the garment a little through K: the sleeves stay mirror images, nothing folds over
    K = pp.K0.clone()
    K[:, 0] *= 1.05
    uv = pp.uv(K)
    assert len(check_inverted(uv, m.faces_uv)) == 0
    pair = pp.symmetry.pairs[0]
    names = m.panel_names
    a, b = names.index(pair.source), names.index(pair.target)
    ua, ub = uv[m.uv_panel == a].numpy(), uv[m.uv_panel == b].numpy()
    # mirror images have the same outline lengths and areas
    assert_close(_area(uv.numpy(), m, a), _area(uv.numpy(), m, b), rtol=1e-12)
    assert len(ua) == len(ub)
    new = pp.to_pattern(K)
    assert set(new.panels) == set(pat.panels)


def _area(uv, m, p):
    loop = uv[m.boundary_loop(p)]
    x, y = loop.T
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def test_to_moves_the_maps_and_K0_follows():
    """``to(device)`` moves the four maps (itself when they are there); K0 is made on their
    device; the original stays on the CPU. A GPU run is in tests/fit/test_cuda.py."""
    _, _, pp = _build(two_squares)
    assert pp.to("cpu") is pp
    moved = pp.to("meta")
    assert all(t.device.type == "meta" for t in (moved.L_c, moved.b_c, moved.L_u, moved.b_u, moved.K0))
    assert moved.symmetry is pp.symmetry and pp.L_u.device.type == "cpu"
