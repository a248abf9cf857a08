"""Model helpers: Euler placement (GarmentCode convention), curve reversal/mirroring, diff."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import edge_point_fn
from unsew.pattern.model import (
    Curvature,
    euler_xyz_to_matrix,
    matrix_to_euler_xyz,
    mirror_curvature,
    pattern_diff,
    reverse_curvature,
)

CURVES = [
    Curvature("quadratic", [[0.3, 0.4]]),
    Curvature("cubic", [[0.2, -0.3], [0.9, 0.25]]),
    Curvature("circle", [0.7, False, True]),
    Curvature("circle", [0.7, True, False]),
]
A, B = np.array([0.1, 0.2]), np.array([0.8, -0.1])
T = np.linspace(0, 1, 41)


def test_euler_matches_scipy_extrinsic_xyz_and_inverts():
    Rotation = pytest.importorskip("scipy.spatial.transform").Rotation
    rng = np.random.default_rng(0)
    for ang in [*rng.uniform(-180, 180, (5, 3)), np.array([-45.0, 90.0, 0.0])]:
        R = euler_xyz_to_matrix(ang)
        assert_close(R, Rotation.from_euler("xyz", ang, degrees=True).as_matrix(), atol=1e-14)
        assert_close(euler_xyz_to_matrix(matrix_to_euler_xyz(R)), R, atol=1e-12)


@pytest.mark.parametrize("c", CURVES, ids=lambda c: c.kind + str(c.params[-1]))
def test_reverse_is_same_curve_backwards(c):
    fwd = edge_point_fn(A, B, c)(T)
    back = edge_point_fn(B, A, reverse_curvature(c))(T)
    assert_close(back[::-1], fwd, atol=1e-12)


@pytest.mark.parametrize("c", CURVES, ids=lambda c: c.kind + str(c.params[-1]))
def test_mirror_is_mirror_image(c):
    M = np.array([-1.0, 1.0])
    fwd = edge_point_fn(A, B, c)(T) * M
    mir = edge_point_fn(A * M, B * M, mirror_curvature(c))(T)
    assert_close(mir, fwd, atol=1e-12)


def test_pattern_diff_reports_changes():
    p = make_base_pattern("skirt")
    q = p.copy()
    assert pattern_diff(p, q) == []
    q.panels["front"].vertices[0, 0] += 1e-6
    q.panels["back"].edges[0].curvature.params[2] = False
    q.stitches[0].label = "x"
    d = pattern_diff(p, q)
    assert len(d) == 3 and "front" in d[0] and "back" in d[1] and "stitch 0" in d[2]
    assert pattern_diff(p, q, atol=1e-5)[:1] != d[:1]
