"""benchmarks/bench_fit.py: a result's metrics become the table's row (fast, no fit), and the
small mode, one coarse fit of a known-truth t-shirt (tests/fit's small settings), beats its base (slow)."""

import json
from types import SimpleNamespace

import pytest
from benchmarks_loader import load_benchmark


def test_row_reads_the_metrics_and_the_redress_choice(capsys):
    mod = load_benchmark("bench_fit")
    mat = SimpleNamespace(h00=1.0, h11=2.0, h22=3.0, bend=4e-6)
    m = {
        "surface": {"chamfer_mm": 2.5, "normal_error_deg": 9.0},
        "surface_base": {"chamfer_mm": 8.0, "normal_error_deg": 20.0},
        "surface_graded": {"chamfer_mm": 3.0},
        "pattern": {"area_error_rel_mean": 0.004, "turning_distance_mean": 0.1},
        "pattern_base": {"area_error_rel_mean": 0.13},
        "redress": {"phase_two_kept": False},
        "peak_memory_mb": 800.0,
    }
    r = mod._row("skirt", SimpleNamespace(material=mat, iterations=7), m, 12.0, 2000)
    assert (r["cf_base_mm"], r["cf_graded_mm"], r["cf_final_mm"]) == (8.0, 3.0, 2.5)
    assert r["area_base_pct"] == pytest.approx(13.0) and r["area_final_pct"] == pytest.approx(0.4)
    assert r["returned"] == "graded" and mod._returned({}) is None
    mod._print([r])
    head, line = capsys.readouterr().out.splitlines()
    assert line.split()[:5] == ["skirt", "2000", "8.00", "3.00", "2.50"]


@pytest.mark.slow
def test_small_mode_fit_beats_its_base(tmp_path):
    load_benchmark("bench_fit").main(
        [
            "--garments",
            "tshirt",
            "--edge-length",
            "0.04",
            "--iterations",
            "3",
            "--out",
            str(tmp_path),
            "--set",
            "drape.steps=8",
            "--set",
            "drape.sew_steps=60",
            "--set",
            "drape.settle_steps=20",
            "--set",
            "material.start=cotton",
            "--set",
            "checks.mesh_spread=0",
            "--set",
            "output.report=false",
        ]
    )
    (row,) = json.loads((tmp_path / "bench_fit.json").read_text())
    assert row["cf_final_mm"] < row["cf_base_mm"] and row["area_final_pct"] < row["area_base_pct"]
