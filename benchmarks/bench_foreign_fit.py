"""How well does the default fit recover garments unsew did not make?

For every case folder in benchmarks/foreign/cases (a GarmentCode-style design draped by newton on an
anny body; see benchmarks/foreign and FORMATS.md), runs the real command-line fit with the default
configuration, ``python -m unsew fit CASE --out OUT/CASE``, one case at a time in a subprocess, and
prints one row per case:

- garment, body (meta.json's source.body_key), base (metrics.json's base: the library base the fit
  chose by draping, or the one named), exit (``ok`` or the fit's last stderr line), wall
  time of the command [s];
- Chamfer [mm] of the base drape, the graded drape and the final result against the target
  (metrics.json: surface_base, surface_graded, surface; since 2026-11 the result's and, judged on
  three meshes, the graded drape are their patterns dressed from scratch, metrics.json's
  ``drapes``), and ``cf_warm_mm``, a kept phase two's own warm-started drape (surface_warm), which
  results before then reported as the final one;
- panel area errors [%] of the base, graded and final pattern against pattern_gt.json
  (unsew.metrics.panels.pattern_metrics; panels matched by name, then unique label, then a
  Hungarian assignment on turning distance + 3D placement, panels left over reported):
  ``area_*`` the area-weighted error in which an unmatched panel counts at its full area
  (area_error_weighted_rel: the figure the area bar is judged on), ``total_*``
  |sum A_est - sum A_gt| / sum A_gt (no correspondence), ``matched_final_pct`` the paper's mean
  over matched panels of |A_est - A_gt| / A_gt; read from metrics.json, or computed from the result
  folder's pattern.json / pattern_base.json / pattern_graded.json when metrics.json predates these
  figures; ``panels`` est/gt panel counts of the final pattern and ``unmatched`` its panels without
  a counterpart (``gt:`` true panels the result lacks, ``est:`` extra ones);
- ``seam_final_mm``: the largest change of a stitch's length difference L_a - L_b in the final
  pattern from the base's [mm] (:func:`unsew.pattern.seams.seam_changes_mm`, from the saved
  pattern files: how far from sewing the fit left a seam, the base's ease left out);
- ``loss_spikes``: phase-two iterations whose loss exceeds 5 x the lowest before it, and in
  brackets how many of them the material range penalty makes (its term over half the loss;
  metrics.json's loss_history);
- the case's cross-simulator floor [mm] (meta.json's floor.chamfer_mm: the true pattern draped by
  ``unsew drape``), and whether phase two's pattern was kept (metrics.json's redress);
- the fit process's peak resident memory [MB] (metrics.json's peak_memory_mb) and the stage that
  set it (:func:`peak_stage`: loaded = reading the case and the body, body_sdf, grading,
  material_choice, optimization, redress, mesh_spread, metrics).

``--record FILE --code REV`` also writes each fitted case's row, with the commit REV its fit ran
on, into FILE (JSON, case -> row; a case's earlier record is replaced), and ``--latest FILE``
prints FILE's rows, each case's latest recorded fit, and the bars over them: results folders do
not outlive a machine, the record does (benchmarks/foreign/fits.json is the project's).

Resumable: a case whose result folder exists is not fitted again (nor one whose earlier failure is
recorded in OUT/_status/CASE.json, unless --retry); an interrupted fit resumes from its checkpoint.

    python -m benchmarks foreign_fit [--cases a,b] [--out bench-out/foreign_fit] [--no-run] [--retry]
        [--config fit.yaml] [--recompute] [--record benchmarks/foreign/fits.json --code REV]
    python -m benchmarks foreign_fit --latest benchmarks/foreign/fits.json
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
#: The project's record of each case's latest fit (``--record``, ``--latest``).
RECORD = ROOT / "benchmarks" / "foreign" / "fits.json"

COLUMNS = [
    "case",
    "garment",
    "body",
    "base",
    "exit",
    "time_s",
    "cf_base_mm",
    "cf_graded_mm",
    "cf_final_mm",
    "cf_warm_mm",
    "floor_mm",
    "area_base_pct",
    "area_graded_pct",
    "area_final_pct",
    "total_base_pct",
    "total_graded_pct",
    "total_final_pct",
    "matched_final_pct",
    "seam_final_mm",
    "loss_spikes",
    "stretch_max",
    "barrier",
    "panels",
    "unmatched",
    "phase2_kept",
    "peak_mb",
    "peak_stage",
]

#: metrics.json key and result-folder file of each pattern the table judges
PATTERNS = (
    ("base", "pattern_base", "pattern_base.json"),
    ("graded", "pattern_graded", "pattern_graded.json"),
    ("final", "pattern", "pattern.json"),
)


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


def run_case(
    case: Path, out: Path, *, retry: bool = False, python: str = sys.executable, config: str | None = None
) -> dict:
    """Fit one case with the CLI into ``out/<case>`` unless done (``config``: a fit.yaml passed as
    ``--config``); returns its status dict:
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
    if config is not None:
        cmd += ["--config", str(Path(config).resolve())]
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
    status = {
        "rc": proc.returncode,
        "exit": "ok" if ok else (_last_line(text) or f"exit {proc.returncode}"),
        "time_s": round(secs, 1),
        "command": " ".join(cmd[1:]),
    }
    if not ok and proc.returncode < 0:
        status["exit"] = f"killed by signal {-proc.returncode}; last line: {_last_line(text)}"
    status_file.write_text(json.dumps(status, indent=1) + "\n")
    return status


