"""Symmetric meshing: mirrored halves and transported pair meshes are exact mirror images."""

import numpy as np
import pytest

from unsew.meshing.sew import mesh_pattern
from unsew.meshing.symmetric import reflect, transport_mesh, triangulate_mirrored
from unsew.meshing.triangulate import signed_areas, triangulate_polygon
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import sample_edge


def _face_set(tris):
    return {tuple(sorted(t)) for t in np.asarray(tris).tolist()}


def _mirror_map(uv_a, uv_b, f):
    """Index map a -> b with f(uv_a) == uv_b (exactly, to 1e-12)."""
    from scipy.spatial import cKDTree

    d, idx = cKDTree(uv_b).query(f(uv_a))
    assert d.max() < 1e-12
    return idx


def test_mirrored_triangulation_is_its_own_mirror_image():
    # a symmetric pentagon (house shape), axis x = 0, sampled so the axis hits two samples
    t = np.linspace(0, 1, 9)[:-1, None]
    corners = np.array([[-0.2, 0.0], [0.2, 0.0], [0.2, 0.3], [0.0, 0.45], [-0.2, 0.3]])
    outline = np.concatenate([a + t * (b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))])
    verts, tris = triangulate_mirrored(outline, np.zeros(2), np.array([0.0, 1.0]), edge_length=0.03)
    assert np.allclose(verts[: len(outline)], outline, atol=1e-12)
    assert (signed_areas(verts, tris) > 0).all()
    idx = _mirror_map(verts, verts, lambda p: reflect(p, np.zeros(2), np.array([0.0, 1.0])))
    assert _face_set(idx[tris]) == _face_set(tris)
    # the area is the polygon's
    ref_v, ref_t = triangulate_polygon(outline, edge_length=0.03)
    assert signed_areas(verts, tris).sum() == pytest.approx(signed_areas(ref_v, ref_t).sum(), rel=1e-12)


def test_asymmetric_outline_is_refused():
    outline = np.array([[0.0, 0.0], [0.3, 0.0], [0.3, 0.2], [0.0, 0.25]])
    assert (
        triangulate_mirrored(outline, np.array([0.15, 0.0]), np.array([0.0, 1.0]), edge_length=0.05) is None
    )


def test_transport_onto_mirrored_panel():
    rng = np.random.default_rng(0)
    ang = np.sort(rng.uniform(0, 2 * np.pi, 40))
    src = np.c_[np.cos(ang) * (1 + 0.2 * np.sin(3 * ang)), np.sin(ang)] * 0.2
    sv, st = triangulate_polygon(src, edge_length=0.03)
    dst = (src * [-1.0, 1.0])[::-1] + [1.0, 0.5]  # mirrored and moved; CCW again after reversing
    dst = np.roll(dst, 7, axis=0)
    res = transport_mesh(src, sv, st, dst, mirrored=True, edge_length=0.03)
    assert res is not None
    verts, tris = res
    assert np.allclose(verts[: len(dst)], dst, atol=1e-12)
    assert (signed_areas(verts, tris) > 0).all()
    assert len(tris) == len(st)
    assert (
        transport_mesh(src, sv, st, dst + rng.normal(0, 0.02, dst.shape), mirrored=True, edge_length=0.03)
        is None
    )


@pytest.mark.parametrize("garment", ["tshirt", "pants", "skirt"])
def test_base_patterns_mesh_symmetrically(garment):
    p = make_base_pattern(garment)
    m = mesh_pattern(p, edge_length=0.03, symmetric=True)
    assert "own" not in m.panel_symmetry.values() or garment == "pants"
    for name, how in m.panel_symmetry.items():
        if how == "own":
            continue
        pi = m.panel_names.index(name)
        sel = np.flatnonzero(m.uv_panel == pi)
        if how == "mirror":
            uv = m.uv[sel]
            c = 0.5 * (uv[:, 0].min() + uv[:, 0].max())
            idx = _mirror_map(uv, uv, lambda q: q * [-1.0, 1.0] + [2 * c, 0.0])
            local = {g: k for k, g in enumerate(sel)}
            tris = np.array([[local[v] for v in t] for t in m.faces_uv if m.uv_panel[t[0]] == pi])
            assert _face_set(idx[tris]) == _face_set(tris)
        else:
            src = m.panel_names.index(how.split(":", 1)[1])
            assert (m.uv_panel == src).sum() == len(sel)
    assert m.quality()["bad_triangles"] == 0
    # the outline is still the sampled edges, snapped to exact symmetry by far less than 1e-3 h,
    # and pattern corners stay where they are
    for name in m.panel_names:
        panel = p.panels[name]
        for i, e in enumerate(panel.edges):
            ev = m.edge_verts[(name, i)]
            assert np.abs(m.uv[ev] - sample_edge(panel, i, len(ev) - 1)).max() < 1e-6 * 0.03
            assert np.abs(m.uv[ev[0]] - panel.vertices[e.start]).max() < 1e-12
    plain = mesh_pattern(p, edge_length=0.03)
    assert set(plain.panel_symmetry.values()) == {"own"}
    assert abs(m.n_x - plain.n_x) < 0.05 * plain.n_x
