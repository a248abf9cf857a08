"""Is a fit's result simulation-ready? Its pattern and material, dressed again from scratch.

A fit reports the Chamfer distance of the drape it ended on: a state its warm-started,
differentiable drapes reached over many iterations. A user who takes pattern.json and
material.json and dresses the garment again gets a fresh drape (place, sew, settle with the
fit's settings, as the known-truth targets were made). For each (case folder, result folder)
pair this prints the reported Chamfer [mm] and that of the fresh drape to the same target.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_redrape.py CASE_DIR RESULT_DIR
     [CASE_DIR RESULT_DIR ...] [--edge-length 0.025] [--samples 20000]

e.g. after ``bench_fit.py --edge-length 0.025 --out bench-out/fit``:
     benchmarks/bench_redrape.py bench-out/fit/cases/skirt bench-out/fit/results/skirt ...
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pairs", nargs="+", help="CASE_DIR RESULT_DIR, repeated")
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--samples", type=int, default=20000)
    args = ap.parse_args()
    if len(args.pairs) % 2:
        ap.error("give CASE_DIR RESULT_DIR pairs")
    pairs = [(Path(a), Path(b)) for a, b in zip(args.pairs[::2], args.pairs[1::2])]
    for case_dir, res in pairs:
        if not (case_dir / "meta.json").is_file():
            ap.error(f"{case_dir}: not a case folder (no meta.json)")
        for f in ("pattern.json", "material.json", "metrics.json"):
            if not (res / f).is_file():
                ap.error(f"{res}: not a finished result folder (no {f})")

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from unsew.dress import dress
    from unsew.errors import InputError
    from unsew.fit.config import FitConfig
    from unsew.body.case import load_case
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.surface import chamfer_mm
    from unsew.sim.material import material_from_dict

    cfg = FitConfig()
    print(f"{'case':<14} {'result':<40} {'reported mm':>11} {'re-dressed mm':>13}")
    for case_dir, res in pairs:
        try:
            case = load_case(case_dir)
            pattern = load_pattern(res / "pattern.json")
        except InputError as exc:
            raise SystemExit(f"{case_dir} / {res}: {exc}") from None
        try:
            mat = material_from_dict(json.loads((res / "material.json").read_text()))
        except (InputError, ValueError) as exc:
            raise SystemExit(f"{res}/material.json: {exc}") from None
        reported = json.loads((res / "metrics.json").read_text())["surface"]["chamfer_mm"]
        d = dress(pattern, case.body, material=mat, settings=cfg.drape.replace(edge_length=args.edge_length))
        x = d.x.detach().cpu().numpy().astype(np.float64)
        tv, tf = np.asarray(case.target_verts), np.asarray(case.target_faces)
        cf = chamfer_mm(x, d.mesh.faces, tv, tf, n_samples=args.samples).mean_mm
        print(f"{case_dir.name:<14} {str(res)[-40:]:<40} {reported:>11.2f} {cf:>13.2f}", flush=True)


if __name__ == "__main__":
    main()
