"""The batch summary: one row per case, as CSV (``summary.csv``), a printed table, and
``index.html`` linking every case's report.

Columns: case, garment, status, iterations, time_s [s], the final loss terms (loss_total,
loss_chamfer, ...: dimensionless, as in metrics.json's loss_final), the 3D metrics of the final
drape against the target (chamfer_mm [mm], normal_error_deg [deg]) and, where the case has a true
pattern, the pattern metrics (area_error_rel_mean [-], turning_distance_mean [-],
vertex_l2_cm_mean [cm]); then resumed, reason (one line for a failure) and result (the case's
result folder, relative to RESULTS_DIR). Empty cells are values that do not exist for that case.
"""

from __future__ import annotations

import csv
import html
import io
import os
from pathlib import Path
from typing import Sequence
from urllib.parse import quote

from unsew.batch.task import CaseRecord
from unsew.io.atomic import atomic_write

__all__ = [
    "summary_rows",
    "write_summary_csv",
    "format_table",
    "write_index_html",
    "BASE_COLUMNS",
    "METRIC_COLUMNS",
]

BASE_COLUMNS = ["case", "garment", "status", "iterations", "time_s"]
#: (column, section of metrics.json, key)
METRIC_COLUMNS = [
    ("chamfer_mm", "surface", "chamfer_mm"),
    ("normal_error_deg", "surface", "normal_error_deg"),
    ("area_error_rel_mean", "pattern", "area_error_rel_mean"),
    ("turning_distance_mean", "pattern", "turning_distance_mean"),
    ("vertex_l2_cm_mean", "pattern", "vertex_l2_cm_mean"),
]
_TAIL = ["resumed", "reason", "result"]
_LOSS_ORDER = ["total", "chamfer", "open", "seam", "material"]


def _num(v):
    return v if isinstance(v, (int, float)) and not isinstance(v, bool) else None


def _loss_keys(records: Sequence[CaseRecord]) -> list[str]:
    keys: list[str] = []
    for r in records:
        for k in (r.metrics or {}).get("loss_final") or {}:
            if k not in keys:
                keys.append(k)
    return sorted(keys, key=lambda k: (_LOSS_ORDER.index(k) if k in _LOSS_ORDER else len(_LOSS_ORDER), k))


def summary_rows(records: Sequence[CaseRecord], *, root: str | os.PathLike | None = None) -> list[dict]:
    """One dict per record with the summary columns (values: str, int, float or None).
    ``root``: the results folder, to write result paths relative to it."""
    losses = _loss_keys(records)
    rows = []
    for r in records:
        m = r.metrics or {}
        row = {
            "case": r.name,
            "garment": r.garment,
            "status": r.status,
            "iterations": _num(m.get("iterations")),
            "time_s": r.time_s,
        }
        for k in losses:
            row[f"loss_{k}"] = _num((m.get("loss_final") or {}).get(k))
        for col, sec, key in METRIC_COLUMNS:
            row[col] = _num((m.get(sec) or {}).get(key)) if isinstance(m.get(sec), dict) else None
        row["resumed"] = r.resumed
        row["reason"] = r.reason
        row["result"] = os.path.relpath(r.out_dir, root) if root is not None else r.out_dir
        rows.append(row)
    return rows


def _columns(rows: Sequence[dict]) -> list[str]:
    if not rows:
        return BASE_COLUMNS + [c for c, _, _ in METRIC_COLUMNS] + _TAIL
    return list(rows[0])


def write_summary_csv(records: Sequence[CaseRecord], path: str | os.PathLike) -> Path:
    """Write ``summary.csv`` atomically (a temporary file renamed onto ``path``). Numbers are
    written with full precision (repr). Returns the path."""
    path = Path(path)
    rows = summary_rows(records, root=path.parent)
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=_columns(rows), lineterminator="\n")
    w.writeheader()
    for row in rows:
        w.writerow({k: ("" if v is None else v) for k, v in row.items()})
    with atomic_write(path) as tmp:
        tmp.write_text(buf.getvalue(), encoding="utf-8")
    return path


def _fmt(col: str, v) -> str:
    if v is None or v == "":
        return "-"
    if isinstance(v, bool):
        return "yes" if v else ""
    if col == "time_s":
        return f"{v:.1f}"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


