"""unsew batch orchestration on the local process pool, with a stand-in fit (tests/batch/fakes.py):
outcomes, summary files, broken and crashing cases, resuming, rerun skipping, Ctrl-C."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from batch.fakes import fake_fit, make_fake_case
from unsew.batch import find_cases, result_state, run_batch
from unsew.batch.summary import format_table
from unsew.errors import InputError
from unsew.fit.config import load_config

CFG = load_config(optimizer={"iterations": 3}, output={"report": False})


def _cases(root: Path, n_good: int = 3, **bad) -> Path:
    for i in range(n_good):
        make_fake_case(root / f"case{i}", value=float(i + 1), pattern_gt=(i == 0))
    if bad:
        make_fake_case(root / "broken", **bad)
    (root / "not_a_case").mkdir()  # no meta.json: ignored
    return root


def _csv(path: Path) -> dict:
    with open(path, newline="") as f:
        return {r["case"]: r for r in csv.DictReader(f)}


def test_batch_two_workers_broken_case_and_rerun(tmp_path):
    cases = _cases(tmp_path / "cases", garment="sweater")
    out = tmp_path / "results"
    res = run_batch(cases, out, cfg=CFG, workers=2, fit_fn=fake_fit, progress=False)
    st = {r.name: r.status for r in res.records}
    assert st == {"broken": "failed", "case0": "done", "case1": "done", "case2": "done"}
    broken = next(r for r in res.records if r.name == "broken")
    assert "garment 'sweater'" in broken.reason and "\n" not in broken.reason
    assert "Traceback" in (out / "broken.log").read_text()
    assert not (out / "broken").exists()
    for i in range(3):
        m = json.loads((out / f"case{i}" / "metrics.json").read_text())
        assert m["surface"]["chamfer_mm"] == 10.0 * (i + 1)
    rows = _csv(out / "summary.csv")
    assert list(rows) == ["broken", "case0", "case1", "case2"]
    assert rows["case1"]["status"] == "done" and float(rows["case1"]["chamfer_mm"]) == 20.0
    assert float(rows["case1"]["loss_total"]) == 2.0 / 3.0  # full precision
    assert rows["case0"]["area_error_rel_mean"] == "0.01" and rows["case1"]["area_error_rel_mean"] == ""
    assert rows["case0"]["iterations"] == "3" and rows["broken"]["iterations"] == ""
    assert rows["case0"]["result"] == "case0"
    html = (out / "index.html").read_text()
    assert "<h2>Summary</h2>" in html
    assert all(f"href='case{i}/report.html'" in html for i in range(3)) and "sweater" in html
    table = format_table(res.records)
    assert "3 done, 1 failed of 4 cases" in table and "failed: garment 'sweater'" in table

    # rerun: finished cases are skipped (their metrics come back into the summary), the broken one is retried
    res2 = run_batch(cases, out, cfg=CFG, workers=2, fit_fn=fake_fit, progress=False)
    st2 = {r.name: r.status for r in res2.records}
    assert st2 == {"broken": "failed", "case0": "skipped", "case1": "skipped", "case2": "skipped"}
    assert _csv(out / "summary.csv")["case1"]["chamfer_mm"] == rows["case1"]["chamfer_mm"]
    assert res2.counts == {"failed": 1, "skipped": 3}


def test_worker_death_is_recorded_and_others_finish(tmp_path):
    cases = _cases(tmp_path / "cases", n_good=2, crash=True)
    for i in range(2):  # slow enough to be in flight when "broken" kills its worker, twice
        make_fake_case(cases / f"case{i}", value=float(i + 1), sleep=0.5)
    res = run_batch(cases, tmp_path / "out", cfg=CFG, workers=2, fit_fn=fake_fit, progress=False)
    st = {r.name: (r.status, r.reason) for r in res.records}
    assert st["case0"] == ("done", "") and st["case1"] == ("done", "")
    assert st["broken"][0] == "failed" and "worker process died" in st["broken"][1]


def test_resumes_from_checkpoint(tmp_path):
    cases = _cases(tmp_path / "cases", n_good=2)
    out = tmp_path / "out"
    work = out / "case1.partial"
    work.mkdir(parents=True)
    (work / "checkpoint.pt").write_text("2")
    assert result_state(out / "case1") == "partial"
    res = run_batch(cases, out, cfg=CFG, workers=1, fit_fn=fake_fit, progress=False)
    rec = {r.name: r for r in res.records}
    assert rec["case1"].resumed and not rec["case0"].resumed
    assert json.loads((out / "case1" / "metrics.json").read_text())["resumed_from"] == 2
    assert _csv(out / "summary.csv")["case1"]["resumed"] == "True"


def test_blocked_result_folder_and_bad_inputs(tmp_path):
    cases = _cases(tmp_path / "cases", n_good=1)
    out = tmp_path / "out"
    (out / "case0").mkdir(parents=True)  # exists but not a complete result
    res = run_batch(cases, out, cfg=CFG, workers=1, fit_fn=fake_fit, progress=False)
    assert res.records[0].status == "failed" and "--overwrite" in res.records[0].reason
    res = run_batch(cases, out, cfg=CFG, workers=1, fit_fn=fake_fit, progress=False, overwrite=True)
    assert res.records[0].status == "done"
    with pytest.raises(InputError, match="no case folder"):
        find_cases(tmp_path / "cases" / "not_a_case")
    with pytest.raises(InputError, match="does not exist"):
        run_batch(tmp_path / "nowhere", out, fit_fn=fake_fit, progress=False)
    with pytest.raises(InputError, match="workers"):
        run_batch(cases, out, workers=0, fit_fn=fake_fit, progress=False)


def test_cli_bad_cases_folder_is_one_line(tmp_path):
    env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE"}
    p = subprocess.run(
        [sys.executable, "-m", "unsew", "batch", str(tmp_path / "nope"), "--out", str(tmp_path / "o")],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert p.returncode == 2 and p.stderr.strip().count("\n") == 0 and "does not exist" in p.stderr


# The driver restores Python's Ctrl-C handler: a process started in the background by a
# non-interactive shell (a CI runner, `cmd &`) inherits SIGINT ignored, and then the interrupt
# below would never reach it (the batch ran to FINISHED in such a run).
_DRIVER = """
import signal
import sys
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path.insert(0, {tests!r})
from batch.fakes import fake_fit
from unsew.batch import run_batch
from unsew.fit.config import load_config
cfg = load_config(optimizer={{"iterations": 40}}, output={{"report": False}})
res = run_batch({cases!r}, {out!r}, cfg=cfg, workers=2, fit_fn=fake_fit, progress=False)
print("INTERRUPTED" if res.interrupted else "FINISHED", flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a process group is POSIX")
def test_ctrl_c_stops_cleanly_and_rerun_continues(tmp_path):
    cases = tmp_path / "cases"
    make_fake_case(cases / "a_quick", value=1.0)
    for n in ("b_slow", "c_slow", "d_slow"):
        make_fake_case(cases / n, value=2.0, sleep=0.2)  # 40 iterations x 0.2 s
    out = tmp_path / "out"
    script = _DRIVER.format(tests=str(Path(__file__).parents[1]), cases=str(cases), out=str(out))
    env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE"}
    proc = subprocess.Popen(
        [sys.executable, "-c", script],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        start_new_session=True,
    )
    deadline = time.monotonic() + 120
    # interrupt while a slow fit is under way (a checkpoint of the quick case may come and go
    # before the signal lands, and then the batch could legitimately finish)
    while time.monotonic() < deadline and not list(out.glob("*_slow.partial/checkpoint.pt")):
        time.sleep(0.1)
    assert list(out.glob("*_slow.partial/checkpoint.pt")), "no slow fit started"
    time.sleep(0.3)
    os.killpg(proc.pid, signal.SIGINT)  # what a terminal's Ctrl-C does: the whole process group
    stdout, stderr = proc.communicate(timeout=60)
    assert "INTERRUPTED" in stdout, stderr
    rows = _csv(out / "summary.csv")
    assert {r["status"] for r in rows.values()} <= {"done", "interrupted", "pending"}
    assert "interrupted" in {r["status"] for r in rows.values()}
    for name, r in rows.items():  # nothing unfinished looks complete
        assert (out / name / "metrics.json").is_file() == (r["status"] == "done")
    time.sleep(0.5)  # the workers are gone: no checkpoint changes any more
    snap = {p: p.read_text() for p in out.glob("*.partial/checkpoint.pt")}
    time.sleep(0.5)
    assert snap == {p: p.read_text() for p in out.glob("*.partial/checkpoint.pt")}

    res = run_batch(
        cases,
        out,
        cfg=load_config(optimizer={"iterations": 40}, output={"report": False}),
        workers=2,
        fit_fn=fake_fit,
        progress=False,
    )
    st = {r.name: r for r in res.records}
    assert all(r.status in ("done", "skipped") for r in res.records)
    assert any(r.resumed for r in res.records if r.status == "done")
    resumed = [n for n, r in st.items() if r.resumed]
    assert all(json.loads((out / n / "metrics.json").read_text())["resumed_from"] > 0 for n in resumed)
