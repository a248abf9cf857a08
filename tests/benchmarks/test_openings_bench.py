"""benchmarks/bench_openings.py: a target's openings against its true pattern's, by name."""

import numpy as np
import pytest
from benchmarks_loader import load_benchmark



def test_a_tube_target_names_its_openings_by_height_and_side():
    """A tube with a thinner tube at each side: the top loop is "neck", the bottom "hem", the
    side tubes' loops "left"/"right" by x, each with its polygon length."""
    mod = load_benchmark("bench_openings")

    def tube(r, y0, y1, cx, n=24, off=0):
        th = np.linspace(0, 2 * np.pi, n, endpoint=False)
        v = np.array([[cx + r * np.cos(t), y, r * np.sin(t)] for y in (y0, y1) for t in th])
        f = [[a, (a + 1) % n, (a + 1) % n + n] for a in range(n)] + [[a, (a + 1) % n + n, a + n] for a in range(n)]
        return v, np.array(f) + off

    parts = [tube(0.15, 0.8, 1.4, 0.0), tube(0.04, 1.1, 1.2, 0.3), tube(0.04, 1.1, 1.2, -0.3)]
    v = np.vstack([p[0] for p in parts])
    f = np.vstack([p[1] + sum(len(q[0]) for q in parts[:k]) for k, p in enumerate(parts)])
    got = mod.target_openings(v, f)
    assert set(got) == {"neck", "hem", "left", "right"}
    assert got["neck"] == pytest.approx(24 * 2 * 0.15 * np.sin(np.pi / 24))
    assert got["left"] == pytest.approx(24 * 2 * 0.04 * np.sin(np.pi / 24))


def test_a_foreign_case_row(capsys):
    """One committed case end to end: every opening paired, the hem at rest (ratio 1.00)."""
    mod = load_benchmark("bench_openings")
    assert mod.main(["--cases", "tee_fitted_short__default", "--edge", "0.04"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("| tee_fitted_short__default"))
    assert row.count("=") == 4 and row.rstrip(" |").endswith("= 1.00")
    assert mod.main(["--cases", "no_such_case"]) == 2
    assert mod.main(["--edge", "2"]) == 2
