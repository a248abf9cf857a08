"""Cloth lengths between open contours (unsew.grading.cloth)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from unsew.grading.alter import alter_pattern, alteration_groups, open_edges
from unsew.grading.cloth import cloth_distance, cloth_lengths, distance_graph, rest_cloth_lengths, top_contour
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern


def grid(n=21, size=1.0):
    """A flat (n x n) vertex grid over [0, size]^2 in the z = 0 plane, split along one diagonal."""
    s = np.linspace(0.0, size, n)
    v = np.array([[x, y, 0.0] for y in s for x in s])
    f = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            f += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return v, np.array(f)


def test_surface_distance_on_a_flat_grid_is_close_to_the_straight_line():
    v, f = grid()
    d = cloth_distance(distance_graph(v, f), [0])
    far = np.linalg.norm(v, axis=1)
    # edges alone read up to 8.2 % long here (5.0 % on average); with the opposite-vertex
    # segments, 2.7 % (1.3 %)
    assert np.all(d >= far - 1e-12)
    excess = (d - far)[far > 0.3] / far[far > 0.3]
    assert np.max(excess) < 0.03 and np.mean(excess) < 0.015
    assert d[0] == 0.0


def test_distance_graph_takes_each_pair_once_whatever_the_winding():
    v, f = grid(5)
    flipped = f.copy()
    flipped[::2] = flipped[::2, ::-1]  # inconsistent winding: a scan's faces
    a, b = distance_graph(v, f), distance_graph(v, flipped)
    assert (a != b).nnz == 0
    rows = np.repeat(np.arange(len(v)), np.diff(a.indptr))
    assert np.allclose(a.data, np.linalg.norm(v[a.indices] - v[rows], axis=1))


def tube(heights, radii, n_around=32):
    """Open surface of revolution about +y: ring k at height heights[k] with radius radii[k].
    Returns (verts, faces, contours): the bottom and top rings as stand-ins for PlacedContour."""
    th = np.linspace(0, 2 * np.pi, n_around, endpoint=False)
    v = np.array([[r * np.cos(t), h, r * np.sin(t)] for h, r in zip(heights, radii) for t in th])
    f = []
    for i in range(len(heights) - 1):
        for j in range(n_around):
            a, b = i * n_around + j, i * n_around + (j + 1) % n_around
            f += [[a, b, b + n_around], [a, b + n_around, a + n_around]]
    last = (len(heights) - 1) * n_around

    def ring(k, start):
        idx = np.arange(start, start + n_around)
        return SimpleNamespace(
            index=k, contour=SimpleNamespace(indices=idx), rim=idx, centre=v[idx].mean(axis=0)
        )

    return v, np.array(f), [ring(0, 0), ring(1, last)]


def test_cloth_length_of_a_tube_is_its_length_folded_or_not():
    n, seg = 13, 0.05  # 12 segments of 5 cm of cloth along every meridian
    v, f, rings = tube(np.linspace(0.0, 0.6, n), np.full(n, 0.15))
    top, lengths = cloth_lengths(v, f, rings)
    assert top is rings[1] and top_contour(rings) is rings[1]
    assert lengths == {0: pytest.approx(0.6, rel=0.005)}
    # the same cloth folded like an accordion: rings alternate 4 cm in and out, so the tube is
    # 0.36 m tall, but every meridian is still 12 x 5 cm of cloth
    dr = 0.04
    dy = np.sqrt(seg**2 - dr**2)
    radii = 0.15 - dr * (np.arange(n) % 2)
    v2, f2, rings2 = tube(dy * np.arange(n), radii)
    assert v2[:, 1].max() < 0.4
    _, folded = cloth_lengths(v2, f2, rings2)
    assert folded[0] == pytest.approx(0.6, rel=0.01)


def test_contour_without_a_path_to_the_top_has_no_cloth_length():
    v, f, rings = tube(np.linspace(0.0, 0.6, 5), np.full(5, 0.15))
    v3, f3, r3 = tube(np.linspace(-1.0, -0.8, 3), np.full(3, 0.15))  # a separate piece below
    verts = np.vstack([v, v3])
    faces = np.vstack([f, f3 + len(v)])
    piece = SimpleNamespace(
        index=2,
        contour=SimpleNamespace(indices=r3[0].contour.indices + len(v)),
        rim=r3[0].rim + len(v),
        centre=r3[0].centre,
    )
    _, lengths = cloth_lengths(verts, faces, rings + [piece])
    assert set(lengths) == {0}


def test_rest_cloth_length_follows_a_known_leg_change():
    """Trousers' legs 10 cm shorter: the rest cloth length from the leg openings to the waist
    changes by 10 cm (the opening is moved along the leg)."""
    p = make_base_pattern("pants")
    legs = alteration_groups(p)["legs"]
    waist = open_edges(p, "waist")
    t = alter_pattern(p, legs, length=-0.10)
    before = rest_cloth_lengths(mesh_pattern(p, edge_length=0.04), {"legs": legs}, waist)
    after = rest_cloth_lengths(mesh_pattern(t, edge_length=0.04), {"legs": legs}, waist)
    assert before["legs"] > 0.8  # a trouser leg's length, waist to opening
    assert after["legs"] - before["legs"] == pytest.approx(-0.10, abs=0.005)
