"""benchmarks/bench_memory.py in its small mode: a fit's 3D metrics on 2K-vertex targets, a
result 5 mm outside the target and one 30 cm away."""

from benchmarks_loader import load_benchmark, markdown_rows


def test_small_mode_measures_the_known_distances(capsys):
    load_benchmark("bench_memory").main(["--sizes", "2000", "--samples", "5000", "--result-verts", "1000"])
    rows = markdown_rows(capsys.readouterr().out)
    assert len(rows) == 4  # the target, uneven, 30 cm away, both
    even = [r for r in rows if float(r["max/median area"]) < 2.0]
    assert len(even) == 2  # the others have triangles ~70x the median at their hem
    for r in rows:
        gap = 5.0 if r["away"] == "0 cm" else 305.0  # the result tube's radius is 5 mm (+ 30 cm) larger
        assert gap * 0.9 < float(r["chamfer mm"]) < (gap * 1.1 if r in even else gap * 2.0), r
        assert float(r["metrics s"]) > 0 and float(r["process peak MB"]) > 0
