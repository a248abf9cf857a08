"""What do the recorded results say now? Writes docs/benchmarks.md from them, rerunning nothing.

    python -m benchmarks report [--out docs/benchmarks.md] [--check]
    python -m benchmarks report --demo demo-out --commit REV   (record a `make demo` run, then write)

Sources, all committed:

- ``benchmarks/foreign/fits.json``: each foreign case's latest recorded fit
  (``python -m benchmarks foreign_fit ... --record benchmarks/foreign/fits.json --code REV``),
  judged on each case's floor as its meta.json holds it today;
- ``benchmarks/results/*.json``: any other recorded table, one object per file:
  ``{"title": str, "command": str, "commit": str, "rows": [{column: value, ...}, ...]}``;

``--check`` writes nothing and exits 1 when the file differs from what would be written (a test
runs it, so the committed page is always the one these records make).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
RESULTS = HERE / "results"
OUT = ROOT / "docs" / "benchmarks.md"

#: Columns of the per-case table of the foreign fits: record key -> heading.
CASE_COLUMNS = {
    "case": "case",
    "code": "commit",
    "base": "base",
    "cf_base_mm": "base mm",
    "cf_graded_mm": "graded mm",
    "cf_final_mm": "fit mm",
    "floor_mm": "floor mm",
    "floor_fitted_mm": "material-fitted floor mm",
    "total_final_pct": "total area %",
    "area_final_pct": "panel area %",
    "phase2_kept": "phase two kept",
    "time_s": "time s",
}


def _median(v: list[float]) -> float:
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def _commit(code: str | None) -> str:
    """The commit a record names first (``cc747b9 (ran at ...)`` -> ``cc747b9``)."""
    return (code or "").split(" ")[0]


def _by_garment(rows: list[dict]) -> list[dict]:
    """Per garment type: the fitted cases, their Chamfer's median and worst [mm], how many are
    within their bar, and the total area error's median and worst [%]."""
    by = defaultdict(list)
    for r in rows:
        by[r.get("garment", "?")].append(r)
    summary = []
    for g in sorted(by):
        rs = [r for r in by[g] if r.get("cf_final_mm") is not None]
        cf = [r["cf_final_mm"] for r in rs]
        tot = [r["total_final_pct"] for r in rs if r.get("total_final_pct") is not None]
        within = sum(
            r.get("floor_mm") is not None and r["cf_final_mm"] <= max(5.0, 1.5 * r["floor_mm"]) for r in rs
        )
        summary.append(
            {
                "garment": g,
                "cases": len(rs),
                "fit mm median": _median(cf),
                "fit mm worst": max(cf),
                "within bar": f"{within} of {len(rs)}",
                "total area % median": _median(tot) if tot else None,
                "total area % worst": max(tot) if tot else None,
            }
        )
    return summary


def foreign_section(record: Path) -> list[str]:
    """The foreign benchmark's section: the bars, a table per garment type and one row per case."""
    from bench_foreign_fit import _read_record, bars, case_dirs
    from tables import markdown_table

    rec = _read_record(record)
    cases = case_dirs()
    rows = []
    for c in cases:
        if c.name not in rec:
            continue
        r = dict(rec[c.name])
        meta = json.loads((c / "meta.json").read_text())
        r["floor_mm"] = (meta.get("floor") or {}).get("chamfer_mm", r.get("floor_mm"))
        r["floor_fitted_mm"] = (meta.get("floor_fitted") or {}).get("chamfer_mm")
        r["code"] = _commit(r.get("code"))
        rows.append(r)
    missing = [c.name for c in cases if c.name not in rec]
    commits = sorted({r["code"] for r in rows if r["code"]})
    lines = [
        "## Foreign targets: garments unsew did not make",
        "",
        f"{len(rows)} of {len(cases)} cases in `benchmarks/foreign/cases` have a recorded fit"
        + (f" (none yet: {', '.join(missing)})" if missing else "")
        + ". A case is a GarmentCode-format design draped "
        "by NVIDIA newton on an anny or GarmentCode body; its floor is its true pattern draped by `unsew "
        "drape`, and its bar is max(5 mm, 1.5 x floor). Each row names the commit its fit ran on "
        f"({len(commits)} commits). Command: `python -m benchmarks foreign_fit --out OUT --cases ...`, then "
        "`--no-run --record benchmarks/foreign/fits.json --code REV`; `--latest "
        "benchmarks/foreign/fits.json` prints this table.",
        "",
        markdown_table(bars(rows), digits=1),
        "",
        "### Per garment type",
        "",
    ]
    lines += [
        markdown_table(_by_garment(rows), digits=1),
        "",
        "### Each case's latest recorded fit",
        "",
        markdown_table([{h: r.get(k) for k, h in CASE_COLUMNS.items()} for r in rows], digits=1),
        "",
    ]
    return lines


