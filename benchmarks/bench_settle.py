"""Is a fit's drape at rest? A pattern dressed as the fit dresses it, then let settle further.

For a case folder and a fit's result folder, dresses each named pattern of the result (default:
the graded and the base pattern) from scratch with the fit's drape settings in the result's
fitted material (``material.json``) or ``--material``,
then settles it ``--rounds`` more times by ``--steps`` steps each (:func:`unsew.dress.settle`,
restarting at rest), and prints after each round the garment's top and lowest height [m] and its
Chamfer to the target [mm], and the largest and the 99th-percentile vertex speed [m/s] at the end
of the dress (the largest only) and of each round. A drape whose figures still move after the
dress was not at rest when the fit measured it. The largest speed cannot tell: a few vertices in
contact keep near 0.02 m/s on drapes whose shape no longer changes; the 99th percentile can.

    python -m benchmarks settle CASE_DIR RESULT_DIR [--patterns pattern_graded.json ...]
        [--material NAME] [--rounds 5] [--steps 40]
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", type=Path)
    ap.add_argument("result", type=Path)
    ap.add_argument("--patterns", nargs="+", default=["pattern_graded.json", "pattern_base.json"])
    ap.add_argument("--material", default=None, help="library material (default: RESULT/material.json)")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--steps", type=int, default=40)
    args = ap.parse_args()

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress, resolve_material
    from unsew.fit.config import FitConfig
    from unsew.fit.target import Target
    from unsew.io.garmentcode import load_pattern
    from unsew.sim.drape import drape
    from unsew.sim.material import material_from_dict
    from unsew.sim.state import SimState

    case = load_case(args.case)
    sdf, target = BodySDF.build(case.body), Target.of_case(case)
    mat = resolve_material(args.material) if args.material else \
        material_from_dict(json.loads((args.result / "material.json").read_text()))
    settings = FitConfig().drape
    rows = []
    for name in args.patterns:
        d = dress(load_pattern(args.result / name), case.body, sdf=sdf, material=mat, settings=settings)
        x, faces = d.x, d.mesh.faces
        uv = torch.as_tensor(np.asarray(d.mesh.uv), dtype=torch.float64)
        vmax, v99 = d.stats["max_speed"], None
        for k in range(args.rounds + 1):
            if k:  # as unsew.dress.settle, keeping the state to read its speeds
                with torch.no_grad():
                    st = drape(d.model, SimState.at_rest(x), sdf, uv=uv, gamma=mat.gamma(), density=mat.density,
                               settings=settings, steps=args.steps, friction=mat.friction)
                x, v = st.x, st.v.norm(dim=1)
                vmax, v99 = float(v.max()), float(torch.quantile(v, 0.99))
            rows.append({"pattern": name, "steps_after_dress": k * args.steps,
                         "max_speed_m_s": vmax, "p99_speed_m_s": v99,
                         "top_m": float(x[:, 1].max()), "lowest_m": float(x[:, 1].min()),
                         "chamfer_mm": target.distance_mm(x.numpy(), faces)})
            print(rows[-1], flush=True)
    what = args.material or "fitted material"
    print_table(rows, title=f"{args.case.name}: the fit's drapes let settle further ({what})", digits=4)


if __name__ == "__main__":
    main()
