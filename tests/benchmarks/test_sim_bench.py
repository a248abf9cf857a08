"""benchmarks/bench_sim.py in its small mode: a 300-vertex sheet draped forward and backward, its
system assembled and factorised."""

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