def _pattern_errors(
    m: dict, key: str, est_path: Path, gt_path: Path, *, recompute: bool = False
) -> dict | None:
    """The pattern metrics of one pattern: metrics.json's ``key`` when it has the area-weighted
    error (and not ``recompute``), else :func:`unsew.metrics.panels.pattern_metrics` of
    ``est_path`` (if saved) against ``gt_path``; None when neither is there."""
    p = m.get(key) or {}
    if "area_error_weighted_rel" in p and not (recompute and est_path.is_file()):
        return p
    if not est_path.is_file():
        return None
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import pattern_metrics

    return pattern_metrics(load_pattern(est_path), load_pattern(gt_path))


def _seam_change(res: Path) -> float | None:
    """The final pattern's largest seam change from the base [mm] (COLUMNS' seam_final_mm), from
    the result folder's pattern.json and pattern_base.json; None without both."""
    if not ((res / "pattern.json").is_file() and (res / "pattern_base.json").is_file()):
        return None
    import warnings

    from unsew.io.garmentcode import load_pattern
    from unsew.pattern.seams import seam_changes_mm

    with warnings.catch_warnings():  # a base's ease (a sleeve cap longer than its armhole) is warned on load
        warnings.simplefilter("ignore", UserWarning)
        pats = {"base": load_pattern(res / "pattern_base.json"), "result": load_pattern(res / "pattern.json")}
    return seam_changes_mm(pats)["change_from_base_max_mm"].get("result")


def _loss_spikes(h: dict, factor: float = 5.0) -> str | None:
    """COLUMNS' loss_spikes from metrics.json's loss_history: "n (m)", n iterations whose total
    loss exceeds ``factor`` x the lowest before it, m of them mostly the material term."""
    t, mat = h.get("total") or [], h.get("material") or []
    if not t:
        return None
    spikes = [i for i in range(1, len(t)) if t[i] > factor * min(t[:i])]
    by_mat = sum(1 for i in spikes if i < len(mat) and mat[i] > 0.5 * t[i])
    return f"{len(spikes)} ({by_mat})"


def _unmatched(p: dict) -> str:
    un = p.get("unmatched") or {}
    parts = [
        f"gt: {','.join(un['true'])}" if un.get("true") else "",
        f"est: {','.join(un['estimated'])}" if un.get("estimated") else "",
    ]
    return "; ".join(x for x in parts if x) or "-"


