"""benchmarks/report.py: docs/benchmarks.md is the page the committed records make, and a record
becomes the bars, a row per garment type and a row per case; a bad record is refused in one line."""

import json

from benchmarks_loader import load_benchmark, markdown_rows


def test_committed_page_is_the_one_the_records_make(capsys):
    assert load_benchmark("report").main(["--check"]) == 0, capsys.readouterr().out


def test_a_record_becomes_bars_garments_and_cases(tmp_path):
    mod = load_benchmark("report")
    ff = load_benchmark("bench_foreign_fit")
    cases = ff.case_dirs()[:2]
    rec = {}
    for c, cf in zip(cases, (4.0, 50.0)):
        meta = json.loads((c / "meta.json").read_text())
        rec[c.name] = {
            "case": c.name,
            "garment": meta["garment"],
            "code": f"abc1234 (ran at {c.name})",
            "exit": "ok",
            "cf_base_mm": 60.0,
            "cf_graded_mm": 10.0,
            "cf_final_mm": cf,
            "time_s": 100.0,
            "total_base_pct": 9.0,
            "total_final_pct": 1.0,
        }
    (tmp_path / "fits.json").write_text(json.dumps(rec))
    (tmp_path / "results").mkdir()
    (tmp_path / "results" / "x.json").write_text(
        json.dumps(
            {
                "title": "A table",
                "command": "python -m benchmarks x",
                "commit": "def5678",
                "rows": [{"a": 1.5}],
            }
        )
    )
    out = tmp_path / "b.md"
    assert (
        mod.main(
            [
                "--record",
                str(tmp_path / "fits.json"),
                "--results",
                str(tmp_path / "results"),
                "--out",
                str(out),
            ]
        )
        == 0
    )
    text = out.read_text()
    rows = markdown_rows(text)
    # 50 mm is past any floor here
    assert {"figure": "Chamfer within max(5 mm, 1.5 x floor)", "value": "1 of 2"} in rows
    case_rows = [r for r in rows if r.get("case") in rec]
    assert [r["commit"] for r in case_rows] == ["abc1234", "abc1234"]
    assert "## A table" in text and "def5678" in text and {"a": "1.50"} in rows
    assert f"2 of {len(ff.case_dirs())} cases" in text


def test_bad_inputs_are_refused_in_one_line(tmp_path, capsys):
    mod = load_benchmark("report")
    assert mod.main(["--record", str(tmp_path / "none.json")]) == 2
    (tmp_path / "fits.json").write_text("{}")
    (tmp_path / "r").mkdir()
    (tmp_path / "r" / "bad.json").write_text(json.dumps({"title": "t"}))
    assert (
        mod.main(
            [
                "--record",
                str(tmp_path / "fits.json"),
                "--results",
                str(tmp_path / "r"),
                "--out",
                str(tmp_path / "b.md"),
            ]
        )
        == 2
    )
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith("report: no record") and "not a recorded table" in err[1]
    assert not (tmp_path / "b.md").exists()


def test_a_demo_run_is_recorded_from_its_metrics(tmp_path, capsys):
    mod = load_benchmark("report")
    surf = {
        s: {"chamfer_mm": c, "normal_error_deg": 10.0}
        for s, c in (("", 2.5), ("_base", 8.2), ("_graded", 2.7))
    }
    pats = {
        f"pattern{s}": {"area_error_rel_mean": a, "turning_distance_mean": 0.05}
        for s, a in (("", 0.004), ("_base", 0.135), ("_graded", 0.003))
    }
    (tmp_path / "demo" / "fit").mkdir(parents=True)
    (tmp_path / "demo" / "fit" / "metrics.json").write_text(
        json.dumps({**{f"surface{k}": v for k, v in surf.items()}, **pats})
    )
    fits = tmp_path / "fits.json"
    fits.write_text("{}")
    (tmp_path / "results").mkdir()
    assert (
        mod.main(
            [
                "--demo",
                str(tmp_path / "demo"),
                "--record",
                str(fits),
                "--results",
                str(tmp_path / "results"),
                "--out",
                str(tmp_path / "b.md"),
            ]
        )
        == 2
    )  # no --commit
    assert (
        mod.main(
            [
                "--demo",
                str(tmp_path / "demo"),
                "--commit",
                "abc1234",
                "--record",
                str(fits),
                "--results",
                str(tmp_path / "results"),
                "--out",
                str(tmp_path / "b.md"),
            ]
        )
        == 0
    )
    t = json.loads((tmp_path / "results" / "demo.json").read_text())
    assert t["commit"] == "abc1234"
    assert {"metric": "Chamfer [mm]", "base": 8.2, "graded": 2.7, "final": 2.5} in t["rows"]
    assert {"metric": "panel area error [%]", "base": 13.5, "graded": 0.3, "final": 0.4} in t["rows"]


def test_the_bars_give_the_material_fitted_floor_where_it_was_measured():
    """Two of three cases have a material-fitted floor: its median beside the same cases' plain
    floor, and how many; none measured, no such line."""
    ff = load_benchmark("bench_foreign_fit")
    base = {"exit": "ok", "cf_base_mm": 40.0, "time_s": 100.0}
    rows = [
        {**base, "case": "a", "cf_final_mm": 5.0, "floor_mm": 20.0, "floor_fitted_mm": 10.0},
        {**base, "case": "b", "cf_final_mm": 6.0, "floor_mm": 30.0, "floor_fitted_mm": 14.0},
        {**base, "case": "c", "cf_final_mm": 7.0, "floor_mm": 8.0},
    ]
    figures = {r["figure"].split(":")[0]: r["value"] for r in ff.bars(rows)}
    assert figures["material-fitted floor (the true pattern, its fabric fitted)"] == "12.0 (25.0); 2 of 3"
    for r in rows:
        r.pop("floor_fitted_mm", None)
    assert not any(r["figure"].startswith("material-fitted") for r in ff.bars(rows))
