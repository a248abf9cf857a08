"""benchmarks/bench_batch.py: its cases differ from one another (fast), and the small mode, one
coarse case fitted by one worker, finishes (slow)."""

import pytest
from benchmarks_loader import load_benchmark


def test_cases_are_distinct_known_truths():
    truths = load_benchmark("bench_batch")._truths(4)
    assert len({(t.hem_length, t.hem_girth, t.sleeve_length, t.material) for t in truths}) == 4


@pytest.mark.slow
def test_small_mode_fits_one_case(tmp_path, capsys):
    load_benchmark("bench_batch").main(
        [
            "--cases",
            "1",
            "--workers",
            "1",
            "--iterations",
            "1",
            "--edge-length",
            "0.08",
            "--keep",
            str(tmp_path),
        ]
    )
    out = capsys.readouterr().out
    assert "local, 1 worker: 1/1 done" in out