def row(case: Path, out: Path, status: dict, *, recompute: bool = False) -> dict:
    """The table row of one case from its meta.json, status and (if any) result folder
    (``recompute``: the pattern metrics computed anew from the saved patterns, by today's code)."""
    meta = json.loads((case / "meta.json").read_text())
    floor = (meta.get("floor") or {}).get("chamfer_mm")
    r = {
        "case": case.name,
        "garment": meta.get("garment"),
        "body": (meta.get("source") or {}).get("body_key", (meta.get("body") or {}).get("model")),
        "exit": status["exit"],
        "time_s": status.get("time_s"),
        "floor_mm": floor,
    }
    res = out / case.name
    if not (res / "metrics.json").is_file():
        return r
    m = json.loads((res / "metrics.json").read_text())
    if r["time_s"] is None:
        r["time_s"] = (m.get("timings_s") or {}).get("total_s")
    r["base"] = m.get("base")  # the base pattern phase one started from (chosen by draping by default)
    for key, col in (
        ("surface_base", "cf_base_mm"),
        ("surface_graded", "cf_graded_mm"),
        ("surface", "cf_final_mm"),
        ("surface_warm", "cf_warm_mm"),
    ):
        r[col] = (m.get(key) or {}).get("chamfer_mm")
    for tag, key, fname in PATTERNS:
        p = _pattern_errors(m, key, res / fname, case / "pattern_gt.json", recompute=recompute)
        if p is None:
            continue
        r[f"area_{tag}_pct"] = 100.0 * p["area_error_weighted_rel"]
        r[f"total_{tag}_pct"] = 100.0 * p["area_error_total_rel"]
        if tag == "final":
            if p.get("area_error_rel_mean") is not None:
                r["matched_final_pct"] = 100.0 * p["area_error_rel_mean"]
            un = p.get("unmatched") or {}
            n_est = len(p["panels"]) + len(un.get("estimated") or [])
            n_gt = len(p["panels"]) + len(un.get("true") or [])
            r["panels"] = f"{n_est}/{n_gt}"
            r["unmatched"] = _unmatched(p)
    r["seam_final_mm"] = _seam_change(res)
    r["loss_spikes"] = _loss_spikes(m.get("loss_history") or {})
    # the returned drape's longest edge / rest
    r["stretch_max"] = (m.get("drape_check") or {}).get("stretch_max")
    stretch = (m.get("loss_history") or {}).get("stretch")
    # the stretch barrier's largest term in phase two (0: never acted)
    r["barrier"] = max(stretch) if stretch else None
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


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="", help="comma-separated case folder names (default: all)")
    ap.add_argument("--out", default=str(ROOT / "bench-out" / "foreign_fit"), help="results folder")
    ap.add_argument("--no-run", action="store_true", help="only tabulate the results already in --out")
    ap.add_argument("--retry", action="store_true", help="fit again the cases whose earlier fit failed")
    ap.add_argument(
        "--recompute",
        action="store_true",
        help="compute the pattern metrics anew from each result's saved patterns instead of reading "
        "metrics.json",
    )
    ap.add_argument(
        "--config", default=None, help="a fit.yaml handed to every fit (default: the default configuration)"
    )
    ap.add_argument(
        "--sheet",
        type=Path,
        default=None,
        help="also write one PNG of every fitted case's target-vs-result figure, to look at them all",
    )
    ap.add_argument(
        "--record",
        type=Path,
        default=None,
        metavar="FILE",
        help=f"also write each fitted case's row into FILE (e.g. {RECORD.relative_to(ROOT)}), with --code",
    )
    ap.add_argument(
        "--code", default=None, metavar="REV", help="the commit the fits in --out ran on (for --record)"
    )
    ap.add_argument(
        "--latest",
        type=Path,
        default=None,
        metavar="FILE",
        help="only print FILE's recorded rows (each case's latest fit) and the bars over them",
    )
    ap.add_argument(
        "--against",
        type=Path,
        default=None,
        metavar="FILE",
        help="also print each fitted case in --out against its recorded row in FILE (a variant's "
        "fits against the record: Chamfer, per-panel area, phase two kept) and the median changes",
    )
    return ap


