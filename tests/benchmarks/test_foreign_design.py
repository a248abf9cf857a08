"""The foreign benchmark's designs take keyword overrides (``python -m benchmarks foreign design
CASE --set KEY=VALUE``): without any, a design drafts what it always drafted; with ``darts=0``,
the darted skirt loses its darts and keeps its hem and band."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.body.measure import measure_body

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def designs():
    spec = importlib.util.spec_from_file_location(
        "_unsew_foreign_designs", ROOT / "benchmarks/foreign/designs.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_overrides_change_only_what_they_name(designs):
    body = default_body()
    m = measure_body(body).as_dict()
    J = dict(zip(body.skeleton.names, body.skeleton.positions))
    _, fn = designs.DESIGNS["skirt_aline_midi"]
    same = designs.skirt(m, J, length=0.72, flare=0.10, darts=2, waistband=True, name="skirt_aline_midi")
    assert fn(m, J) == same
    plain = fn(m, J, darts=0)["pattern"]["panels"]
    darted = same["pattern"]["panels"]
    front = [k for k in darted if "front" in k and "band" not in k][0]
    # the top's one edge: three pieces and four dart legs
    assert len(darted[front]["edges"]) == len(plain[front]["edges"]) + 6
    for key in ("waistband_front", "waistband_back"):
        band = lambda p: np.ptp(np.asarray(p[key]["vertices"])[:, 0])  # noqa: E731
        assert band(plain) == pytest.approx(band(darted), abs=1e-12)


def test_cli_refuses_an_unknown_case_in_one_line():
    r = subprocess.run(
        [sys.executable, "-m", "benchmarks", "foreign", "design", "nope", "--out", "x.json"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2
    assert r.stderr.strip().splitlines()[-1] == (
        "benchmarks foreign: unknown case 'nope'; `python -m benchmarks foreign list --all` names them"
    )


def test_cli_refuses_an_unwritable_out_in_one_line(tmp_path):
    """--out under a file: refused before anything is drafted, one line, exit 2, nothing written."""
    blocker = tmp_path / "f.txt"
    blocker.write_text("")
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "benchmarks",
            "foreign",
            "design",
            "skirt_aline_midi__default",
            "--out",
            str(blocker / "x.json"),
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert lines[-1].startswith("benchmarks foreign: cannot write --out") and "Traceback" not in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.txt"]
