"""benchmarks/bench_sdf.py in its small mode: a coarse grid of the default body, its accuracy
against exact distances and its query times."""

from benchmarks_loader import load_benchmark


def test_small_mode_builds_and_queries_a_coarse_grid(capsys):
    load_benchmark("bench_sdf").main(
        ["--voxel", "0.02", "--points", "256", "--accuracy-points", "200", "--threads", "1"]
    )
    out = capsys.readouterr().out
    grid = next(
        ln for ln in out.splitlines() if ln.startswith("| ") and "x" in ln.split("|")[1] and "20.0" in ln
    )
    rms_mm, max_mm = (float(c) for c in grid.strip("| \n").split("|")[-2:])
    assert 0 <= rms_mm <= max_mm < 20.0  # a 2 cm grid: errors within a voxel near the surface
    assert sum(ln.startswith("| float") for ln in out.splitlines()) == 3
