"""benchmarks/bench_judge.py on hand-written metrics.json files: the one-mesh verdict is read from
the re-dress figures, the three-mesh one as the fit recorded it, and fits judged on one mesh are
listed apart (fast: no fit)."""

import json

from benchmarks_loader import load_benchmark


def _redress(fit_mm, graded_mm, kept, start_mm):
    pairs = [(a, b) for a, b in zip(fit_mm, graded_mm) if b is not None]  # as unsew.fit.checks pairs them
    failed = any(a is None for a, _ in pairs)
    return {"fit_redressed_mm": fit_mm[0], "graded_mm": start_mm, "phase_two_kept": kept, "refused": "", "meshes": 3,
            "edge_lengths_m": [0.025, 0.024, 0.026], "fit_mm": fit_mm, "graded_fresh_mm": graded_mm,
            "fit_mean_mm": None if failed else sum(a for a, _ in pairs) / len(pairs),
            "graded_mean_mm": sum(b for _, b in pairs) / len(pairs)}


def test_judge_rows_and_summary(tmp_path, capsys):
    mod = load_benchmark("bench_judge")
    cases = {"a": _redress([4.0, 6.0, 6.0], [5.0, 5.0, 5.0], False, 4.5),  # one mesh keeps it, three do not
             "b": _redress([3.0, 3.0, None], [4.0, 4.0, 4.0], False, 4.1)}  # a failed drape: lower on 2 of 2 pairs
    for name, red in cases.items():
        (tmp_path / name).mkdir()
        (tmp_path / name / "metrics.json").write_text(json.dumps({"redress": red}))
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "metrics.json").write_text(json.dumps({"redress": {"fit_redressed_mm": 3.0, "graded_mm": 4.0,
                                                                         "phase_two_kept": True, "refused": ""}}))
    a = mod.row("a", cases["a"])
    assert a["one_mesh"] == "kept (4.0 vs 4.5)" and a["three_mesh"] == "graded" and a["agree"] == "no"
    assert a["lower_on"] == "1/3" and a["fit_mm"] == "4.0 / 6.0 / 6.0"
    b = mod.row("b", cases["b"])
    assert b["lower_on"] == "2/2" and b["fit_mm"] == "3.0 / 3.0 / failed" and b["agree"] == "no"
    assert mod.main([str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "kept on one mesh 2 of 2, on three 0; verdicts differ on 2" in out
    assert "not judged on three meshes: c" in out
