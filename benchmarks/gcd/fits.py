"""Fits of the GarmentCode benchmark's built cases, each one's outcome kept (a failed fit is a miss).

``python -m benchmarks gcd fit --cases DIR --results RESULTS [--only ...] [--redo]`` runs
``python -m unsew fit CASE --out RESULTS/<case> --no-progress`` on every built case, one at a
time, and writes each fit's exit code, wall time [s] and last stderr line to
``RESULTS/fits.json`` as soon as it ends, so that ``gcd score`` counts a fit that stopped with
an error (and wrote no result folder) as a tried case, not as one never run.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

#: Wall-clock limit of one fit [s]; the benchmark's bar is 10 min on 2 cores, this only stops a hung one.
FIT_TIMEOUT_S = 3600

LOG_NAME = "fits.json"


def read_log(results: Path) -> dict:
    """``{case: {"exit", "seconds", "message"}}`` of the fits run into ``results`` (empty if none)."""
    p = results / LOG_NAME
    return json.loads(p.read_text()) if p.is_file() else {}


def _write_log(results: Path, log: dict) -> None:
    tmp = results / (LOG_NAME + ".tmp")
    tmp.write_text(json.dumps(log, indent=1, sort_keys=True) + "\n")
    tmp.replace(results / LOG_NAME)


def run_fit(case: Path, out: Path, timeout: int = FIT_TIMEOUT_S, *, material_only: bool = False) -> dict:
    """One ``unsew fit`` of ``case`` into ``out``: ``{"exit", "seconds", "message"}`` (message:
    the last stderr line, the one-line reason of a failed fit or a warning of a missed one). With
    ``material_only`` the case's true pattern is held and only its fabric fitted (the
    material-fitted floor: ``--material-only --base CASE/pattern_gt.json``)."""
    cmd = [sys.executable, "-m", "unsew", "fit", str(case), "--out", str(out), "--no-progress"]
    if material_only:
        cmd += ["--material-only", "--base", str(case / "pattern_gt.json")]
    if out.exists():
        cmd.append("--overwrite")
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "PASSIVE"))
    t0 = time.time()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=timeout, env=env)
        code, err = r.returncode, r.stderr
    except subprocess.TimeoutExpired as exc:
        code, err = (
            124,
            f"timed out after {timeout} s\n" + (exc.stderr or b"").decode(errors="replace")[-200:],
        )
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    return {"exit": code, "seconds": round(time.time() - t0, 1), "message": lines[-1][:300] if lines else ""}


def cmd_fit(args, case_ids: list[str]) -> int:
    """Fit every built case of ``args.cases`` (or ``args.only``) into ``args.results``; a case with
    an outcome in fits.json is skipped unless ``args.redo``; ``args.material_only``: the true
    pattern's material only (``gcd floor-fitted`` records those)."""
    cases, results = Path(args.cases), Path(args.results)
    built_p = cases / "build.json"
    if not built_p.is_file():
        print(
            f"gcd fit: no build.json in {cases} (run `python -m benchmarks gcd build` first)", file=sys.stderr
        )
        return 2
    built = json.loads(built_p.read_text())
    todo = [c for c in case_ids if built.get(c, {}).get("status") == "built"]
    if args.only:
        unknown = sorted(set(args.only) - set(case_ids))
        if unknown:
            print(f"gcd fit: unknown case(s) {unknown}", file=sys.stderr)
            return 2
        todo = [c for c in todo if c in args.only]
    results.mkdir(parents=True, exist_ok=True)
    log = read_log(results)
    for cid in todo:
        if cid in log and not args.redo:
            continue
        print(f"{cid}: fitting", flush=True)
        log[cid] = run_fit(cases / cid, results / cid, material_only=getattr(args, "material_only", False))
        _write_log(results, log)
        o = log[cid]
        print(f"{cid}: exit {o['exit']} in {o['seconds']} s {o['message']}", flush=True)
    return 0
