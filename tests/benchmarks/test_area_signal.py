"""benchmarks/bench_area_signal.py on a real case: the target's area against its true pattern's,
and a result folder's graded and final patterns and drape (here the true pattern and the target
themselves, so every difference is known)."""

import shutil

from benchmarks_loader import load_benchmark


def test_rows_compare_areas_and_read_a_result_folder(tmp_path):
    mod = load_benchmark("bench_area_signal")
    case = next(p for p in sorted(mod.CASES.iterdir()) if (p / "target.obj").is_file())
    r = mod.row(case, [])
    assert r["true_area_m2"] > 0.1 and abs(r["target_vs_true_pct"]) < 2.0  # newton barely stretches it
    assert "final_pct" not in r
    res = tmp_path / case.name
    res.mkdir()
    for name in ("pattern.json", "pattern_graded.json"):
        shutil.copy(case / "pattern_gt.json", res / name)
    shutil.copy(case / "target.obj", res / "garment.obj")
    r = mod.row(case, [tmp_path / "missing", tmp_path])
    assert abs(r["final_pct"]) < 1e-9 and abs(r["graded_pct"]) < 1e-9
    assert abs(r["drape_vs_pattern_pct"] - r["target_vs_true_pct"]) < 1e-9
    assert mod.main(["--cases", "no_such_case"]) == 1
