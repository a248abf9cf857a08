"""How much of a fit's remaining 3D error is the fabric: the *true* pattern of a known-truth case
draped on the case's body in the fit's starting material and in the target's own material.

For each case folder (FORMATS.md, with pattern_gt.json and meta.json's truth.material, as
benchmarks/make_cases.py writes them), the true pattern is dressed with the fit's settings
(FitConfig: sew and settle steps, dt) at ``--edge-length`` in: the start material (cotton), the
start material with the target's friction, the target's material, and the target's stiffness with
the start's friction; the Chamfer distance [mm] of each drape to the target is printed. If the
true pattern in the start material is far from the target while in the true material it is
close, a fit that cannot recover the material cannot reach the target with the right pattern.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_fabric_gap.py CASE_DIR [CASE_DIR ...]
     [--edge-length 0.025] [--start cotton]
"""

from __future__ import annotations

import argparse
import dataclasses
import os

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--start", default="cotton", help="the fit's starting material")
    ap.add_argument("--samples", type=int, default=20000)
    args = ap.parse_args()
    from unsew.sim.material import MATERIALS

    if args.start not in MATERIALS:
        ap.error(f"--start {args.start!r}: not a library material ({', '.join(MATERIALS)})")
    from truth_cases import check_case_dirs, truth_cases

    check_case_dirs(ap, args.cases)
    import torch

    torch.set_num_threads(1)
    from unsew.dress import dress
    from unsew.fit.config import FitConfig
    from unsew.metrics.surface import chamfer_mm

    cfg = FitConfig()
    print(f"{'case':<12} {'truth fabric':<12} {'drape of the true pattern in':<40} {'Chamfer mm':>10}")
    for name, case, truth, sdf, tv, tf in truth_cases(args.cases):
        start, true = MATERIALS[args.start], MATERIALS[truth]
        variants = [
            (f"{args.start} (the fit's start)", start),
            (f"{args.start} with {truth}'s friction", dataclasses.replace(start, friction=true.friction)),
            (f"{truth} (the target's)", true),
            (f"{truth} with {args.start}'s friction", dataclasses.replace(true, friction=start.friction)),
        ]
        for label, mat in variants:
            dr = dress(case.pattern_gt, case.body, sdf=sdf, material=mat,
                       settings=cfg.drape.replace(edge_length=args.edge_length))
            cf = chamfer_mm(dr.x.numpy(), dr.mesh.faces, tv, tf, n_samples=args.samples).mean_mm
            print(f"{name:<12} {truth:<12} {label:<40} {cf:>10.2f}", flush=True)


if __name__ == "__main__":
    main()
