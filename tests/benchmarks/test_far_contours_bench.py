"""benchmarks/bench_far_contours.py: the pairs matched beyond grading's centre gate, and those the
rule would match on any part."""

from types import SimpleNamespace

import numpy as np
import pytest
from benchmarks_loader import load_benchmark


def _c(part, y, bone=True):
    return SimpleNamespace(part=part, centre=np.array([0.0, y, 0.0]), bone=object() if bone else None)


def test_far_pairs_are_the_matches_beyond_the_gate():
    mod = load_benchmark("bench_far_contours")
    src, tgt = [_c("torso", 0.5), _c("head", 1.5)], [_c("torso", 1.0), _c("head", 1.52)]
    ms = [SimpleNamespace(source=0, target=0), SimpleNamespace(source=1, target=1)]
    assert mod.far_pairs(src, tgt, ms, 0.45) == [("torso", pytest.approx(0.5))]
    assert mod.far_pairs(src, tgt, ms, 0.6) == []


def test_lone_far_pairs_need_one_contour_of_the_part_on_each_mesh_within_the_factor():
    mod = load_benchmark("bench_far_contours")
    src = [_c("left_arm", 0.9), _c("torso", 0.4)]
    tgt = [_c("left_arm", 1.4), _c("torso", 0.9), _c("torso", 1.3)]  # a skirt's waist and hem
    assert mod.lone_far_pairs(src, tgt, 0.45, 2.0) == [("left_arm", pytest.approx(0.5))]
    assert mod.lone_far_pairs(src, tgt, 0.45, 1.05) == []  # 0.5 m is past 1.05 x the gate
    assert mod.lone_far_pairs([_c("left_arm", 0.9, bone=False)], tgt, 0.45, 2.0) == []  # not on a bone


def test_an_edge_outside_the_meshers_range_is_refused_in_one_line(capsys):
    mod = load_benchmark("bench_far_contours")
    assert mod.main(["--cases", "tank_top__default", "--edge", "-1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--edge -1.0 m is outside" in err[0]