def main(argv=None) -> int:
    ap = _parser()
    args = ap.parse_args(argv)
    if args.latest is not None:
        return print_latest(args.latest)
    if args.record is not None and not args.code:
        ap.error("--record needs --code REV: the commit the fits in --out ran on")
    if args.record is not None and args.record.is_file():
        try:
            _read_record(args.record)  # before any fit: a bad record is refused at once
        except ValueError as exc:
            ap.error(str(exc))
    names = [n for n in args.cases.split(",") if n]
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for case in case_dirs(names):
        sf = out / "_status" / f"{case.name}.json"
        if args.no_run and not (out / case.name / "metrics.json").is_file():
            status = json.loads(sf.read_text()) if sf.is_file() else {"exit": "not run", "time_s": None}
        else:
            status = run_case(case, out, retry=args.retry, config=args.config)
        rows.append(row(case, out, status, recompute=args.recompute))
    from tables import print_table

    print_table(rows, COLUMNS, title=f"Foreign benchmark: default fit per case (results in {out})", digits=1)
    summary = bars(rows)
    if summary:
        print_table(summary, title="The bars over the fitted cases", digits=1)
    if args.sheet is not None:
        contact_sheet(rows, out, args.sheet)
        print(f"\nwrote {args.sheet}")
    if args.against is not None:
        try:
            print_against(rows, _read_record(args.against), args.against)
        except ValueError as exc:
            ap.error(str(exc))
    if args.record is not None:
        n = record(rows, args.record, code=args.code, out=out)
        print(f"\nrecorded {n} fits in {args.record}")
    return 0


def record(rows: list[dict], path: Path, *, code: str, out: Path) -> int:
    """Write the fitted ``rows`` (those with a final Chamfer) into the record at ``path`` (JSON,
    case -> row plus ``code``, the commit the fit ran on, and ``results``, the folder it was read
    from), replacing a case's earlier record; returns how many were written."""
    from unsew.io.atomic import atomic_write

    old = _read_record(path) if path.is_file() else {}
    done = [r for r in rows if r.get("cf_final_mm") is not None]
    for r in done:
        old[r["case"]] = {**r, "code": code, "results": str(out)}
    with atomic_write(path) as tmp:
        Path(tmp).write_text(json.dumps(dict(sorted(old.items())), indent=1) + "\n")
    return len(done)


def print_against(rows: list[dict], rec: dict, path: Path) -> None:
    """Each fitted row of ``rows`` beside its case's recorded row in ``rec`` (read from ``path``):
    Chamfer, its bar, per-panel area error (unmatched at 100 %) and over matched panels, total
    area error, phase two kept, "recorded -> now"; then the median changes and how many moved
    each way (by more than 0.05)."""
    from tables import print_table

    def f(v):
        return "-" if v is None else f"{float(v):.1f}"

    def f2(v):
        return "-" if v is None else f"{float(v):.2f}"

    out, dcf, dpa = [], [], []
    for r in rows:
        old = rec.get(r["case"])
        if r.get("cf_final_mm") is None or old is None or old.get("cf_final_mm") is None:
            continue
        floor = r.get("floor_mm")
        out.append(
            {
                "case": r["case"],
                "recorded at": old.get("code"),
                "base": old.get("base")
                if old.get("base") == r.get("base")
                else f"{old.get('base')} -> {r.get('base')}",
                "graded [mm]": f"{f(old.get('cf_graded_mm'))} -> {f(r.get('cf_graded_mm'))}",
                "Chamfer [mm]": f"{f(old['cf_final_mm'])} -> {f(r['cf_final_mm'])}",
                "bar [mm]": f(max(5.0, 1.5 * floor)) if floor is not None else "-",
                "per panel [%]": f"{f(old.get('area_final_pct'))} -> {f(r.get('area_final_pct'))}",
                "matched panels [%]": f"{f(old.get('matched_final_pct'))} -> {f(r.get('matched_final_pct'))}",
                "total [%]": f"{f(old.get('total_final_pct'))} -> {f(r.get('total_final_pct'))}",
                "phase two kept": f"{old.get('phase2_kept') or '-'} -> {r.get('phase2_kept') or '-'}",
                "stretch max": f"{f2(old.get('stretch_max'))} -> {f2(r.get('stretch_max'))}",
                "barrier": f2(r.get("barrier")),
                "time [s]": f(r.get("time_s")),
            }
        )
        dcf.append(float(r["cf_final_mm"]) - float(old["cf_final_mm"]))
        if r.get("area_final_pct") is not None and old.get("area_final_pct") is not None:
            dpa.append(float(r["area_final_pct"]) - float(old["area_final_pct"]))
    print_table(out, title=f"The fits in --out against their record ({path})")
    for name, d, unit in (("Chamfer", dcf, "mm"), ("per-panel area error", dpa, "points")):
        if d:
            print(
                f"{name}: median change {_median(d):+.2f} {unit} over {len(d)}; lower on "
                f"{sum(v < -0.05 for v in d)}, higher on {sum(v > 0.05 for v in d)}"
            )


