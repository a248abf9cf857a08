"""benchmarks/bench_losses.py in its small mode: every loss and metric timed once at 500 points."""

import re

from benchmarks_loader import load_benchmark


def test_small_mode_times_every_operation(capsys):
    load_benchmark("bench_losses").main(["--sizes", "500", "--repeat", "1", "--threads", "1"])
    out = capsys.readouterr().out
    for op in (
        "nn indices, KD-tree",
        "Chamfer fwd+bwd curvature-weighted",
        "open_contours",
        "surface_metrics",
    ):
        line = next(ln for ln in out.splitlines() if ln.startswith(op))
        ms = float(
            re.findall(r"(\d+\.\d)", line)[-1]
            if "(" not in line.rsplit(None, 1)[-1]
            else re.findall(r"(\d+\.\d)", line)[0]
        )
        assert ms > 0
    assert "turning_distance" in out and "256 x 256" in out
