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
    f = {
        k: "-" if r.get(k) is None else f"{r[k]:{w}}"
        for k, w in (("chamfer_mm", ".2f"), ("panel_err", ".3f"), ("turning", ".3f"))
    }
    return f"{f['chamfer_mm']} mm, {f['panel_err']}, {f['turning']}, {r.get('panels_rec')} pieces{ok}"


#: What a case folder needs to judge a fit of it.
CASE_FILES = ("truth.json", "pattern_gt.json", "target.obj")


class Unjudged(Exception):
    """A fit or a case that cannot be judged, with the one-line reason."""


def _rows(cases: Path, before: Path, after: Path, wanted: list[str]) -> list:
    """(case, before, after) of each case fitted in either folder; raises Unjudged."""
    rows = []
    for cid in wanted:
        if not any((d / cid).is_dir() or cid in fits.read_log(d) for d in (before, after)):
            continue
        missing = [f for f in CASE_FILES if not (cases / cid / f).is_file()]
        if missing:
            raise Unjudged(f"case {cid} has no {', '.join(missing)} in {cases} (give --cases)")
        pair = []
        for d in (before, after):
            try:
                pair.append(judged(cases, d, cid))
            except (KeyError, ValueError, TypeError, OSError) as exc:
                raise Unjudged(f"{d / cid} cannot be judged: {type(exc).__name__}: {exc}") from exc
        rows.append((cid, *pair))
    return rows


def cmd_compare(args, case_ids: list[str]) -> int:
    """Print the before -> after table and the tally of two result folders (``args.before``,
    ``args.after``) over the built cases in ``args.cases`` (``args.only`` when given)."""
    cases, before, after = Path(args.cases), Path(args.before), Path(args.after)
    for p in (cases, before, after):
        if not p.is_dir():
            print(f"gcd compare: no folder {p}", file=sys.stderr)
            return 2
    unknown = sorted(set(args.only or ()) - set(case_ids))
    if unknown:
        print(f"gcd compare: no such case {', '.join(unknown)} (ids are gc_s<seed>_<index>)", file=sys.stderr)
        return 2
    wanted = [c for c in case_ids if not args.only or c in args.only]
    try:
        rows = _rows(cases, before, after, wanted)
    except Unjudged as exc:
        print(f"gcd compare: {exc}", file=sys.stderr)
        return 2
    if not rows:
        print(f"gcd compare: no fit of these cases in {before} or {after}", file=sys.stderr)
        return 2
    print("| case | before (Chamfer, panel error, turning, pieces) | after |")
    print("|---|---|---|")
    for cid, b, a in rows:
        print(f"| {cid} | {_cell(b)} | {_cell(a)} |")
    print(json.dumps(tally(rows)))
    return 0