def _read_record(path: Path) -> dict:
    """The record at ``path`` (case -> row); ValueError with one line when it is not one."""
    try:
        rec = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not a fit record (JSON: {exc})") from None
    if not isinstance(rec, dict) or not all(isinstance(r, dict) for r in rec.values()):
        raise ValueError(f"{path} is not a fit record (a JSON object of case -> row)")
    return rec


def print_latest(path: Path) -> int:
    """Print the recorded latest fit of each case (``--latest``), the cases with none, and the
    bars over the recorded ones."""
    from tables import print_table

    if not path.is_file():
        print(f"foreign_fit: no record at {path}", file=sys.stderr)
        return 2
    try:
        rec = _read_record(path)
    except ValueError as exc:
        print(f"foreign_fit: {exc}", file=sys.stderr)
        return 2
    rows = [rec[c.name] for c in case_dirs() if c.name in rec]
    for r in rows:  # today's floor: a case re-floored since its fit is judged on the new one
        meta = json.loads((CASES / r["case"] / "meta.json").read_text())
        r["floor_mm"] = (meta.get("floor") or {}).get("chamfer_mm", r.get("floor_mm"))
        r["floor_fitted_mm"] = (meta.get("floor_fitted") or {}).get("chamfer_mm")
    missing = [c.name for c in case_dirs() if c.name not in rec]
    print_table(
        rows,
        ["case", "code", *COLUMNS[1:11], "floor_fitted_mm", *COLUMNS[11:]],
        title=f"Foreign benchmark: each case's latest recorded fit ({path})",
        digits=1,
    )
    print(
        f"\n{len(rows)} of {len(rows) + len(missing)} cases recorded"
        + (f"; no record: {', '.join(missing)}" if missing else "")
    )
    summary = bars(rows)
    if summary:
        print_table(summary, title="The bars over the recorded fits", digits=1)
    return 0


