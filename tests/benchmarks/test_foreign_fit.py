"""benchmarks/bench_foreign_fit.py without fitting: a failed fit is recorded as its last stderr line
and not rerun, and a result folder's metrics.json becomes the row's Chamfer, area and redress cells
(fast: a fake fit command and a hand-written metrics.json on a real case)."""

import json
import shutil
from pathlib import Path

from benchmarks_loader import load_benchmark


def _module():
    return load_benchmark("bench_foreign_fit")


def test_failed_fit_is_recorded_and_not_rerun(tmp_path):
    mod = _module()
    case = mod.case_dirs()[0]
    fake = tmp_path / "fake_python"
    calls = tmp_path / "calls"
    fake.write_text(
        f"#!/bin/sh\necho x >> {calls}\necho 'progress line'\necho 'error: the garment fell' >&2\nexit 3\n"
    )
    fake.chmod(0o755)
    out = tmp_path / "out"
    st = mod.run_case(case, out, python=str(fake))
    assert st["rc"] == 3 and st["exit"] == "error: the garment fell"
    assert not (out / case.name).exists()
    again = mod.run_case(case, out, python=str(fake))  # resumable: the failure is not rerun
    assert again["exit"] == st["exit"] and calls.read_text().count("x") == 1
    r = mod.row(case, out, again)
    assert r["exit"] == "error: the garment fell" and r.get("cf_final_mm") is None


def test_row_reads_metrics_and_pattern_files(tmp_path):
    """metrics.json's area-weighted, total and matched errors become the row's cells; a pattern
    metrics.json lacks (an older result) is computed from the saved pattern file; unmatched panels
    are named."""
    mod = _module()
    case = mod.case_dirs()[0]
    res = tmp_path / case.name
    res.mkdir()
    shutil.copy(case / "pattern_gt.json", res / "pattern_base.json")  # the true pattern as the "base"
    final = {
        "area_error_rel_mean": 0.3,
        "area_error_weighted_rel": 0.4,
        "area_error_total_rel": 0.1,
        "panels": {"a": {}, "b": {}},
        "unmatched": {"estimated": [], "true": ["belt_f", "belt_b"]},
    }
    metrics = {
        "surface": {"chamfer_mm": 7.0},
        "surface_base": {"chamfer_mm": 30.0},
        "surface_graded": {"chamfer_mm": 9.0},
        "surface_warm": {"chamfer_mm": 6.5},
        "pattern": final,
        "pattern_base": {"error": "panels without a counterpart"},
        "redress": {"fit_redressed_mm": 8.0, "graded_mm": 9.0, "phase_two_kept": True},
        "drape_check": {"stretch_max": 1.62},
        "loss_history": {"total": [1.0, 0.9], "stretch": [0.0, 0.25]},
        "timings_s": {"total_s": 12.0},
        "peak_memory_mb": 2048.5,
        "peak_memory_stages_mb": {
            "loaded": 600.0,
            "body_sdf_s": 700.0,
            "grading_s": 2048.5,
            "optimization_s": 2048.5,
        },
    }
    (res / "metrics.json").write_text(json.dumps(metrics))
    r = mod.row(case, tmp_path, {"exit": "ok", "time_s": None})
    assert (r["cf_base_mm"], r["cf_graded_mm"], r["cf_final_mm"], r["cf_warm_mm"]) == (30.0, 9.0, 7.0, 6.5)
    assert abs(r["area_final_pct"] - 40.0) < 1e-9 and abs(r["total_final_pct"] - 10.0) < 1e-9
    assert abs(r["matched_final_pct"] - 30.0) < 1e-9
    assert r["panels"] == "2/4" and r["unmatched"] == "gt: belt_f,belt_b"
    assert abs(r["area_base_pct"]) < 1e-9 and abs(r["total_base_pct"]) < 1e-9  # from pattern_base.json
    assert r.get("area_graded_pct") is None  # neither in metrics.json nor saved
    assert r["phase2_kept"] == "yes" and r["time_s"] == 12.0 and r["peak_mb"] == 2048.5
    assert r["peak_stage"] == "grading"  # the first stage whose end reached the final peak
    assert r["seam_final_mm"] is None  # no pattern.json saved
    assert r["loss_spikes"] == "0 (0)" and r["stretch_max"] == 1.62 and r["barrier"] == 0.25
    assert mod._loss_spikes({"total": [1.0, 0.9, 9.0, 0.8, 3.9], "material": [0, 0, 8.5, 0, 0]}) == "1 (1)"
    assert mod._loss_spikes({"total": [1.0, 6.0], "material": [0.0, 0.0]}) == "1 (0)"
    shutil.copy(case / "pattern_gt.json", res / "pattern.json")
    assert mod.row(case, tmp_path, {"exit": "ok", "time_s": None})["seam_final_mm"] == 0.0  # the base's seams


