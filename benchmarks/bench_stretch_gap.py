"""Is stretch stiffness observable in a drape? The material table's skirt (benchmarks/run.py:
base skirt with hem (0.04, 0.08), jersey) draped with its stretch entries (H00, H01, H11, H22)
scaled by each factor; prints the lowest point of each drape and the Chamfer [mm] between every
pair of drapes. If two stiffnesses drape alike, no fit can tell them apart.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_stretch_gap.py [--factors 0.1,0.5,1,2]
        [--edge-length 0.025] [--out bench-out/stretch-gap]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
sys.path.insert(0, str(Path(__file__).resolve().parent))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--factors", default="0.1,0.5,1,2")
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--out", default="bench-out/stretch-gap")
    args = ap.parse_args(argv)

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from run import MATERIAL_BASE, MATERIAL_SKIRT

    from unsew.fit.synthetic import Alteration, make_truth_case
    from unsew.sim.drape import DrapeSettings
    from unsew.io.mesh import read_mesh
    from unsew.metrics.surface import surface_metrics
    from unsew.sim.material import get_material

    base = get_material(MATERIAL_BASE)
    factors = [float(f) for f in args.factors.split(",")]
    drapes = {}
    print(f"{'stretch':>8} {'H00 N/m':>8} {'lowest y m':>10} {'time s':>7}")
    for f in factors:
        mat = dataclasses.replace(base, **{k: getattr(base, k) * f for k in ("h00", "h01", "h11", "h22")})
        t = time.perf_counter()
        d = make_truth_case(Path(args.out) / f"skirt_stretch_x{f:g}", garment="skirt",
                            alteration=Alteration(MATERIAL_SKIRT, mat),
                            settings=DrapeSettings(edge_length=args.edge_length))
        drapes[f] = read_mesh(d / "target.obj")
        print(f"{'x%g' % f:>8} {mat.h00:>8.0f} {np.asarray(drapes[f][0])[:, 1].min():>10.4f} "
              f"{time.perf_counter() - t:>7.0f}", flush=True)
    print("\nChamfer between drapes [mm]")
    for i, a in enumerate(factors):
        for b in factors[i + 1:]:
            m = surface_metrics(*drapes[a], *drapes[b])
            print(f"  x{a:g} vs x{b:g}: {m['chamfer_mm']:.2f}")


if __name__ == "__main__":
    main()
