"""Does settling each candidate fabric from a drape choose the fit's start material as dressing it from scratch does, and how much faster?

For each case folder, runs phase one once (the automatic base choice and grading in cotton, as
``unsew fit`` does), then the automatic material choice (:func:`unsew.fit.material.choose_start`:
every library fabric, two re-gradings, two rounds of stiffness search) once per value of
``material.warm_steps``: 0 dresses every candidate from scratch (placement, 80 sewing and 40
settling steps: the fit before this benchmark), N > 0 lets it settle N steps from the drape it
competes with. One row per case and setting: the choice's time [s], the material chosen and the
Chamfer [mm] of phase two's start drape to the target; a second table gives every plain library
fabric's Chamfer [mm] on the cotton-graded pattern under each setting, side by side.

    python -m benchmarks material_warm [CASE_DIR ...] [--warm 0 40]

Default cases: three foreign cases (benchmarks/foreign/cases), a pair of shorts, a skirt and a tee.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_CASES = [ROOT / "benchmarks" / "foreign" / "cases" / c
                 for c in ("shorts_short__default", "skirt_aline_knee__default", "tee_fitted_short__default")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", type=Path, default=DEFAULT_CASES)
    ap.add_argument("--warm", nargs="+", type=int, default=[0, 40], help="material.warm_steps values to compare")
    args = ap.parse_args()

    import dataclasses

    import torch

    torch.set_num_threads(1)
    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import resolve_material
    from unsew.fit.config import FitConfig
    from unsew.fit.material import AUTO_START_MATERIAL, choose_start
    from unsew.fit.progress import Progress
    from unsew.fit.start import choose_base, start
    from unsew.fit.target import Target

    cfg0 = FitConfig()
    quiet = Progress(False)
    rows, fabrics = [], []
    for case_dir in args.cases:
        case = load_case(case_dir)
        sdf, target = BodySDF.build(case.body), Target.of_case(case, seed=cfg0.seed)
        cotton = resolve_material(AUTO_START_MATERIAL)
        base = choose_base(case, target, sdf, cfg0, cotton, progress=quiet, log=lambda s: None)
        first = start(base.pattern, case.body, target, sdf, cfg0, cotton, progress=quiet, garment=base.name)
        per_fabric = {}
        for w in args.warm:
            cfg = cfg0.replace(material=dataclasses.replace(cfg0.material, warm_steps=w))
            t0 = time.perf_counter()
            ch = choose_start(first, case.body, target, sdf, cfg, progress=quiet, log=lambda s: None,
                              garment=base.name)
            sec = time.perf_counter() - t0
            r0 = ch.table[0]
            rows.append({"case": case_dir.name, "warm_steps": w, "choice_s": sec, "material": r0["material"],
                         "pattern": r0["pattern"], "start_chamfer_mm": r0["chamfer_mm"]})
            print_table(rows[-1:])
            for r in ch.table:
                if "(" not in r["material"] and r["pattern"] == f"graded in {AUTO_START_MATERIAL}":
                    per_fabric.setdefault(r["material"], {})[w] = r["chamfer_mm"]
        for name, by_w in sorted(per_fabric.items()):
            fabrics.append({"case": case_dir.name, "fabric": name, **{f"warm {w}": by_w.get(w) for w in args.warm}})
    print("\nThe choice (time, material, phase two's start):")
    print_table(rows)
    print("\nEach fabric's Chamfer [mm] on the cotton-graded pattern:")
    print_table(fabrics)


if __name__ == "__main__":
    main()
