"""How well does the default fit recover garments unsew did not make (issue 21's foreign cases)?

For every case folder in benchmarks/foreign/cases (a GarmentCode-style design draped by newton on an
anny body; see benchmarks/foreign and FORMATS.md), runs the real command-line fit with the default
configuration, ``python -m unsew fit CASE --out OUT/CASE``, one case at a time in a subprocess, and
prints one row per case:

- garment, body (meta.json's source.body_key), exit (``ok`` or the fit's last stderr line), wall
  time of the command [s];
- Chamfer [mm] of the base drape, the graded drape and the final result against the target
  (metrics.json: surface_base, surface_graded, surface);
- panel area error [%] of the base, graded and final pattern against pattern_gt.json, as metrics.json
  computes it (unsew.metrics.panels.pattern_metrics): the mean over matched panels of
  |A_est - A_gt| / A_gt, panels matched by name, then unique label, then a Hungarian assignment on
  turning distance + 3D placement; when the panel counts differ (column panels: est/gt) metrics.json
  has no match and the base and graded cells stay empty (those patterns are not saved), and the
  final cell is the mean over the panels matched without strictness (the unmatched left out);
- total area error [%]: |sum A_est - sum A_gt| / sum A_gt over all panels (no correspondence
  needed) for the same three patterns; the final one is read from the result's pattern.json, base
  and graded from metrics.json's per-panel areas when matched;
- the case's cross-simulator floor [mm] (meta.json's floor.chamfer_mm: the true pattern draped by
  ``unsew drape``), and whether phase two's pattern was kept (metrics.json's redress);
- the fit process's peak resident memory [MB] (metrics.json's peak_memory_mb) and the stage that
  set it (:func:`peak_stage`: loaded = reading the case and the body, body_sdf, grading,
  material_choice, optimization, redress, mesh_spread, metrics).

Resumable: a case whose result folder exists is not fitted again (nor one whose earlier failure is
recorded in OUT/_status/CASE.json, unless --retry); an interrupted fit resumes from its checkpoint.

    python -m benchmarks foreign_fit [--cases a,b] [--out bench-out/foreign_fit] [--no-run] [--retry]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"

COLUMNS = ["case", "garment", "body", "exit", "time_s",
           "cf_base_mm", "cf_graded_mm", "cf_final_mm", "floor_mm",
           "area_base_pct", "area_graded_pct", "area_final_pct",
           "total_base_pct", "total_graded_pct", "total_final_pct",
           "panels", "phase2_kept", "peak_mb", "peak_stage"]


def case_dirs(names: list[str] | None = None) -> list[Path]:
    """Case folders (those holding meta.json) in benchmarks/foreign/cases, sorted; ``names`` picks
    some by folder name (an unknown name is an error)."""
    all_ = {p.parent.name: p.parent for p in sorted(CASES.glob("*/meta.json"))}
    if not names:
        return list(all_.values())
    missing = [n for n in names if n not in all_]
    if missing:
        raise SystemExit(f"foreign_fit: no case named {missing}; cases: {', '.join(all_)}")
    return [all_[n] for n in names]


def _last_line(text: str) -> str:
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    return lines[-1] if lines else ""


def run_case(case: Path, out: Path, *, retry: bool = False, python: str = sys.executable) -> dict:
    """Fit one case with the CLI into ``out/<case>`` unless done; returns its status dict:
    rc (exit code), exit ('ok' or the last stderr line), time_s (wall time of the command [s])."""
    res = out / case.name
    status_file = out / "_status" / f"{case.name}.json"
    if res.is_dir() and (res / "metrics.json").is_file():
        if status_file.is_file():
            return json.loads(status_file.read_text())
        return {"rc": 0, "exit": "ok", "time_s": None}
    if status_file.is_file() and not retry:
        return json.loads(status_file.read_text())
    status_file.parent.mkdir(parents=True, exist_ok=True)
    cmd = [python, "-m", "unsew", "fit", str(case), "--out", str(res)]
    partial = res.with_name(res.name + ".partial")
    if (partial / "checkpoint.pt").is_file():
        cmd.append("--resume")
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), OMP_WAIT_POLICY="PASSIVE")
    log = out / "_status" / f"{case.name}.log"
    print(f"fitting {case.name} -> {res} (log {log})", file=sys.stderr, flush=True)
    t = time.perf_counter()
    with open(log, "w") as fh:
        proc = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    secs = time.perf_counter() - t
    text = log.read_text(errors="replace")
    ok = proc.returncode == 0 and (res / "metrics.json").is_file()
    status = {"rc": proc.returncode, "exit": "ok" if ok else (_last_line(text) or f"exit {proc.returncode}"),
              "time_s": round(secs, 1), "command": " ".join(cmd[1:])}
    if not ok and proc.returncode < 0:
        status["exit"] = f"killed by signal {-proc.returncode}; last line: {_last_line(text)}"
    status_file.write_text(json.dumps(status, indent=1) + "\n")
    return status


def _total_err(panels: dict) -> float | None:
    """|sum est - sum gt| / sum gt [%] from metrics' per-panel areas, or None."""
    if not panels:
        return None
    est = sum(p["area_est_m2"] for p in panels.values())
    gt = sum(p["area_gt_m2"] for p in panels.values())
    return 100.0 * abs(est - gt) / gt


