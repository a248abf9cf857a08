"""Damaged garment meshes: cleaned back to the clean mesh, or refused with one line."""

import numpy as np
import pytest
from geometry_meshes import grid_tube

from unsew.errors import InputError
from unsew.geometry.repair import repair_garment


def _damaged(v, f, rng):
    """50 duplicate faces (some flipped), a 3-face fin on an interior edge, a degenerate face, a
    duplicate vertex and an unreferenced one."""
    dup = f[rng.choice(len(f), 50, replace=False)]
    dup[::2] = dup[::2, ::-1]
    # fin: a strip of 3 triangles standing on the interior edge (a, b) of face 0, sticking out
    a, b = f[0, 0], f[0, 2]
    mid = 0.5 * (v[a] + v[b])
    out = mid * np.array([1.0, 0, 1.0])
    out = 0.05 * out / np.linalg.norm(out)
    n = len(v)
    fin_v = np.array([v[a] + out, v[b] + out, mid + 2 * out])
    fin_f = np.array([[a, b, n + 1], [a, n + 1, n], [n, n + 1, n + 2]])
    copy_of_vertex = v[f[5, 1]][None]  # a duplicate of vertex f[5, 1], used by the degenerate face
    # repeated corner; collapses on merge
    deg_f = np.array([[f[3, 0], f[3, 1], f[3, 1]], [n + 3, f[5, 1], f[5, 2]]])
    lone = np.array([[9.0, 9.0, 9.0]])
    v2 = np.concatenate([v, fin_v, copy_of_vertex, lone])
    f2 = np.concatenate([f[:40], dup, f[40:], fin_f, deg_f])
    return v2, f2


def test_damaged_target_cleans_to_the_clean_mesh():
    v, f = grid_tube(24, 12)
    v2, f2, rep = repair_garment(*_damaged(v, f, np.random.default_rng(0)))
    assert v2.shape == v.shape and (v2 == v).all()
    # the same triangles; a duplicate placed before its original (some flipped) is the one kept
    canon = lambda x: np.unique(np.sort(x, axis=1), axis=0)  # noqa: E731
    assert (canon(f2) == canon(f)).all()
    assert rep.duplicate_faces == 50
    assert rep.degenerate_faces == 2
    assert rep.fin_faces == 3
    assert rep.merged_vertices == 1 and rep.unreferenced_vertices == 1
    assert rep.components == 1
    s = rep.summary()
    assert "50 duplicate faces" in s and "fin" in s and " m" in s and "\n" not in s


def test_damage_after_the_faces_keeps_their_order():
    v, f = grid_tube(24, 12)
    vd, fd = _damaged(v, f, np.random.default_rng(1))
    tail = np.concatenate([fd[: len(f)][:40], fd[90 : 90 + len(f) - 40]])  # the original faces, in order
    assert (tail == f).all()
    v2, f2, _ = repair_garment(vd, np.concatenate([tail, fd[40:90], fd[90 + len(f) - 40 :]]))
    assert (v2 == v).all() and (f2 == f).all()


def test_clean_mesh_is_unchanged():
    v, f = grid_tube()
    v2, f2, rep = repair_garment(v, f)
    assert (v2 == v).all() and (f2 == f).all()
    assert not rep.changed and rep.summary() == "clean"
    assert rep.as_dict()["duplicate_faces"] == 0


def test_branching_surface_refused():
    v, f = grid_tube(12, 6)
    # a large flap (a whole second tube half) on one interior edge: not a small fin
    flap_v, flap_f = grid_tube(12, 6, radius=0.4)
    a, b = f[0, 0], f[0, 2]
    flap_f = flap_f + len(v)
    flap_v = flap_v.copy()
    flap_v[flap_f[0, 0] - len(v)] = v[a]
    flap_v[flap_f[0, 2] - len(v)] = v[b]
    with pytest.raises(InputError, match=r"non-manifold edges .* at \("):
        repair_garment(np.concatenate([v, flap_v]), np.concatenate([f, flap_f]))


def test_two_garments_refused_and_split_panels_kept():
    v, f = grid_tube()
    far_v = v + [0, 1.0, 0]
    with pytest.raises(InputError, match="separate surfaces"):
        repair_garment(np.concatenate([v, far_v]), np.concatenate([f, f + len(v)]))
    # two halves of a garment with a 5 mm gap at the seam: kept as they are
    near_v = v + [0, 0.505, 0]
    _, f2, rep = repair_garment(np.concatenate([v, near_v]), np.concatenate([f, f + len(v)]))
    assert rep.components == 2 and len(f2) == 2 * len(f)


def _split_open(v, f, gap, slope=0.0):
    """The tube cut into a front (z > slope y) and a back piece along its two side seams (faces
    by their centroid: a slanted cut's seams are stepped), each seam vertex doubled and the
    back's copy moved ``gap`` [m] back: panels exported unwelded."""
    front = (v[f].mean(1) @ [0.0, -slope, 1.0]) > 0
    seam = np.intersect1d(f[front].ravel(), f[~front].ravel())
    copy = {int(i): len(v) + k for k, i in enumerate(seam)}
    back = np.vectorize(lambda i: copy.get(int(i), int(i)))(f[~front])
    v2 = np.concatenate([v, v[seam] + [0.0, 0.0, -gap]])
    return v2, np.concatenate([f[front], back]), len(seam)


