"""mesh_pattern: panel triangulation, seams sewn vertex to vertex, the sewn mesh X and its map to U."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import assert_close
from meshing.handmade_patterns import curved_panel, mini_shirt, nonconvex_panel, pentagon, two_squares

from unsew.errors import InputError, PatternError
from unsew.meshing import GarmentMesh, mesh_pattern, write_rest_obj
from unsew.meshing.triangulate import signed_areas, triangle_min_angles
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Stitch, StitchSide

ALL = [two_squares, curved_panel, pentagon, nonconvex_panel, mini_shirt]


@pytest.mark.parametrize("make", ALL)
@pytest.mark.parametrize("h", [0.01, 0.03])
def test_quality_ccw_nondegenerate(make, h):
    m = mesh_pattern(make(), edge_length=h)
    assert isinstance(m, GarmentMesh)
    assert triangle_min_angles(m.uv, m.faces_uv).min() >= 20.0 - 1e-9
    area = signed_areas(m.uv, m.faces_uv)
    assert area.min() > 1e-3 * h * h  # CCW and far from degenerate
    # no triangle spans two panels
    assert (m.uv_panel[m.faces_uv] == m.uv_panel[m.faces_uv[:, :1]]).all()
    # every vertex is used
    assert np.array_equal(np.unique(m.faces_uv), np.arange(m.n_uv))


@pytest.mark.parametrize("make", ALL)
def test_boundary_is_the_sampled_outline(make):
    pat = make()
    h = 0.02
    m = mesh_pattern(pat, edge_length=h)
    for p, name in enumerate(m.panel_names):
        panel = pat.panels[name]
        for i, e in enumerate(panel.edges):
            ev = m.edge_verts[(name, i)]
            n = len(ev) - 1
            assert n >= max(1, int(np.ceil(edge_length(panel, i) / h - 1e-9)))
            assert_close(m.uv[ev], sample_edge(panel, i, n), atol=1e-15, what=f"{name} edge {i}: ")
            assert_close(m.uv[ev[0]], panel.vertices[e.start], atol=0, what="corner: ")
            assert_close(m.uv[ev[-1]], panel.vertices[e.end], atol=0, what="corner: ")
        loop = m.boundary_loop(p)
        assert np.array_equal(
            np.concatenate([m.edge_verts[(name, i)][:-1] for i in range(len(panel.edges))]), loop
        )
        # the outline is a boundary of the 2D mesh: each outline segment belongs to exactly one triangle
        f = m.faces_uv[m.uv_panel[m.faces_uv[:, 0]] == p]
        edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
        uniq, count = np.unique(edges, axis=0, return_counts=True)
        boundary = {tuple(e) for e in uniq[count == 1]}
        outline = {tuple(sorted((int(loop[k]), int(loop[(k + 1) % len(loop)])))) for k in range(len(loop))}
        assert boundary == outline


def test_a_pattern_off_in_its_last_bits_meshes_the_same():
    """Another processor's arithmetic (or a file written in cm and read in m) moves a pattern's
    numbers by a bit or two; the mesh, and so every drape of it, must not change with them."""
    pat = mini_shirt()
    m = mesh_pattern(pat, edge_length=0.02)
    rng = np.random.default_rng(0)
    for _ in range(3):
        for panel in pat.panels.values():
            v = panel.vertices
            panel.vertices = v * (1.0 + rng.integers(-2, 3, v.shape) * np.finfo(float).eps)
        m2 = mesh_pattern(pat, edge_length=0.02)
        assert m2.n_uv == m.n_uv and np.array_equal(m2.faces_uv, m.faces_uv)
        assert_close(m2.uv, m.uv, atol=1e-9)


def test_seams_vertex_to_vertex_and_sewn_map():
    pat = two_squares()
    m = mesh_pattern(pat, edge_length=0.02)
    ea, eb = m.edge_verts[("A", 1)], m.edge_verts[("B", 3)]
    assert len(ea) == len(eb)
    assert np.array_equal(m.seam_pairs, np.stack([ea, eb[::-1]], axis=1))
    # the squares are placed side by side, so sewn vertices coincide in 3D
    assert_close(m.uv_placed3d[m.seam_pairs[:, 0]], m.uv_placed3d[m.seam_pairs[:, 1]], atol=1e-12)
    assert np.array_equal(m.x_of_u[m.seam_pairs[:, 0]], m.x_of_u[m.seam_pairs[:, 1]])
    assert m.n_x == m.n_uv - len(ea)
    assert np.array_equal(m.faces, m.x_of_u[m.faces_uv])
    # the sewn mesh is one disk: every edge in at most two triangles, the seam edges in exactly two
    f = m.faces
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    assert count.max() == 2
    xs = m.x_of_u[ea]
    seam_edges = {tuple(sorted(e)) for e in zip(xs[:-1], xs[1:])}
    assert seam_edges <= {tuple(e) for e in uniq[count == 2]}
    # Euler characteristic of a disk
    assert m.n_x - len(uniq) + len(f) == 1


def test_stitched_sides_share_the_larger_count():
    pat = two_squares()
    pat.panels["B"].vertices[:, 1] *= 1.5  # B's sewn edge now longer than A's
    m = mesh_pattern(pat, edge_length=0.02)
    assert len(m.edge_verts[("A", 1)]) == len(m.edge_verts[("B", 3)]) == int(np.ceil(0.45 / 0.02)) + 1


def test_mini_shirt_seams_meet_in_3d_and_corners_merge():
    pat = mini_shirt()
    m = mesh_pattern(pat, edge_length=0.02)
    # front and back face each other: side seams coincide in x and y, differ only in z
    for s in pat.stitches[:4]:
        ea, eb = m.edge_verts[(s.a.panel, s.a.edge)], m.edge_verts[(s.b.panel, s.b.edge)]
        assert_close(m.uv_placed3d[ea][:, :2], m.uv_placed3d[eb[::-1]][:, :2], atol=1e-12, what=s.label)
    # every group of uv vertices merged into one x vertex is closed under the seam pairs
    groups = {}
    for u, x in enumerate(m.x_of_u):
        groups.setdefault(int(x), []).append(u)
    sizes = np.array([len(g) for g in groups.values()])
    assert sizes.max() >= 2 and m.n_x == len(groups)
    # the waist corner (front vertex 1) is on the side seam only: 2 copies; a sleeve's corner
    # (0,0) is on its underarm seam with (0, 0.2): the tube closes
    ls0 = m.edge_verts[("lsleeve", 0)][0]
    ls3 = m.edge_verts[("lsleeve", 2)][-1]
    assert m.x_of_u[ls0] == m.x_of_u[ls3]


def test_corner_shared_by_two_seams():
    pat = two_squares()
    # Also sew A's top edge (s,s)->(0,s) to B's top edge (s,s)->(0,s): A's (s,s) meets B's (0,s),
    # which the first stitch already sewed to it, so that corner is shared by both seams.
    pat.stitches.append(Stitch(StitchSide("A", 2), StitchSide("B", 2), "top"))
    m = mesh_pattern(pat, edge_length=0.05)
    a_corner = m.edge_verts[("A", 1)][-1]  # (s, s) in A
    b_corner = m.edge_verts[("B", 3)][0]  # (0, s) in B
    b_tr = m.edge_verts[("B", 2)][0]  # (s, s) in B, sewn to A's (0, s)
    a_tl = m.edge_verts[("A", 2)][-1]  # (0, s) in A
    assert m.x_of_u[a_corner] == m.x_of_u[b_corner]
    assert m.x_of_u[b_tr] == m.x_of_u[a_tl] != m.x_of_u[a_corner]
    assert m.n_x == m.n_uv - len(m.edge_verts[("A", 1)]) - len(m.edge_verts[("A", 2)]) + 1


def test_placed3d_follows_garmentcode_euler_convention():
    # GarmentCode's mesh generator places a panel with R = Rz @ Ry @ Rx (scipy's extrinsic "xyz")
    from scipy.spatial.transform import Rotation

    pat = two_squares()
    pat.panels["A"].rotation = np.array([30.0, -50.0, 70.0])
    m = mesh_pattern(pat, edge_length=0.05)
    idx = np.flatnonzero(m.uv_panel == 0)
    R = Rotation.from_euler("xyz", [30.0, -50.0, 70.0], degrees=True).as_matrix()
    expect = np.c_[m.uv[idx], np.zeros(len(idx))] @ R.T + pat.panels["A"].translation
    assert_close(m.uv_placed3d[idx], expect, atol=1e-12)


def test_placed3d_uses_rotation_and_translation():
    pat = mini_shirt()
    m = mesh_pattern(pat, edge_length=0.03)
    p = m.panel_names.index("back")
    idx = np.flatnonzero(m.uv_panel == p)
    expect = np.c_[-m.uv[idx, 0], m.uv[idx, 1], np.zeros(len(idx))] + [0, 1.0, -0.15]  # 180 deg about y
    assert_close(m.uv_placed3d[idx], expect, atol=1e-12)


def test_bad_inputs():
    with pytest.raises(InputError):
        mesh_pattern(two_squares(), edge_length=0.001)
    with pytest.raises(InputError):
        mesh_pattern(two_squares(), edge_length=0.5)
    pat = two_squares()
    pat.stitches.append(Stitch(StitchSide("A", 0), StitchSide("C", 0)))
    with pytest.raises(PatternError, match="'C'"):
        mesh_pattern(pat)


def test_write_rest_obj(tmp_path):
    m = mesh_pattern(two_squares(), edge_length=0.05)
    path = tmp_path / "rest.obj"
    write_rest_obj(m, path)
    v, vt, f = [], [], []
    for line in path.read_text().splitlines():
        t = line.split()
        if not t or t[0].startswith("#"):
            continue
        if t[0] == "v":
            v.append([float(x) for x in t[1:4]])
        elif t[0] == "vt":
            vt.append([float(x) for x in t[1:3]])
        elif t[0] == "f":
            f.append([[int(i) for i in c.split("/")[:2]] for c in t[1:4]])
    f = np.array(f) - 1
    assert_close(np.array(v)[f[:, :, 0]], m.uv_placed3d[m.faces_uv], atol=1e-8)
    assert_close(np.array(vt)[f[:, :, 1]], m.uv[m.faces_uv], atol=1e-8)
    assert [p.name for p in tmp_path.iterdir()] == ["rest.obj"]


@pytest.mark.parametrize("garment", ["tshirt", "dress", "pants", "shorts", "skirt"])
def test_base_patterns_mesh_cleanly(garment):
    from unsew.pattern.base import make_base_pattern

    pat = make_base_pattern(garment)
    m = mesh_pattern(pat, edge_length=0.03)
    q = m.quality()
    assert q["min_angle_deg"] >= 20.0 and q["bad_triangles"] == 0
    # every stitch sews vertex to vertex, and sewn vertices are merged
    for s in pat.stitches:
        ea, eb = m.edge_verts[(s.a.panel, s.a.edge)], m.edge_verts[(s.b.panel, s.b.edge)]
        assert len(ea) == len(eb)
        assert np.array_equal(m.x_of_u[ea], m.x_of_u[eb[::-1]])
    # the sewn mesh is an edge-manifold surface (every edge in one or two triangles)
    f = m.faces
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, count = np.unique(edges, axis=0, return_counts=True)
    assert count.max() <= 2
    assert (np.diff(f[:, [0, 1, 2, 0]], axis=1) != 0).all()  # no triangle collapsed by sewing