def _pattern_area(path: Path) -> tuple[float, int]:
    """Total panel area [m^2] and panel count of a GarmentCode JSON pattern."""
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import panel_area

    pat = load_pattern(path)
    return sum(panel_area(p) for p in pat.panels.values()), len(pat.panels)


def _matched_area_err(est_path: Path, gt_path: Path) -> float | None:
    """Mean relative area error [%] over the panels :func:`unsew.metrics.panels.match_panels`
    matches without strictness (the unmatched ones, e.g. a waistband the base pattern lacks, are
    left out), or None when none match."""
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import area_error, match_panels

    est, gt = load_pattern(est_path), load_pattern(gt_path)
    corr = match_panels(est, gt, strict=False)
    return 100.0 * area_error(est, gt, corr).mean if corr else None


def row(case: Path, out: Path, status: dict) -> dict:
    """The table row of one case from its meta.json, status and (if any) result folder."""
    meta = json.loads((case / "meta.json").read_text())
    floor = (meta.get("floor") or {}).get("chamfer_mm")
    r = {"case": case.name, "garment": meta.get("garment"),
         "body": (meta.get("source") or {}).get("body_key", (meta.get("body") or {}).get("model")),
         "exit": status["exit"], "time_s": status.get("time_s"), "floor_mm": floor}
    res = out / case.name
    if not (res / "metrics.json").is_file():
        return r
    m = json.loads((res / "metrics.json").read_text())
    if r["time_s"] is None:
        r["time_s"] = (m.get("timings_s") or {}).get("total_s")
    for key, col in (("surface_base", "cf_base_mm"), ("surface_graded", "cf_graded_mm"), ("surface", "cf_final_mm")):
        r[col] = (m.get(key) or {}).get("chamfer_mm")
    for key, tag in (("pattern_base", "base"), ("pattern_graded", "graded"), ("pattern", "final")):
        p = m.get(key) or {}
        if "area_error_rel_mean" in p:
            r[f"area_{tag}_pct"] = 100.0 * p["area_error_rel_mean"]
            r[f"total_{tag}_pct"] = _total_err(p.get("panels"))
    if r.get("area_final_pct") is None:  # strict matching failed (panel counts differ): matched panels only
        r["area_final_pct"] = _matched_area_err(res / "pattern.json", case / "pattern_gt.json")
    gt_area, n_gt = _pattern_area(case / "pattern_gt.json")
    est_area, n_est = _pattern_area(res / "pattern.json")
    r["total_final_pct"] = 100.0 * abs(est_area - gt_area) / gt_area
    r["panels"] = f"{n_est}/{n_gt}"
    red = m.get("redress")
    r["phase2_kept"] = None if red is None else ("yes" if red.get("phase_two_kept") else "no")
    r["peak_mb"] = m.get("peak_memory_mb")  # the fit process's peak resident memory [MB]
    r["peak_stage"] = peak_stage(m)
    return r


def peak_stage(metrics: dict) -> str | None:
    """The fit stage that set the process's peak memory: the first stage in metrics.json's
    ``peak_memory_stages_mb`` (the peak so far at the end of each stage) reaching the final peak;
    "metrics" when only the metrics after the last stage did; None when not recorded."""
    stages = metrics.get("peak_memory_stages_mb") or {}
    peak = metrics.get("peak_memory_mb")
    if not stages or peak is None:
        return None
    for name, mb in stages.items():
        if mb is not None and mb >= peak - 1.0:  # within 1 MB: the same page high-water mark
            return name.removesuffix("_s")
    return "metrics"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="", help="comma-separated case folder names (default: all)")
    ap.add_argument("--out", default=str(ROOT / "bench-out" / "foreign_fit"), help="results folder")
    ap.add_argument("--no-run", action="store_true", help="only tabulate the results already in --out")
    ap.add_argument("--retry", action="store_true", help="fit again the cases whose earlier fit failed")
    args = ap.parse_args(argv)
    names = [n for n in args.cases.split(",") if n]
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for case in case_dirs(names):
        sf = out / "_status" / f"{case.name}.json"
        if args.no_run and not (out / case.name / "metrics.json").is_file():
            status = json.loads(sf.read_text()) if sf.is_file() else {"exit": "not run", "time_s": None}
        else:
            status = run_case(case, out, retry=args.retry)
        rows.append(row(case, out, status))
    from tables import print_table

    print_table(rows, COLUMNS, title=f"Foreign benchmark: default fit per case (results in {out})", digits=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
