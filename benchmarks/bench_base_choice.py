"""How noisy is the fit's automatic base choice between bases with and without a waistband?

For each case folder, runs :func:`unsew.fit.start.choose_base` (every library base of the case's
garment type dressed from scratch in cotton on a coarse mesh, its Chamfer to the target) at three
nearby candidate mesh edges (default 3.8, 4.0 and 4.2 cm; the fit uses 4.0) and prints one row per
case and edge: each base's Chamfer [mm], for dresses also over the torso, which the choice is made
on (``<base> torso``; :data:`unsew.fit.start.TORSO_CHOICE`), whether its openings on the arms are
the target's (a sleeveless base for a sleeved target: no; :func:`unsew.fit.start.arm_openings`)
and the base chosen. A second table gives
each base's mean and spread (largest - smallest Chamfer over the edges) [mm].

    python -m benchmarks base_choice [CASE_DIR ...] [--edges 0.038 0.04 0.042]

Default cases: the foreign straight trousers and knee shorts on the default body. The project's own
per-garment cases are written by ``python -m benchmarks fit --out DIR`` under ``DIR/cases``.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_CASES = [ROOT / "benchmarks" / "foreign" / "cases" / c
                 for c in ("trousers_straight__default", "shorts_knee__default")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", type=Path, default=DEFAULT_CASES)
    ap.add_argument("--edges", nargs="+", type=float, default=[0.038, 0.04, 0.042],
                    help="candidate mesh edge lengths [m]")
    args = ap.parse_args()

    import torch

    torch.set_num_threads(1)
    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import resolve_material
    from unsew.fit.config import FitConfig
    from unsew.fit.material import AUTO_START_MATERIAL
    from unsew.fit.progress import Progress
    from unsew.fit.start import choose_base
    from unsew.fit.target import Target
    from unsew.pattern.base import bases_for, garment_of

    cfg0 = FitConfig()
    rows, spread = [], []
    for case_dir in args.cases:
        case = load_case(case_dir)
        sdf, target = BodySDF.build(case.body), Target.of_case(case)
        names = bases_for(garment_of(case.garment))
        seen = {n: [] for n in names}
        for e in args.edges:
            t0 = time.perf_counter()
            bc = choose_base(case, target, sdf, cfg0.replace(base_choice_edge=e),
                             resolve_material(AUTO_START_MATERIAL), progress=Progress(False), log=lambda s: None)
            row = {"case": case_dir.name, "edge_cm": e * 100}
            for r in bc.table:
                row[r["base"]] = r["chamfer_mm"]
                if "torso_mm" in r:
                    row[f"{r['base']} torso"] = r["torso_mm"]
                row[f"{r['base']} arms"] = r.get("arms")  # its openings on the arms are the target's
                if r["chamfer_mm"] is not None:
                    seen[r["base"]].append(r["chamfer_mm"])
            row.update(chosen=bc.name, time_s=time.perf_counter() - t0)
            rows.append(row)
            print(row, flush=True)
        for n, v in seen.items():
            spread.append({"case": case_dir.name, "base": n, "mean_mm": sum(v) / len(v) if v else None,
                           "min_mm": min(v) if v else None, "max_mm": max(v) if v else None,
                           "spread_mm": (max(v) - min(v)) if v else None})
    bases = [b for b in dict.fromkeys(k for r in rows for k in r) if b not in ("case", "edge_cm", "chosen", "time_s")]
    print_table(rows, ["case", "edge_cm", *bases, "chosen", "time_s"],
                title="base choice at nearby candidate edges (Chamfer mm, cotton)")
    print_table(spread, title="spread of each base's Chamfer over the edges [mm]")


if __name__ == "__main__":
    main()
