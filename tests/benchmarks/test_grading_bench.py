"""benchmarks/bench_grading.py in its small mode: the base skirt graded to a skirt 12 cm longer and
10 % narrower at the hem, both laid flat at their placement (no physics: the geometry alone)."""

from benchmarks_loader import load_benchmark


def test_small_mode_grades_the_base_onto_the_known_change(capsys):
    load_benchmark("bench_grading").main(
        [
            "--drape",
            "flat",
            "--garments",
            "skirt",
            "--samples",
            "2000",
            "--floor-scale",
            "0",
            "--edge-length",
            "0.05",
        ]
    )
    lines = capsys.readouterr().out.splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("garment  target Chamfer"))
    cells = lines[i + 1].split()
    base_mm, graded_mm = float(cells[2]), float(cells[3])
    assert graded_mm < 0.2 * base_mm  # grading recovers the change
    worst = next(ln for ln in lines[i:] if ln.startswith("skirt") and len(ln.split()) == 5).split()
    assert all(float(x) < 1.0 for x in worst[1:])  # every residual under 1 cm, drape and pattern
