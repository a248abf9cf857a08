"""benchmarks/bench_sim.py in its small mode: a 300-vertex sheet draped forward and backward, its
system assembled and factorised."""

from pathlib import Path

from benchmarks_loader import load_benchmark


def test_small_mode_drapes_and_factorises(capsys):
    load_benchmark("bench_sim").main(
        ["--sizes", "300", "--repeat", "1", "--no-loop", "--sheet", "--variants", "ring:cholespy"]
    )
    out = capsys.readouterr().out.splitlines()
    drape = [ln for ln in out if "ring:cholespy |" in ln]
    assert len(drape) == 1
    times = [float(x) for x in drape[0].split("|")[1].split()]
    assert len(times) == 5 and all(t > 0 for t in times)
    solves = [
        ln for ln in out if ln.strip().startswith("sheet") and "ring:cholespy" in ln and "asm" not in ln
    ]
    assert any("x |" in ln for ln in solves)  # the assembly and solver table has its row


def test_dress_mode_drapes_a_true_pattern_alike_in_both_factorizations(capsys):
    """`--dress`: a tank top's true pattern dressed with CHOLMOD's simplicial and supernodal
    factorizations: both drape it, with as many factorizations, to the same place."""
    import pytest

    pytest.importorskip("sksparse.cholmod")
    case = Path(__file__).parents[2] / "benchmarks/foreign/cases/tank_top__gc_mean_female"
    load_benchmark("bench_sim").main(["--dress", str(case)])
    row = [
        ln for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("tank_top__gc_mean_female")
    ]
    assert len(row) == 1
    cells = row[0].split("|")
    (t_super, n_super), (t_simpl, n_simpl) = (c.split() for c in cells[1:3])
    assert float(t_super) > 0 and float(t_simpl) > 0 and int(n_super) == int(n_simpl) > 0
    median_mm, max_mm = (float(x) for x in cells[3].split())
    assert median_mm < 0.01 and max_mm < 1.0
