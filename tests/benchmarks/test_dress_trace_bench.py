"""true_patterns --trace's measure of cloth stretched across the body: which edges pass through a
limb (here a cylinder 5 cm in radius), and the stretch of edges against their pattern lengths."""

import numpy as np
from benchmarks_loader import load_benchmark

from unsew.body.sdf import BodySDF

bench = load_benchmark("_dress_trace")


def _limb():
    """A vertical cylinder of radius 0.05 m about the Y axis."""
    return BodySDF.from_function(
        lambda p: np.hypot(p[:, 0], p[:, 2]) - 0.05, [-0.2, -0.2, -0.2], [0.2, 0.2, 0.2], voxel=0.005
    )


def test_an_edge_across_the_limb_passes_through_it():
    x = np.array(
        [
            [-0.08, 0.0, 0.0],  # 0: left of the limb
            [0.08, 0.0, 0.0],  # 1: right of it: 0-1 crosses it
            [-0.08, 0.0, 0.07],  # 2: 0-2 runs beside it
            [-0.06, 0.05, 0.0],  # 3: 0-3 rises towards the limb, 1 cm off it
            [0.0, 0.0, 0.0535],  # 4 and 5: 4-5 lies along the surface, 2-5 mm off it
            [0.03, 0.0, 0.046],
        ]
    )
    edges = np.array([[0, 1], [0, 2], [0, 3], [4, 5]])
    got = bench.through_edges(x, edges, _limb())
    assert got.tolist() == [True, False, False, False]


def test_edge_stretch_against_the_pattern():
    faces = np.array([[0, 1, 2]])
    uv = np.array([[0.0, 0.0], [0.01, 0.0], [0.0, 0.01]])
    x = np.array([[0.0, 0.0, 0.0], [0.03, 0.0, 0.0], [0.0, 0.01, 0.0]])
    r = bench.edge_stretch(x, faces, faces, uv)
    assert np.allclose(sorted(r), sorted([3.0, np.sqrt(0.03**2 + 0.01**2) / np.sqrt(2e-4), 1.0]))
