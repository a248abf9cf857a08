"""How do two runs of the foreign fits differ, case by case (a method change measured)?

Reads ``python -m benchmarks foreign_fit --out DIR`` result folders: ``--before`` one or more
folders (the first holding a case wins), ``--after`` one; for every case fitted in both, prints
the final Chamfer [mm], area-weighted and total panel area errors [%] before -> after, whether the
fit is better than its base on Chamfer and area error (area-weighted, then total) and whether
phase two was kept; then issue 21's bars over those cases for each run, and the time each
stage took (metrics.json's ``timings_s``) with phase two's iterations and what the time limit cut
(a speed change measured). Pattern metrics are
computed anew from the saved patterns (foreign_fit's ``--recompute``), so both runs are judged by
today's metric.

    python -m benchmarks fit_compare --before OLD [OLD ...] --after NEW
"""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path

import bench_foreign_fit as ff

COLUMNS = ["case", "chamfer_mm", "area_weighted_pct", "total_pct", "better_weighted", "better_total", "phase2_kept", "time_s"]


def _status(d: Path, name: str) -> dict:
    f = d / "_status" / f"{name}.json"
    return json.loads(f.read_text()) if f.is_file() else {"exit": "ok", "time_s": None}


def _better(r: dict, col: str) -> bool:
    return r["cf_final_mm"] < r["cf_base_mm"] and r[f"{col}_final_pct"] < r[f"{col}_base_pct"]


def _yn(b: bool) -> str:
    return "yes" if b else "no"


def compare(before: list[Path], after: Path) -> tuple[list[dict], list[dict], list[dict]]:
    """(comparison rows, foreign_fit rows before, rows after) over the cases fitted in both."""
    rows, old, new = [], [], []
    for case in ff.case_dirs():
        od = next((d for d in before if (d / case.name / "metrics.json").is_file()), None)
        if od is None or not (after / case.name / "metrics.json").is_file():
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # GarmentCode's clockwise panels, said when fitted
            ro = ff.row(case, od, _status(od, case.name), recompute=True)
            rn = ff.row(case, after, _status(after, case.name), recompute=True)
        old.append(ro)
        new.append(rn)
        rows.append({
            "case": case.name,
            "chamfer_mm": f"{ro['cf_final_mm']:.1f} -> {rn['cf_final_mm']:.1f}",
            "area_weighted_pct": f"{ro['area_final_pct']:.1f} -> {rn['area_final_pct']:.1f}",
            "total_pct": f"{ro['total_final_pct']:.1f} -> {rn['total_final_pct']:.1f}",
            "better_weighted": f"{_yn(_better(ro, 'area'))} -> {_yn(_better(rn, 'area'))}",
            "better_total": f"{_yn(_better(ro, 'total'))} -> {_yn(_better(rn, 'total'))}",
            "phase2_kept": f"{ro['phase2_kept']} -> {rn['phase2_kept']}",
            "time_s": rn.get("time_s"),
        })
    return rows, old, new


STAGES = ["grading_s", "material_choice_s", "optimization_s", "redress_s", "total_s"]


def stage_rows(before: list[Path], after: Path) -> list[dict]:
    """Per case fitted in both: each stage's seconds before -> after, phase two's iterations and
    how many things the time limit cut."""
    out = []
    for case in ff.case_dirs():
        od = next((d for d in before if (d / case.name / "metrics.json").is_file()), None)
        if od is None or not (after / case.name / "metrics.json").is_file():
            continue
        mo, mn = (json.loads((d / case.name / "metrics.json").read_text()) for d in (od, after))
        row = {"case": case.name}
        for k in STAGES:
            a, b = mo.get("timings_s", {}).get(k), mn.get("timings_s", {}).get(k)
            row[k] = f"{a:.0f} -> {b:.0f}" if a is not None and b is not None else "-"
        row["iterations"] = f"{mo.get('iterations')} -> {mn.get('iterations')}"
        row["cuts"] = f"{len(mo.get('time_limit', {}).get('cuts', []))} -> {len(mn.get('time_limit', {}).get('cuts', []))}"
        out.append(row)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", nargs="+", type=Path, required=True, help="foreign_fit result folders of the old method")
    ap.add_argument("--after", type=Path, required=True, help="the foreign_fit result folder of the new method")
    args = ap.parse_args(argv)
    rows, old, new = compare(args.before, args.after)
    if not rows:
        print("fit_compare: no case is fitted in both --before and --after")
        return 1
    from tables import print_table

    print_table(rows, COLUMNS, title=f"Foreign fits, before -> after ({len(rows)} cases)", digits=0)
    b_old, b_new = ff.bars(old), ff.bars(new)
    print_table([{"figure": o["figure"], "before": o["value"], "after": n["value"]} for o, n in zip(b_old, b_new)],
                title="Issue 21's bars over these cases")
    print_table(stage_rows(args.before, args.after), ["case", *STAGES, "iterations", "cuts"],
                title="Seconds per stage, phase two's iterations, time-limit cuts (before -> after)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
