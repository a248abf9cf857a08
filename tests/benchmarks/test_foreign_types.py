"""``python -m benchmarks foreign types``: the garment type read off a case's target, against its
meta.json's (the case's body is built by anny, an optional extra)."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_types_prints_each_case_and_the_count():
    pytest.importorskip("anny")
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "benchmarks",
            "foreign",
            "types",
            "--cases",
            "tank_top__default",
            "shorts_knee__default",
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert "| tank_top__default | tshirt | tshirt | yes |" in out.stdout
    assert "2 of 2 read right" in out.stdout