def contact_sheet(rows: list[dict], out: Path, path: Path, *, cols: int = 4) -> None:
    """Tile every fitted case's report figure (figures/target_vs_result.png: target above, result
    below, front and side) into one PNG, titled with the case, its Chamfer and floor [mm]."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    shown = [r for r in rows if (out / r["case"] / "figures" / "target_vs_result.png").is_file()]
    if not shown:
        return
    n_rows = (len(shown) + cols - 1) // cols
    fig, axes = plt.subplots(n_rows, cols, figsize=(4 * cols, 5.4 * n_rows), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, r in zip(axes.flat, shown):
        ax.imshow(mpimg.imread(out / r["case"] / "figures" / "target_vs_result.png"))
        ax.set_title(
            f"{r['case']}\nChamfer {r['cf_final_mm']:.1f} mm (floor {r.get('floor_mm') or float('nan'):.1f})",
            fontsize=9,
        )
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=60)
    plt.close(fig)


def _median(v: list[float]) -> float:
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def bars(rows: list[dict]) -> list[dict]:
    """The must-show figures over the cases that have a result: median and worst area error
    (weighted, total and matched), median Chamfer, cases within max(5 mm, 1.5 x floor), cases
    better than their base on both, cases under 10 minutes, and phase two's effect (final against
    graded: medians, and cases improved)."""
    done = [r for r in rows if r.get("cf_final_mm") is not None]
    if not done:
        return []
    out = [
        {
            "figure": "cases fitted (exit 0, on the body)",
            "value": f"{sum(r['exit'] == 'ok' for r in done)} of {len(rows)}",
        }
    ]
    for col, what in (
        ("area_final_pct", "area error, unmatched panels at 100 % [%]"),
        ("total_final_pct", "total area error, abs(sum A - sum A_gt) / sum A_gt [%]"),
        ("matched_final_pct", "area error over matched panels [%]"),
    ):
        v = [r[col] for r in done if r.get(col) is not None]
        if v:
            out.append({"figure": f"{what}: median / worst", "value": f"{_median(v):.1f} / {max(v):.1f}"})
    sv = [r["seam_final_mm"] for r in done if r.get("seam_final_mm") is not None]
    if sv:
        out.append(
            {
                "figure": "seams of the final pattern, largest change from the base [mm]: median / worst; "
                "over 2 mm",
                "value": f"{_median(sv):.1f} / {max(sv):.1f}; {sum(v > 2.0 for v in sv)} of {len(sv)}",
            }
        )
    cf = [r["cf_final_mm"] for r in done]
    out.append(
        {"figure": "Chamfer of the fit: median / worst [mm]", "value": f"{_median(cf):.1f} / {max(cf):.1f}"}
    )
    within = [
        r["case"]
        for r in done
        if r.get("floor_mm") is not None and r["cf_final_mm"] <= max(5.0, 1.5 * r["floor_mm"])
    ]
    out.append({"figure": "Chamfer within max(5 mm, 1.5 x floor)", "value": f"{len(within)} of {len(done)}"})
    fitted = [r["floor_fitted_mm"] for r in done if r.get("floor_fitted_mm") is not None]
    if fitted:
        floors = [r["floor_mm"] for r in done if r.get("floor_fitted_mm") is not None and r.get("floor_mm")]
        out.append(
            {
                "figure": "material-fitted floor (the true pattern, its fabric fitted): median [mm] "
                "(plain floor of the same cases); cases measured",
                "value": f"{_median(fitted):.1f} ({_median(floors):.1f}); {len(fitted)} of {len(done)}",
            }
        )
    out += _better_than_base(done)
    timed = [r for r in done if r.get("time_s") is not None]
    out.append(
        {
            "figure": "under 10 minutes (as run; see the load)",
            "value": f"{sum(r['time_s'] < 600 for r in timed)} of {len(timed)}",
        }
    )
    return out + _phase_two_bars(done)


def _better_than_base(done: list[dict]) -> list[dict]:
    """The cases whose fit is better than their base on both the Chamfer and an area error."""
    out = []
    for col in ("area", "total"):
        better = [
            r
            for r in done
            if r.get(f"{col}_final_pct") is not None
            and r.get(f"{col}_base_pct") is not None
            and r[f"{col}_final_pct"] < r[f"{col}_base_pct"]
            and r["cf_final_mm"] < r["cf_base_mm"]
        ]
        out.append(
            {
                "figure": "better than the base on Chamfer and "
                f"{'total area' if col == 'total' else 'area'} error",
                "value": f"{len(better)} of {len(done)}",
            }
        )
    return out


def _phase_two_bars(done: list[dict]) -> list[dict]:
    """Phase two's effect over the fitted cases (final against graded): medians, the median
    change and the cases lowered and raised, for the Chamfer and both area errors."""
    out = []
    for col, what in (("cf", "Chamfer [mm]"), ("area", "area error [%]"), ("total", "total area error [%]")):
        pairs = [
            (
                r[f"{col}_graded{'_mm' if col == 'cf' else '_pct'}"],
                r[f"{col}_final{'_mm' if col == 'cf' else '_pct'}"],
            )
            for r in done
            if r.get(f"{col}_graded{'_mm' if col == 'cf' else '_pct'}") is not None
        ]
        if pairs:
            g, f = zip(*pairs)
            lower = sum(b < a - 1e-9 for a, b in pairs)
            higher = sum(b > a + 1e-9 for a, b in pairs)
            change = _median([b - a for a, b in pairs])
            out.append(
                {
                    "figure": f"phase two, {what}: median graded -> final; median change; cases lower / "
                    "higher",
                    "value": f"{_median(list(g)):.1f} -> {_median(list(f)):.1f}; {change:+.1f}; {lower} / "
                    f"{higher}",
                }
            )
    return out


if __name__ == "__main__":
    sys.exit(main())
