"""benchmarks/_flared_floor.py: its shape measures on known shapes and its input check."""

import math

import numpy as np
from benchmarks_loader import load_benchmark

bench = load_benchmark("_flared_floor")


def _cone(top_r, hem_r, y0=0.5, y1=1.0, n=2000, seed=0):
    rng = np.random.default_rng(seed)
    t, a = rng.uniform(0, 1, n), rng.uniform(0, 2 * math.pi, n)
    r = hem_r + (top_r - hem_r) * t
    return np.c_[0.1 + r * np.cos(a), y0 + (y1 - y0) * t, -0.2 + r * np.sin(a)]


def test_shape_reads_a_cones_heights_and_hem_radius():
    s = bench.shape(_cone(0.12, 0.3), np.array([0.1, -0.2]))
    assert abs(s["top"] - 1.0) < 2e-3 and abs(s["bottom"] - 0.5) < 2e-3
    assert abs(s["hem_r"] - 0.3) < 0.01  # vertices within 3 cm of the bottom: r 0.290-0.300


def test_band_distances_find_where_two_drapes_part():
    target = _cone(0.12, 0.3)
    narrower = target.copy()
    low = narrower[:, 1] < 0.6  # the lowest 10 cm hang 5 cm further in
    narrower[low, 0] -= 0.05 * np.sign(narrower[low, 0] - 0.1)
    d = bench.band_distances(narrower, target)
    assert len(d) == 5
    assert d[0] > 20 and max(d[1:]) < 10


def test_unknown_case_exits_2(capsys):
    assert bench.main(["--cases", "no_such_case"]) == 2
    assert "no case 'no_such_case'" in capsys.readouterr().err


def test_a_change_that_names_nothing_exits_2(capsys):
    assert bench.main(["--cases", "skirt_circle_knee__default", "--set", "m.stiffness=3"]) == 2
    assert "neither m.<material field> nor a setting" in capsys.readouterr().err


def test_against_a_folder_without_the_drape_exits_2(tmp_path, capsys):
    assert bench.main(["--cases", "skirt_circle_knee__default", "--against", str(tmp_path)]) == 2
    assert "has no skirt_circle_knee__default.obj" in capsys.readouterr().err