def _shown(p: Path) -> str:
    """``p`` relative to the repository when it lies in it."""
    try:
        return str(p.resolve().relative_to(ROOT))
    except ValueError:
        return str(p)


def results_sections(folder: Path) -> list[str]:
    """One section per recorded table in ``folder`` (``*.json``)."""
    from tables import markdown_table

    lines = []
    for p in sorted(folder.glob("*.json")):
        t = json.loads(p.read_text())
        missing = {"title", "command", "commit", "rows"} - set(t)
        if missing:
            raise ValueError(f"{p} is not a recorded table: no {', '.join(sorted(missing))}")
        lines += [
            f"## {t['title']}",
            "",
            f"Command: `{t['command']}` at {t['commit']} (`{_shown(p)}`).",
            "",
            markdown_table(t["rows"], digits=2),
            "",
        ]
    return lines


def demo_table(demo_out: Path, commit: str) -> dict:
    """The recorded table of a finished ``unsew demo`` run (its ``fit/metrics.json``): the base,
    graded and final garments' Chamfer [mm], normal error [deg], panel area error [%] and turning
    distance, and the re-drape on the wider body when the demo wrote it."""
    m = json.loads((Path(demo_out) / "fit" / "metrics.json").read_text())
    stages = {"base": "_base", "graded": "_graded", "final": ""}

    def row(name, get):
        return {"metric": name, **{k: get(suffix) for k, suffix in stages.items()}}

    def pat(suffix, key, scale=1.0):
        v = (m.get("pattern" + suffix) or {}).get(key)
        return None if v is None else round(scale * v, 3)

    rows = [
        row("Chamfer [mm]", lambda s: round(m["surface" + s]["chamfer_mm"], 3)),
        row("normal error [deg]", lambda s: round(m["surface" + s]["normal_error_deg"], 3)),
        row("panel area error [%]", lambda s: pat(s, "area_error_rel_mean", 100.0)),
        row("turning distance [rad]", lambda s: pat(s, "turning_distance_mean")),
    ]
    return {
        "title": "Demo: a known t-shirt fitted on the default body",
        "command": "make demo",
        "commit": commit,
        "rows": rows,
    }


def render(record: Path, results: Path = RESULTS) -> str:
    """The whole page (Markdown)."""
    lines = [
        "# Benchmarks: current figures",
        "",
        "Generated by `python -m benchmarks report` from the recorded results; edit those, not this page.",
        "Every figure names the command that measured it and the commit it ran on. Benchmarks print",
        "tables and never assert timings; `python -m benchmarks` lists them.",
        "",
    ]
    lines += foreign_section(record)
    lines += results_sections(results) if results.is_dir() else []
    lines += [
        "## Decisions behind the defaults",
        "",
        "The reasons for the defaults, each with its measurement and command: [docs/decisions](decisions/).",
    ]
    return "\n".join(lines).rstrip() + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=OUT, help="the page to write")
    ap.add_argument(
        "--record", type=Path, default=HERE / "foreign" / "fits.json", help="the foreign fits' record"
    )
    ap.add_argument("--results", type=Path, default=RESULTS, help="folder of other recorded tables")
    ap.add_argument(
        "--check", action="store_true", help="write nothing; exit 1 when --out is not what would be written"
    )
    ap.add_argument(
        "--demo",
        type=Path,
        help="a finished `unsew demo` folder: record its figures as results/demo.json first",
    )
    ap.add_argument("--commit", default="", help="with --demo: the commit the demo ran on")
    args = ap.parse_args(argv)
    if args.demo is not None:
        if not (args.demo / "fit" / "metrics.json").is_file() or not args.commit:
            print(
                f"report: --demo needs a finished demo folder ({args.demo}/fit/metrics.json) and --commit",
                file=sys.stderr,
            )
            return 2
        (args.results / "demo.json").write_text(
            json.dumps(demo_table(args.demo, args.commit), indent=1) + "\n"
        )
    if not args.record.is_file():
        print(f"report: no record at {args.record}", file=sys.stderr)
        return 2
    try:
        text = render(args.record, args.results)
    except ValueError as exc:
        print(f"report: {exc}", file=sys.stderr)
        return 2
    if args.check:
        same = args.out.is_file() and args.out.read_text() == text
        print(
            f"{args.out}: "
            f"{'up to date' if same else 'differs from the records; run python -m benchmarks report'}"
        )
        return 0 if same else 1
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text)
    print(f"wrote {args.out} ({text.count(chr(10))} lines)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
