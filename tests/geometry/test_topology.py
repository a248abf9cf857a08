"""Mesh connectivity against hand-counted answers and trimesh."""

import numpy as np
import pytest
import trimesh
from geometry_meshes import grid_tube, square

from unsew.geometry import topology as T


def test_square_edges_boundary_and_adjacency():
    v, f = square()
    edges, inv, cnt = T.unique_edges(f)
    assert edges.tolist() == [[0, 1], [0, 2], [0, 3], [1, 2], [2, 3]]
    assert cnt.tolist() == [1, 2, 1, 1, 1]
    assert (edges[inv] == np.sort(T.half_edges(f), axis=1)).all()
    assert sorted(map(tuple, T.boundary_edges(f).tolist())) == [(0, 1), (1, 2), (2, 3), (3, 0)]
    loops = T.boundary_loops(f)
    assert len(loops) == 1 and len(loops[0]) == 4
    k = int(np.flatnonzero(loops[0] == 0)[0])
    assert np.roll(loops[0], -k).tolist() == [0, 1, 2, 3]  # oriented like the faces
    ie, ef = T.edge_faces(f)
    assert ie.tolist() == [[0, 2]] and ef.tolist() == [[0, 1]]
    adj = T.vertex_adjacency(f, 4).toarray()
    assert (adj == adj.T).all() and adj.sum() == 10 and not adj[1, 3]
    assert T.boundary_vertices(f, 5).tolist() == [True, True, True, True, False]


def test_tube_against_trimesh():
    v, f = grid_tube()
    m = trimesh.Trimesh(v, f, process=False)
    edges, _, cnt = T.unique_edges(f)
    assert set(map(tuple, edges.tolist())) == set(map(tuple, np.sort(m.edges_unique, axis=1).tolist()))
    loops = T.boundary_loops(f)
    assert [len(x) for x in loops] == [12, 12]
    ys = sorted(float(v[x, 1].mean()) for x in loops)
    assert ys == pytest.approx([0.0, 0.5])
    ie, ef = T.edge_faces(f)
    assert len(ie) == int((cnt == 2).sum())
    # each pair of faces shares exactly the edge listed
    for (a, b), (fa, fb) in zip(ie, ef):
        assert {a, b} <= set(f[fa]) and {a, b} <= set(f[fb]) and fa != fb
    assert T.components(f, len(v)) == (1, pytest.approx(np.zeros(len(f))))


def test_closed_mesh_has_no_boundary():
    m = trimesh.creation.icosphere(2)
    assert T.boundary_loops(m.faces) == []
    assert len(T.boundary_edges(m.faces)) == 0
    assert len(T.unique_edges(m.faces)[0]) == len(m.edges_unique)


def test_bowtie_components_and_loops():
    # two triangles touching at vertex 0 only
    f = np.array([[0, 1, 2], [0, 3, 4]])
    n_e, lab_e = T.components(f, 5, by="edge")
    n_v, _ = T.components(f, 5, by="vertex")
    assert (n_e, n_v) == (2, 1) and lab_e[0] != lab_e[1]
    loops = T.boundary_loops(f)
    assert sorted(sorted(x.tolist()) for x in loops) == [[0, 1, 2], [0, 3, 4]]
    with pytest.raises(ValueError):
        T.components(f, 5, by="face")


def test_empty_faces():
    f = np.zeros((0, 3), np.int64)
    assert T.unique_edges(f)[0].shape == (0, 2)
    assert T.boundary_loops(f) == []
    assert T.components(f, 3)[0] == 0
