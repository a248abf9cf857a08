"""benchmarks/bench_geometry.py in its small mode: closest points on 5K-triangle tubes by libigl
with its queries in Morton order, each measurement in its own process, checked against libigl's
plain query."""

from benchmarks_loader import load_benchmark, markdown_rows


def test_small_mode_measures_each_mesh_in_a_worker(capsys):
    load_benchmark("bench_geometry").main(
        ["--quick", "--no-inside", "--timeout", "120", "--libs", "igl, Morton order"]
    )
    rows = markdown_rows(capsys.readouterr().out)
    assert [(r["mesh"], r["away"]) for r in rows] == [
        ("tube", "0 cm"),
        ("uneven tube", "0 cm"),
        ("tube", "30 cm"),
        ("uneven tube", "30 cm"),
    ]
    # reordering changes no distance
    assert all(r["status"] == "ok" and float(r["err um"]) < 1.0 for r in rows)