def test_open_seams_welded_to_one_surface():
    """Panels exported with their seams unwelded (0.5 mm apart) are one surface again: the tube's
    two rims are its only openings, not the seams; pieces 5 mm apart stay apart."""
    from unsew.geometry import topology

    v, f = grid_tube()
    v2, f2, n_seam = _split_open(v, f, 0.0005)
    assert len(topology.boundary_loops(f2)) == 2  # each piece one outline: its seams run into the rims
    v3, f3, rep = repair_garment(v2, f2)
    assert rep.components == 1 and rep.welded_vertices == n_seam
    assert any("welded" in note for note in rep.notes)
    loops = topology.boundary_loops(f3)
    assert sorted(len(loop) for loop in loops) == [12, 12]  # the rims, as on the welded tube
    assert np.allclose(np.sort(v3, axis=0), np.sort(v, axis=0), atol=0.001)
    _, f4, rep = repair_garment(*_split_open(v, f, 0.005)[:2])
    assert rep.welded_vertices == 0 and rep.components == 2 and len(f4) == len(f)


def test_open_seams_sampled_otherwise_are_sewn_edge_to_edge():
    """A back piece meshed twice as finely as the front (its seams carry a vertex between each
    two of the front's): the extra vertices are sewn into the front's edges, no slit is left."""
    _sewn_edge_to_edge(*grid_tube())
    # stepped seams of 3-6 mm edges (the back's halved): a vertex is within the weld's reach of
    # edges next to its own, and is sewn into its nearest only
    _sewn_edge_to_edge(*grid_tube(nu=200, nv=170), slope=0.3)


def _sewn_edge_to_edge(v, f, slope=0.0):
    import trimesh

    from unsew.geometry import topology

    v2, f2, _ = _split_open(v, f, 0.0005, slope)
    front = (v2[f2].mean(1) @ [0.0, -slope, 1.0]) > 0
    back = trimesh.Trimesh(v2, f2[~front], process=False).subdivide()
    front_mesh = trimesh.Trimesh(v2, f2[front], process=False)
    both = trimesh.util.concatenate([front_mesh, back])
    v3, f3, rep = repair_garment(np.asarray(both.vertices), np.asarray(both.faces))
    assert rep.components == 1
    loops = topology.boundary_loops(f3)
    assert len(loops) == 2  # the rims alone
    _, _, cnt = topology.unique_edges(f3)
    assert cnt.max() == 2


def test_loose_debris_removed():
    v, f = grid_tube(24, 12)
    bit = np.array([[0.0, 2.0, 0.0], [0.01, 2.0, 0.0], [0.0, 2.01, 0.0]])
    v2, f2, rep = repair_garment(
        np.concatenate([v, bit]), np.concatenate([f, [[len(v), len(v) + 1, len(v) + 2]]])
    )
    assert rep.debris_faces == 1 and (f2 == f).all() and (v2 == v).all()


def test_nothing_left_refused():
    v = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0.0]])
    with pytest.raises(InputError, match="no triangles"):
        repair_garment(v, np.array([[0, 1, 2], [0, 0, 1]]))
    with pytest.raises(InputError, match="missing vertices"):
        repair_garment(v, np.array([[0, 1, 3]]))
    with pytest.raises(InputError, match="finite"):
        repair_garment(v * np.nan, np.array([[0, 1, 2]]))


def test_damaged_case_loads_the_clean_target(tmp_path):
    """A case whose target has 50 duplicate faces, a 3-face fin and a degenerate face loads the
    same target arrays as the clean case, so a fit's inputs (and its pattern) are the clean ones;
    what was cleaned is kept for metrics.json."""
    import json

    from unsew.body.case import load_case
    from unsew.io.mesh import write_obj

    v, f = grid_tube(32, 10, radius=0.2, height=0.4, y0=0.9)
    v = v + [0, 0, 0.05]
    cases = {}
    for name, (vv, ff) in {"clean": (v, f), "damaged": _damaged(v, f, np.random.default_rng(2))}.items():
        d = tmp_path / name
        d.mkdir()
        write_obj(d / "target.obj", vv, ff)
        (d / "meta.json").write_text(json.dumps({"garment": "tshirt", "body": "default"}))
        if name == "damaged":
            with pytest.warns(UserWarning, match="repaired"):
                cases[name] = load_case(d)
        else:
            cases[name] = load_case(d)
    c, b = cases["clean"], cases["damaged"]
    assert (b.target_verts == c.target_verts).all()
    canon = lambda x: np.unique(np.sort(x, axis=1), axis=0)  # noqa: E731
    assert (canon(b.target_faces) == canon(c.target_faces)).all()
    assert b.target_repair["duplicate_faces"] == 50 and b.target_repair["fin_faces"] == 3
    assert c.target_repair["notes"] == []
