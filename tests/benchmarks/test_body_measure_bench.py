"""benchmarks/bench_body_measure.py: GarmentCode's bodies measured with skeletons of several
conventions, against their own measurements."""

import subprocess
import sys
from pathlib import Path

import pytest
from benchmarks_loader import load_benchmark

ROOT = Path(__file__).resolve().parents[2]


def test_quick_table_on_the_reported_body():
    """Small mode (mean_female, the body of the report): four skeletons, none refused, each within
    2.5 cm of the body's .yaml at bust, waist and hips (the SMPL-style one too: its collar joints
    no longer leave the side of the chest to the arms)."""
    mod = load_benchmark("bench_body_measure")
    if not (mod.BODIES / "mean_female.obj").is_file():
        pytest.skip(f"GarmentCode bodies not at {mod.BODIES}")
    text, worst = mod.run(mod.BODIES, ["mean_female"])
    rows = [ln for ln in text.splitlines()[2:] if ln.startswith("| mean_female |")]
    assert [r.split("|")[2].strip() for r in rows] == list(mod.VARIANTS)
    assert "refused" not in text
    assert worst["acceptance"] <= 2.5 and worst["all"] <= 2.5, worst


def test_table_marks_a_refused_skeleton_and_its_error():
    mod = load_benchmark("bench_body_measure")
    from unsew.pattern.measurements import Measurements

    ref = {"bust": 100.0, "waist": 80.0, "hips": 100.0}
    rows = [
        {
            "body": "b",
            "variant": "rig",
            "measured": Measurements(bust=1.01, waist=0.78, hip=1.0),
            "reference": ref,
        },
        {"body": "b", "variant": "smpl", "measured": "waist 5.7 cm is under 40 cm", "reference": ref},
    ]
    text, worst = mod.table(rows)
    assert "| b | rig | 101.0 / 100.0 | 78.0 / 80.0 | 100.0 / 100.0 | 2.0 |" in text
    assert "refused: waist 5.7 cm" in text
    assert worst["acceptance"] == pytest.approx(2.0) and worst["all"] == float("inf")


def test_recorded_rows_group_the_skeletons_that_read_the_same():
    mod = load_benchmark("bench_body_measure")
    from unsew.pattern.measurements import Measurements

    ref = {"bust": 100.0, "waist": 80.0, "hips": 100.0}
    same = Measurements(bust=1.01, waist=0.80, hip=1.0)
    rows = [{"body": "b", "variant": v, "measured": same, "reference": ref} for v in ("none", "rig", "limb")]
    rows.append(
        {
            "body": "b",
            "variant": "smpl",
            "measured": Measurements(bust=0.97, waist=0.8, hip=1.0),
            "reference": ref,
        }
    )
    rows.append({"body": "c", "variant": "rig", "measured": "waist 5.7 cm is under 40 cm", "reference": ref})
    out = mod.record_rows(rows)
    assert [(r["body"], r["skeleton"], r["max error"]) for r in out] == [
        ("b", "none, rig, limb", 1.0),
        ("b", "SMPL-style", 3.0),
        ("c", "rig", None),
    ]
    assert out[0]["bust"] == "101.0 / 100.0" and out[2]["bust"].startswith("refused: waist 5.7")


def test_bad_folder_exits_2_with_one_line(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "benchmarks", "body_measure", "--bodies", str(tmp_path / "none")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "is not a folder" in r.stderr