def test_peak_stage_is_metrics_when_no_stage_reached_the_peak():
    mod = _module()
    m = {"peak_memory_mb": 900.0, "peak_memory_stages_mb": {"loaded": 500.0, "optimization_s": 800.0}}
    assert mod.peak_stage(m) == "metrics"
    assert mod.peak_stage({"peak_memory_mb": 900.0}) is None


def test_config_is_handed_to_every_fit(tmp_path):
    """foreign_fit hands --config on to every fit."""
    ff = _module()
    case = ff.case_dirs()[0]
    fake = tmp_path / "fake_python"
    fake.write_text(f'#!/bin/sh\necho "$@" > {tmp_path / "args"}\nexit 1\n')
    fake.chmod(0o755)
    ff.run_case(case, tmp_path / "out", python=str(fake), config=str(tmp_path / "fit.yaml"))
    assert f"--config {tmp_path / 'fit.yaml'}" in (tmp_path / "args").read_text()


def test_record_keeps_each_case_latest_fit_and_latest_prints_it(tmp_path, capsys):
    """--record writes fitted rows with the commit they ran on, replacing a case's older record and
    skipping cases without a result; --latest prints them with the bars over them."""
    mod = _module()
    cases = mod.case_dirs()[:2]
    path = tmp_path / "fits.json"
    rows = [
        {"case": cases[0].name, "cf_final_mm": 7.0, "cf_base_mm": 9.0, "exit": "ok", "time_s": 100.0},
        {"case": cases[1].name, "exit": "fell", "time_s": 5.0},
    ]
    assert mod.record(rows, path, code="aaa1111", out=tmp_path / "a") == 1
    rows[0] = {**rows[0], "cf_final_mm": 6.0}
    assert mod.record(rows, path, code="bbb2222", out=tmp_path / "b") == 1
    rec = json.loads(path.read_text())
    assert list(rec) == [cases[0].name]
    assert rec[cases[0].name]["code"] == "bbb2222" and rec[cases[0].name]["cf_final_mm"] == 6.0
    assert mod.main(["--latest", str(path)]) == 0
    out = capsys.readouterr().out
    assert "bbb2222" in out and f"1 of {len(mod.case_dirs())} cases recorded" in out
    assert "Chamfer of the fit: median / worst [mm] | 6.0 / 6.0" in out
    assert mod.main(["--latest", str(tmp_path / "none.json")]) == 2


