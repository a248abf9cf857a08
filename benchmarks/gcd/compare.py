"""Two folders of fit results of the same cases, side by side: what a trial of a method change on
the sample prints. Fit the cases at two commits (``gcd fit --results BEFORE --only ...`` and
``--results AFTER``), then ``gcd compare BEFORE AFTER``: each case in either folder judged in both
(score.score_case without newton's re-drapes nor the floors: Chamfer, panel error, turning,
pieces after merging), before -> after, and how many moved which way. A fit that ended with an
error counts as one; a case fitted in one folder only is listed, not counted.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import fits
import score

#: Differences within these count as the same (Chamfer [mm], panel error [-], turning [rad]).
SAME = {"chamfer_mm": 0.1, "panel_err": 0.005, "turning": 0.005}


def judged(cases: Path, results: Path, cid: str) -> dict | None:
    """{exit, chamfer_mm, panel_err, turning, panels_rec, fit_ok} of one case's fit in ``results``,
    or None when the folder has no outcome nor fit of it; a failed fit has its exit and message."""
    out = fits.read_log(results).get(cid)
    res = results / cid
    if out is None and not (res / "pattern.json").is_file():
        return None
    if out is not None and out["exit"] != 0:
        return {"exit": out["exit"], "message": out["message"]}
    rec = score.score_case(cases / cid, res, floor=False, redrape=False)
    keys = ("chamfer_mm", "panel_err", "turning", "panels_rec", "fit_ok")
    return {"exit": 0, **{k: rec.get(k) for k in keys}}


def tally(rows: list[tuple[str, dict | None, dict | None]]) -> dict:
    """Per measure, over the cases fitted with exit 0 in both: {"lower": n, "higher": n, "same": n}
    (beyond :data:`SAME`), and the count of failed fits in each folder."""
    both = [(b, a) for _, b, a in rows if b and a and b["exit"] == 0 and a["exit"] == 0]
    out: dict = {"cases": len(both)}
    for key, tol in SAME.items():
        pairs = [
            (float(b[key]), float(a[key]))
            for b, a in both
            if b.get(key) is not None and a.get(key) is not None
        ]
        out[key] = {
            "lower": int(sum(a < b - tol for b, a in pairs)),
            "higher": int(sum(a > b + tol for b, a in pairs)),
            "same": int(sum(abs(a - b) <= tol for b, a in pairs)),
        }
    out["failed_before"] = sum(1 for _, b, _ in rows if b and b["exit"] != 0)
    out["failed_after"] = sum(1 for _, _, a in rows if a and a["exit"] != 0)
    return out


def _cell(r: dict | None) -> str:
    if r is None:
        return "-"
    if r["exit"] != 0:
        return f"exit {r['exit']}"
    ok = "" if r.get("fit_ok", True) else ' ("ok": false)'
    return f"{r['chamfer_mm']:.2f} mm, {r['panel_err']:.3f}, {r['turning']:.3f}, {r['panels_rec']} pieces{ok}"


def cmd_compare(args, case_ids: list[str]) -> int:
    """Print the before -> after table and the tally of two result folders (``args.before``,
    ``args.after``) over the built cases in ``args.cases`` (``args.only`` when given)."""
    cases, before, after = Path(args.cases), Path(args.before), Path(args.after)
    for p in (cases, before, after):
        if not p.is_dir():
            print(f"gcd compare: no folder {p}", file=sys.stderr)
            return 2
    wanted = [c for c in case_ids if not args.only or c in args.only]
    rows = [(cid, judged(cases, before, cid), judged(cases, after, cid)) for cid in wanted]
    rows = [r for r in rows if r[1] is not None or r[2] is not None]
    if not rows:
        print(f"gcd compare: no fit of these cases in {before} or {after}", file=sys.stderr)
        return 2
    print("| case | before (Chamfer, panel error, turning, pieces) | after |")
    print("|---|---|---|")
    for cid, b, a in rows:
        print(f"| {cid} | {_cell(b)} | {_cell(a)} |")
    print(json.dumps(tally(rows)))
    return 0
