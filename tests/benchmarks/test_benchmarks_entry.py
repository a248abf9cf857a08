"""`python -m benchmarks`: lists every benchmark with its question, runs one by name, refuses an
unknown name, or bad input to a benchmark, with one line and exit 2."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _run(*args):
    return subprocess.run(
        [sys.executable, "-m", "benchmarks", *args], cwd=ROOT, capture_output=True, text=True
    )


def test_lists_benchmarks_with_their_question():
    r = _run("list")
    assert r.returncode == 0, r.stderr
    lines = {ln.split()[0]: ln for ln in r.stdout.splitlines()[2:] if ln.strip()}
    assert "fit" in lines and "grading" in lines and "run" in lines
    assert "_meshes" not in lines and "tables" not in lines  # helpers, not benchmarks
    assert "Linear grading benchmark" in lines["grading"]


def test_unknown_name_exits_2():
    r = _run("no_such_bench")
    assert r.returncode == 2
    assert "no benchmark named 'no_such_bench'" in r.stderr


def test_bad_input_to_a_benchmark_exits_2_with_one_line(tmp_path):
    r = _run("sdf", "--case", str(tmp_path / "no_case"))
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        f"benchmarks sdf: case folder {tmp_path / 'no_case'} does not exist"
    ]


def test_runs_a_benchmark_by_name_with_its_options():
    r = _run("meshing", "--help")
    assert r.returncode == 0, r.stderr
    assert "usage" in r.stdout.lower()


def test_markdown_table():
    sys.path.insert(0, str(ROOT))
    from benchmarks.tables import markdown_table

    t = markdown_table([{"a": 1.234, "b": None}, {"a": "x", "b": 2}], digits=1)
    assert t.splitlines() == ["| a | b |", "|---|---|", "| 1.2 |  |", "| x | 2 |"]


def test_gcd_reading_modes_refuse_a_missing_folder_in_one_line(tmp_path):
    for args in (
        ["types", "--out", str(tmp_path / "none")],
        ["starts", "--drafts", "--out", str(tmp_path / "none")],
    ):
        r = _run("gcd", *args)
        assert r.returncode == 2
        assert r.stderr.strip().splitlines() == [f"gcd {args[0]}: --out {tmp_path / 'none'} is not a folder"]


def test_gcd_starts_refuses_darts_without_drafts_in_one_line(tmp_path):
    tmp_path.mkdir(exist_ok=True)
    r = _run("gcd", "starts", "--darts", "--out", str(tmp_path))
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == ["gcd starts: --darts judges the drafts; give it with --drafts"]


def test_gcd_settle_refuses_a_missing_folder_and_a_case_without_a_target_in_one_line(tmp_path):
    r = _run("gcd", "settle", "--out", str(tmp_path / "none"), "--to", str(tmp_path / "to"))
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        f"gcd settle: --out {tmp_path / 'none'} is not a folder, or it is --to"
    ]
    (tmp_path / "cases" / "gc_s1_000").mkdir(parents=True)
    r = _run(
        "gcd", "settle", "--out", str(tmp_path / "cases"), "--to", str(tmp_path / "to"), "--only", "gc_s1_000"
    )
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [f"gcd settle: gc_s1_000 has no target in {tmp_path / 'cases'}"]
    assert not list((tmp_path / "to").iterdir())
