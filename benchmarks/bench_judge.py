"""Is phase two's pattern better than the graded one on one fresh drape, and on three?

Reads ``python -m benchmarks foreign_fit --out DIR`` result folders of the default fit
(``checks.redress_meshes: 3``: both patterns dressed from scratch on the fit's mesh and the mesh
spread's two; metrics.json's ``redress``) and prints per case:

- ``one_mesh``: what the one-mesh check (``checks.redress_meshes: 1``, the default before session
  25: phase two's pattern dressed from scratch on the fit's mesh against the graded start drape)
  would have decided, and its two figures [mm];
- ``start_mm`` / ``graded_fresh_mm``: the graded start drape (let settle from another material's
  drape during the material choice, and kept for being closest) and the graded pattern dressed
  from scratch on the same mesh [mm]: how much the start drape's selection flatters the graded
  pattern;
- ``fit_mm`` / ``graded_mm``: each pattern's three fresh drapes (the fit's mesh, 4 % finer,
  4 % coarser) and ``fit_mean`` / ``graded_mean`` [mm];
- ``three_mesh``: the three-mesh verdict, and whether the two verdicts agree;
- ``lower_on``: on how many of the three meshes phase two's drape lies below the graded one's.

    python -m benchmarks judge DIR [DIR ...]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from tables import print_table

from unsew.fit.checks import REDRESS_MARGIN_MM, mm_list

COLUMNS = ["case", "one_mesh", "start_mm", "graded_fresh_mm", "fit_mm", "graded_mm", "fit_mean", "graded_mean",
           "lower_on", "three_mesh", "agree"]


def row(name: str, red: dict) -> dict:
    """One case's row from metrics.json's ``redress`` (judged on three meshes)."""
    one = red["fit_redressed_mm"] < red["graded_mm"] - REDRESS_MARGIN_MM
    fit, graded = red["fit_mm"], red["graded_fresh_mm"]
    pairs = [(a, b) for a, b in zip(fit, graded) if a is not None and b is not None]
    return {"case": name, "one_mesh": f"{'kept' if one else 'graded'} ({red['fit_redressed_mm']:.1f} vs {red['graded_mm']:.1f})",
            "start_mm": red["graded_mm"], "graded_fresh_mm": graded[0], "fit_mm": mm_list(fit, 1), "graded_mm": mm_list(graded, 1),
            "fit_mean": red["fit_mean_mm"], "graded_mean": red["graded_mean_mm"],
            "lower_on": f"{sum(a < b for a, b in pairs)}/{len(pairs)}",
            "three_mesh": "kept" if red["phase_two_kept"] else "graded", "agree": "yes" if one == red["phase_two_kept"] else "no"}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="+", type=Path, help="foreign_fit --out folders of fits with checks.redress_meshes 3")
    args = ap.parse_args(argv)
    rows, other = [], []
    for d in args.dirs:
        for m in sorted(d.glob("*/metrics.json")):
            red = json.loads(m.read_text()).get("redress")
            if red and red.get("meshes") == 3:
                rows.append(row(m.parent.name, red))
            else:
                other.append(m.parent.name)  # judged on one mesh (the time limit) or phase two never ran
    print_table(rows, COLUMNS, title=f"Phase two judged on one and on three fresh drapes ({', '.join(map(str, args.dirs))})",
                digits=1)
    if rows:
        kept1 = sum(r["one_mesh"].startswith("kept") for r in rows)
        kept3 = sum(r["three_mesh"] == "kept" for r in rows)
        bias = [r["graded_fresh_mm"] - r["start_mm"] for r in rows if r["graded_fresh_mm"] is not None]
        print(f"\nkept on one mesh {kept1} of {len(rows)}, on three {kept3}; verdicts differ on "
              f"{sum(r['agree'] == 'no' for r in rows)}; the graded pattern dressed afresh lies "
              f"{sorted(bias)[len(bias) // 2]:+.2f} mm (median) from its start drape's distance")
    if other:
        print(f"not judged on three meshes: {', '.join(other)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
