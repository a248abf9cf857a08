"""Does a target's surface area tell its true pattern's total area?

Cloth barely stretches, so a draped garment's surface area should be its pattern's area. For
every case of benchmarks/foreign/cases this prints the target's surface area (the summed area of
target.obj's triangles) against the true pattern's total panel area (pattern_gt.json), and, for
the cases fitted in the given ``foreign_fit`` result folders (the first folder holding the case
wins), the total area error of the fit's graded and final patterns and how far the fit's own
drape (garment.obj) is from its pattern's area: whether a term pulling the pattern's area
towards the target's (``loss.area``, unsew.losses.area) has a signal to follow.

    python -m benchmarks area_signal [--results OUT [OUT ...]] [--cases a,b]
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"
COLUMNS = ["case", "target_area_m2", "true_area_m2", "target_vs_true_pct", "graded_pct", "final_pct", "drape_vs_pattern_pct"]


def _mesh_area(path: Path) -> float:
    """Summed triangle area [m^2] of an OBJ."""
    from unsew.geometry.repair import triangle_areas
    from unsew.io.mesh import read_mesh

    v, f = read_mesh(path)[:2]
    return float(triangle_areas(v, f).sum())


def _pattern_area(path: Path) -> float:
    """Total panel area [m^2] of a pattern file."""
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import panel_area

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's clockwise panels: reoriented, said elsewhere
        return sum(panel_area(p) for p in load_pattern(path).panels.values())


def row(case: Path, results: list[Path]) -> dict:
    """One case's areas; the fit's columns when a result folder holds it."""
    t, gt = _mesh_area(case / "target.obj"), _pattern_area(case / "pattern_gt.json")
    r = {"case": case.name, "target_area_m2": t, "true_area_m2": gt, "target_vs_true_pct": 100 * (t / gt - 1)}
    res = next((d / case.name for d in results if (d / case.name / "pattern.json").is_file()), None)
    if res is not None:
        fin = _pattern_area(res / "pattern.json")
        r["graded_pct"] = 100 * (_pattern_area(res / "pattern_graded.json") / gt - 1)
        r["final_pct"] = 100 * (fin / gt - 1)
        r["drape_vs_pattern_pct"] = 100 * (_mesh_area(res / "garment.obj") / fin - 1)
    return r


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--results", nargs="*", type=Path, default=[], help="foreign_fit result folders")
    ap.add_argument("--cases", default="", help="comma-separated case names (default: all)")
    args = ap.parse_args(argv)
    names = [n for n in args.cases.split(",") if n]
    cases = sorted(p for p in CASES.iterdir() if (p / "target.obj").is_file() and (not names or p.name in names))
    if not cases:
        print(f"area_signal: no case folder in {CASES} matches {args.cases!r}")
        return 1
    rows = [row(c, args.results) for c in cases]
    from tables import print_table

    print_table(rows, COLUMNS, title="Target surface area against the true pattern's area (and the fit's)", digits=2)
    summary = []
    for col in COLUMNS[3:]:
        v = np.abs([r[col] for r in rows if r.get(col) is not None])
        if len(v):
            summary.append({"column": col, "cases": len(v), "median_abs_pct": float(np.median(v)), "max_abs_pct": float(v.max())})
    print_table(summary, title="Absolute differences [%]", digits=2)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
