"""``python -m benchmarks phase_two_paths --small``: the phase-two proof's case per floating-point
path, in its quick mode: a row per path asked for, with the bars' verdict."""

from benchmarks_loader import load_benchmark, markdown_rows


def test_small_mode_prints_a_row_per_path(capsys):
    load_benchmark("bench_phase_two_paths").main(["--paths", "base", "--small"])
    rows = [r for r in markdown_rows(capsys.readouterr().out) if r.get("path")]
    assert [r["path"] for r in rows] == ["base"]
    assert rows[0]["bars hold"] in ("yes", "no") and len(rows[0]["loss per iteration"].split()) == 2
