"""benchmarks/bench_meshing.py in its small mode: the skirt base meshed at 1, 2 and 3 cm."""

from benchmarks_loader import load_benchmark


def test_small_mode_meshes_finer_with_a_smaller_edge(capsys):
    load_benchmark("bench_meshing").main(["--garments", "skirt", "--repeat", "1", "--no-params"])
    rows = [ln.split() for ln in capsys.readouterr().out.splitlines() if ln.startswith("skirt")]
    assert [r[1] for r in rows] == ["1", "2", "3"]
    tris = [int(r[4]) for r in rows]
    assert tris[0] > 2 * tris[1] > 2 * tris[2] > 0  # about (h1 / h2)^2 more triangles at a smaller edge
    assert all(int(r[6]) == 0 for r in rows)  # no bad triangles


def test_last_bits_mode_meshes_a_moved_specification_as_read_on_the_grid(capsys):
    from pathlib import Path

    spec = Path(__file__).resolve().parents[1] / "data" / "gc_dress_cuffs_specification.json"
    load_benchmark("bench_meshing").main(["--last-bits", str(spec), "--trials", "2"])
    rows = [ln.split() for ln in capsys.readouterr().out.splitlines() if ln.startswith("gc_dress_cuffs")]
    assert [r[1] for r in rows] == ["yes", "no"]
    grid = rows[0]
    assert grid[3:5] == [grid[2], grid[2]] and grid[5:8] == ["2", "of", "2"]  # the same mesh every time