#: short headers of the printed table
_SHORT = {
    "iterations": "iters",
    "time_s": "time[s]",
    "chamfer_mm": "chamfer[mm]",
    "normal_error_deg": "normal[deg]",
    "area_error_rel_mean": "area_err",
    "turning_distance_mean": "turning",
    "vertex_l2_cm_mean": "vtx_l2[cm]",
}


def format_table(records: Sequence[CaseRecord]) -> str:
    """A plain-text table of the summary (one line per case; a failure's reason on the next
    line), for the terminal. Columns that are empty for every case are left out."""
    rows = summary_rows(records)
    cols = [c for c in _columns(rows) if c not in ("reason", "result", "resumed")]
    cols = [c for c in cols if c in BASE_COLUMNS or any(r.get(c) is not None for r in rows)]
    cells = [[_SHORT.get(c, c) for c in cols]] + [[_fmt(c, r[c]) for c in cols] for r in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(cols))]
    lines = []
    for j, row in enumerate(cells):
        lines.append(
            "  ".join(v.ljust(w) if i < 3 else v.rjust(w) for i, (v, w) in enumerate(zip(row, widths)))
        )
        if j == 0:
            lines.append("-" * len(lines[0]))
        elif rows[j - 1]["reason"]:
            lines.append(f"    {rows[j - 1]['status']}: {rows[j - 1]['reason']}")
    n = {
        s: sum(r.status == s for r in records)
        for s in ("done", "skipped", "failed", "interrupted", "pending")
    }
    lines.append(", ".join(f"{v} {k}" for k, v in n.items() if v) + f" of {len(records)} cases")
    return "\n".join(lines)


def write_index_html(
    records: Sequence[CaseRecord], path: str | os.PathLike, *, title: str = "unsew batch"
) -> Path:
    """Write ``index.html`` atomically: counts by status, then the summary table with each case
    linking its ``report.html`` (where it exists) and its result folder. Returns the path."""
    path = Path(path)
    rows = summary_rows(records, root=path.parent)
    cols = [c for c in _columns(rows) if c not in ("result", "reason")]
    counts = {}
    for r in records:
        counts[r.status] = counts.get(r.status, 0) + 1
    e = html.escape
    out = [
        "<!DOCTYPE html>",
        "<html><head><meta charset='utf-8'>",
        f"<title>{e(title)}</title>",
        "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
        "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}td.l,th.l{text-align:left}"
        "tr.failed{background:#fde8e8}tr.interrupted,tr.pending{background:#fff6dd}</style></head><body>",
        f"<h1>{e(title)}</h1>",
        "<h2>Summary</h2>",
        "<p>" + ", ".join(f"{v} {e(k)}" for k, v in sorted(counts.items())) + f" of {len(records)} cases. "
        "Units: time in s, Chamfer in mm, normal error in degrees, vertex L2 in cm; losses and "
        "pattern errors are dimensionless. Machine-readable: <a href='summary.csv'>summary.csv</a>.</p>",
        "<table><tr>"
        + "".join(
            f"<th class='{'l' if c in ('case', 'garment', 'status') else ''}'>{e(c)}</th>" for c in cols
        )
        + "<th class='l'>report / reason</th></tr>",
    ]
    for r, row in zip(records, rows):
        tds = []
        for c in cols:
            v = _fmt(c, row[c])
            if c == "case" and Path(r.out_dir).is_dir():
                v = f"<a href='{e(quote(row['result']))}/'>{e(v)}</a>"
            else:
                v = e(v)
            tds.append(f"<td class='{'l' if c in ('case', 'garment', 'status') else ''}'>{v}</td>")
        report = Path(r.out_dir) / "report.html"
        if report.is_file() and r.status in ("done", "skipped"):
            last = f"<a href='{e(quote(row['result']))}/report.html'>report</a>"
        else:
            last = e(r.reason)
        out.append(f"<tr class='{e(r.status)}'>" + "".join(tds) + f"<td class='l'>{last}</td></tr>")
    out += ["</table>", "</body></html>", ""]
    with atomic_write(path) as tmp:
        tmp.write_text("\n".join(out), encoding="utf-8")
    return path
