"""Is a fit closer to its target than its base pattern, judged over three triangulations?

A single drape of a wide skirt moves by more than the fit changes it (metrics.json's mesh_spread:
the half-circle skirt's result lies 39.2 / 42.0 / 47.4 mm from its target on meshes 4 % finer and
coarser), so "better than the base" on one drape of each is a coin flip there. For every result
folder of ``python -m benchmarks foreign_fit --out OUT``, this dresses the base pattern
(``pattern_base.json``, in the fit's start material) from scratch with the fit's drape settings on
the three meshes the fit's mesh spread used for the result (edge length x (1 - s), x 1, x (1 + s)),
measures each drape's distance to the target as the fit measures it (``Target.distance_mm``), and
prints it beside the result's three (``mesh_spread.chamfer_mm``, and on the fit's mesh the
re-dress check's drape from scratch when phase two was kept, else the graded drape): their means,
and whether the result's mean is lower; with the single-drape comparison of foreign_fit's table.

    python -m benchmarks base_spread --out OUT [--cases a,b]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"

COLUMNS = ["case", "base", "base_mm", "base_mean_mm", "result_mm", "result_mean_mm", "lower_mean",
           "cf_base_mm", "cf_final_mm", "lower_single", "time_s"]


def base_spread(case_dir: Path, res: Path) -> dict:
    """The base pattern's three drapes and the result's three distances [mm] of one fitted case."""
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.errors import PatternError, SimulationError
    from unsew.fit.config import load_config
    from unsew.fit.material import AUTO_START_MATERIAL
    from unsew.fit.target import Target
    from unsew.io.garmentcode import load_pattern

    t0 = time.perf_counter()
    m = json.loads((res / "metrics.json").read_text())
    spread = m.get("mesh_spread")
    if not spread or None in spread["chamfer_mm"]:
        return {"case": case_dir.name, "base": m.get("base"), "base_mm": "no mesh spread in the result"}
    cfg = load_config(res / "config.yaml")
    case = load_case(case_dir)
    target = Target.of_case(case, seed=cfg.seed)
    sdf = BodySDF.build(case.body)
    material = AUTO_START_MATERIAL if cfg.material.start == "auto" else cfg.material.start
    pattern = load_pattern(res / "pattern_base.json")
    lo, hi = spread["edge_lengths_m"]
    base = []
    for h in (lo, cfg.drape.edge_length, hi):
        try:
            d = dress(pattern, case.body, sdf=sdf, material=material, settings=cfg.drape.replace(edge_length=h))
            base.append(target.distance_mm(d.x.numpy(), d.mesh.faces))
        except (SimulationError, PatternError):
            base.append(None)
    red = m.get("redress") or {}
    # the result on the fit's own mesh dressed from scratch, as the base is: phase two's drape is
    # warm-started along the optimisation's path, so its re-dress stands in for it when kept
    mid = red["fit_redressed_mm"] if red.get("phase_two_kept") else spread["result_mm"]
    result = [spread["chamfer_mm"][0], mid, spread["chamfer_mm"][1]]
    ok = [v for v in base if v is not None]
    if not ok:
        return {"case": case_dir.name, "base": m.get("base"), "base_mm": "every base drape failed"}
    bm, rm = sum(ok) / len(ok), sum(result) / 3
    cfb, cff = m["surface_base"]["chamfer_mm"], m["surface"]["chamfer_mm"]
    return {"case": case_dir.name, "base": m.get("base"),
            "base_mm": " / ".join("failed" if v is None else f"{v:.1f}" for v in base), "base_mean_mm": bm,
            "result_mm": " / ".join(f"{v:.1f}" for v in result), "result_mean_mm": rm,
            "lower_mean": "yes" if rm < bm else "no", "cf_base_mm": cfb, "cf_final_mm": cff,
            "lower_single": "yes" if cff < cfb else "no", "time_s": time.perf_counter() - t0}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="a foreign_fit results folder")
    ap.add_argument("--cases", default="", help="comma-separated case names (default: every fitted case)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    names = [n for n in args.cases.split(",") if n] or sorted(
        p.parent.name for p in out.glob("*/metrics.json") if (CASES / p.parent.name).is_dir())
    if not names:
        print(f"no fitted case in {out}")
        return 1
    from tables import print_table

    rows = []
    for n in names:
        if not (out / n / "metrics.json").is_file():
            rows.append({"case": n, "base_mm": "not fitted"})
            continue
        rows.append(base_spread(CASES / n, out / n))
        print(f"{n}: base {rows[-1]['base_mm']} mm, result {rows[-1].get('result_mm')} mm", flush=True)
    print_table(rows, COLUMNS, title=f"Base against result over three triangulations ({out})", digits=1)
    done = [r for r in rows if "lower_mean" in r]
    print(f"\nresult lower than the base: {sum(r['lower_mean'] == 'yes' for r in done)} of {len(done)} "
          f"on the three-mesh mean, {sum(r['lower_single'] == 'yes' for r in done)} of {len(done)} on one drape")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
