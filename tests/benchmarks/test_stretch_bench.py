"""benchmarks/bench_stretch.py: a garment's openings and its longest edge, on a flat drape."""

from pathlib import Path

import numpy as np
import pytest
from benchmarks_loader import load_benchmark

from unsew.grading.grade import flat_drape
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import edge_length

ROOT = Path(__file__).resolve().parents[2]


def test_openings_of_a_tee_and_its_longest_edge():
    """The base tee's panels placed by their hints: four openings (neck, hem, two cuffs), the
    hem's rest length that of the pattern's two hem edges; pull the highest vertex up and the
    longest edge is found there."""
    mod = load_benchmark("bench_stretch")
    p = make_base_pattern("tshirt")
    m = mesh_pattern(p, edge_length=0.05)
    x = flat_drape(p, m)
    found = mod.openings(x, m)
    assert sorted(o["name"] for o in found) == ["hem", "left", "neck", "right"]
    for o in found:
        assert o["rest"] > 0.1
    hem = next(o for o in found if o["name"] == "hem")
    hem_edges = sum(edge_length(p.panels[n], i) for n in ("front", "back")
                    for i, e in enumerate(p.panels[n].edges) if e.label == "hem")
    assert hem["rest"] == pytest.approx(hem_edges, rel=1e-9)
    k = int(np.argmax(x[:, 1]))
    x2 = x.copy()
    x2[k, 1] += 0.3
    y, panel = mod.longest_edge(x2, m)
    assert y > x[:, 1].max() and panel in m.panel_names


def test_missing_result_files_exit_with_one_line(tmp_path, capsys):
    mod = load_benchmark("bench_stretch")
    case = ROOT / "benchmarks" / "foreign" / "cases" / "tank_top__default"
    assert mod.main(["--case", str(case), "--results", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "pattern.json is missing" in err[0]