def test_a_record_that_is_not_one_is_refused_in_one_line(tmp_path, capsys):
    mod = _module()
    bad = tmp_path / "fits.json"
    bad.write_text("[1, 2")
    assert mod.main(["--latest", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("foreign_fit: ") and "is not a fit record" in err and err.count("\n") == 1


def test_against_prints_each_fit_beside_its_record(tmp_path, capsys):
    """--against: every fitted row beside the same case's recorded row ("recorded -> now": its base,
    named once when unchanged, graded and final Chamfer), its bar from the floor, and the median
    changes; rows without a fit or without a record are left out."""
    mod = _module()
    rec = {
        "a": {
            "case": "a",
            "code": "aaa1111",
            "base": "pants",
            "cf_graded_mm": 7.0,
            "cf_final_mm": 5.0,
            "area_final_pct": 4.0,
            "phase2_kept": "yes",
        },
        "b": {
            "case": "b",
            "code": "aaa1111",
            "cf_final_mm": 8.0,
            "area_final_pct": 2.0,
            "phase2_kept": "yes",
        },
        "d": {"case": "d", "code": "aaa1111", "base": "skirt", "cf_final_mm": 8.0},
    }
    rows = [
        {
            "case": "a",
            "base": "pants_band",
            "cf_graded_mm": 6.5,
            "cf_final_mm": 6.0,
            "area_final_pct": 1.0,
            "floor_mm": 4.0,
            "phase2_kept": "no",
        },
        {"case": "b", "exit": "fell"},
        {"case": "c", "cf_final_mm": 3.0, "area_final_pct": 1.0},
        {"case": "d", "base": "skirt", "cf_final_mm": 8.0},
    ]
    mod.print_against(rows, rec, tmp_path / "fits.json")
    out = capsys.readouterr().out
    assert (
        "| a | aaa1111 | pants -> pants_band | 7.0 -> 6.5 | 5.0 -> 6.0 | 6.0 | 4.0 -> 1.0 |" in out
        and "yes -> no" in out
    )
    assert "| d | aaa1111 | skirt | - -> - | 8.0 -> 8.0 |" in out
    assert "| b |" not in out and "| c |" not in out
    assert "Chamfer: median change +0.50 mm over 2; lower on 0, higher on 1" in out
    assert "per-panel area error: median change -3.00 points over 1; lower on 1, higher on 0" in out


def test_the_material_fitted_floor_makes_its_results_folder(tmp_path, monkeypatch):
    """``foreign floor --material-only --results DIR``: a DIR not there yet is made before the
    first fit (``unsew fit --out`` refuses a missing folder, which failed every case), and a fit
    that fails is recorded as its exit and last line."""
    import argparse

    mod = load_benchmark("foreign/run")
    case = tmp_path / "cases" / "a_case"
    case.mkdir(parents=True)
    (case / "meta.json").write_text("{}")
    seen = []

    def fake_unsew(cmd, timeout):
        out = cmd[cmd.index("--out") + 1]
        seen.append((tmp_path / "new" / "results").is_dir() and out.endswith("a_case"))
        return 3, "error: the garment fell"

    monkeypatch.setattr(mod, "_run_unsew", fake_unsew)
    args = argparse.Namespace(
        dir=str(tmp_path / "cases"),
        cases=None,
        material_only=True,
        results=str(tmp_path / "new" / "results"),
        timeout=5,
    )
    assert mod.cmd_floor(args) == 0
    assert seen == [True]
    rec = json.loads((case / "meta.json").read_text())["floor_fitted"]
    assert rec["error"] == "exit 3: error: the garment fell"


def test_a_material_fitted_floor_whose_fit_missed_is_no_floor(tmp_path, monkeypatch):
    """A material-only fit that exits 0 but ends ``"ok": false`` (far from its target) is
    recorded as missed, its distance kept aside: no table counts it as a floor."""
    import argparse

    mod = load_benchmark("foreign/run")
    case = tmp_path / "cases" / "a_case"
    case.mkdir(parents=True)
    (case / "meta.json").write_text("{}")

    def fake_unsew(cmd, timeout):
        out = Path(cmd[cmd.index("--out") + 1])
        out.mkdir(parents=True, exist_ok=True)
        (out / "garment.obj").write_text("v 0 0 0\n")
        miss = "the fitted garment lies 158.2 mm from its target"
        (out / "metrics.json").write_text(json.dumps({"ok": False, "miss": miss, "material_fitted": False}))
        (out / "material.json").write_text("{}")
        return 0, ""

    monkeypatch.setattr(mod, "_run_unsew", fake_unsew)
    monkeypatch.setattr(mod, "_chamfer_to_target", lambda g, d: {"chamfer_mm": 158.2, "p95_mm": 300.0})
    args = argparse.Namespace(
        dir=str(tmp_path / "cases"), cases=None, material_only=True, results=str(tmp_path / "r"), timeout=5
    )
    assert mod.cmd_floor(args) == 0
    rec = json.loads((case / "meta.json").read_text())["floor_fitted"]
    assert rec["ok"] is False and rec["miss"].startswith("the fitted garment lies 158.2 mm")
    assert "chamfer_mm" not in rec and rec["chamfer_missed_mm"] == 158.2
