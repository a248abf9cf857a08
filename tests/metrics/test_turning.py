"""Turning-function distance (Arkin et al. 1991)."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.metrics.turning import _exact_var, turning_distance, turning_function

SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]])


def _star(n=7, seed=0):
    rng = np.random.default_rng(seed)
    th = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = rng.uniform(0.5, 1.5, n)
    return np.c_[r * np.cos(th), r * np.sin(th)]


def _similar(p, ang=0.7, scale=3.2, shift=(5.0, -2.0), roll=2):
    R = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
    return np.roll(p @ R.T * scale + shift, roll, axis=0)


def test_published_reference_value():
    moved = np.array([[0, 0], [1, 0], [1, 1], [-1, 1.0]])
    assert_close(turning_distance(SQUARE, moved), 0.6144398026382778, atol=1e-9, rtol=0)
    assert_close(turning_distance(moved, SQUARE), 0.6144398026382778, atol=1e-9, rtol=0)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_zero_under_similarity_and_start_shift(seed):
    p = _star(seed=seed)
    assert turning_distance(p, _similar(p)) < 1e-9
    assert turning_distance(p, np.roll(p, 3, axis=0)) < 1e-9


def test_collinear_vertex_and_orientation_do_not_matter():
    extra = np.array([[0, 0], [0.3, 0], [1, 0], [1, 1], [0, 1.0]])
    assert turning_distance(SQUARE, extra) < 1e-9
    assert turning_distance(SQUARE, SQUARE[::-1]) < 1e-9
    # a repeated closing vertex is dropped
    assert turning_distance(SQUARE, np.vstack([SQUARE, SQUARE[:1]])) < 1e-9


def test_turning_function_of_square():
    b, a = turning_function(SQUARE)
    assert_close(b, [0, 0.25, 0.5, 0.75], atol=1e-15)
    assert_close(a, [0, np.pi / 2, np.pi, 3 * np.pi / 2], atol=1e-15)


@pytest.mark.parametrize("seed", [3, 4])
def test_matches_bruteforce_over_shifts(seed):
    pa, pb = _star(6, seed), _star(9, seed + 10)
    a, al = turning_function(pa)
    b, be = turning_function(pb)
    grid = np.linspace(0, 1, 4001)[:-1]
    brute = np.sqrt(min(_exact_var(a, al, b, be, t) for t in grid))
    d = turning_distance(pa, pb)
    assert d <= brute + 1e-12  # the exact minimum is never above a sampled one
    assert brute - d < 0.02 * brute  # and the grid comes close to it


def test_triangle_vs_square_is_positive_and_symmetric():
    tri = np.array([[0, 0], [1, 0], [0.5, 0.8]])
    d1, d2 = turning_distance(SQUARE, tri), turning_distance(tri, SQUARE)
    assert d1 > 0.1
    assert_close(d1, d2, rtol=1e-9)


def test_bad_polygons_raise():
    with pytest.raises(ValueError):
        turning_distance(SQUARE, np.array([[0, 0], [1, 0], [2, 0.0]]))
    with pytest.raises(ValueError):
        turning_distance(SQUARE, np.array([[0, 0], [1, 0.0]]))
    with pytest.raises(ValueError):
        turning_distance(SQUARE, np.array([[0, 0], [1, np.nan], [0, 1]]))
