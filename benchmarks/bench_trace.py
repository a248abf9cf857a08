"""Trace phase two of one fit, iteration by iteration: where does the pattern go, and what does the
drape gain for it?

Fits one known-truth case folder (FORMATS.md, with pattern_gt.json) with FitConfig's defaults,
changed by ``--set KEY=VALUE``, and records the control points and the drape of every
iteration of phase two. Prints per iteration: the loss, the Chamfer distance [mm] of that
iteration's (warm-started) drape to the target, and the mean panel area error [%] and mean
vertex L2 [cm] of that iteration's pattern against the true one. ``--json`` writes the rows.

A frozen pattern (``--set pattern_start=1000 material_params=``) shows how far the drape
moves by itself over the iterations (creep); the default shows how far the pattern moves for
what the drape gains.

``--redress-every N`` also dresses every N-th iterate (and the best) from scratch, as the fit's
re-dress check does with the best one, and prints how far that fresh drape lies from the target.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_trace.py CASE_DIR [--set KEY=VALUE ...]
     [--json rows.json] [--redress-every N]
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE", help="FitConfig overrides (YAML values)")
    ap.add_argument("--json", default=None, help="write the per-iteration rows here")
    ap.add_argument("--samples", type=int, default=20000)
    ap.add_argument("--redress-every", type=int, default=0, metavar="N",
                    help="also dress every N-th iterate's pattern (in that iteration's material) from scratch "
                         "on the fit's mesh and print its Chamfer [mm] (0: off)")
    args = ap.parse_args()
    if not (Path(args.case) / "pattern_gt.json").is_file():
        ap.error(f"{args.case}: not a known-truth case folder (no pattern_gt.json)")
    import yaml

    sets = {}
    for kv in args.set:
        if "=" not in kv:
            ap.error(f"--set {kv!r}: expected KEY=VALUE")
        k, v = kv.split("=", 1)
        sets[k] = yaml.safe_load(v)

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from unsew.errors import InputError
    from unsew.fit.config import load_config
    from unsew.fit.fit import fit
    from unsew.body.case import load_case
    from unsew.metrics.panels import pattern_metrics
    from unsew.metrics.surface import chamfer_mm

    try:
        case = load_case(args.case)
        cfg = load_config(None, report=False, **sets)
    except InputError as exc:
        raise SystemExit(f"bench_trace: {exc}") from None

    # Record every iteration of phase two through the fit's per-iteration callback: the control
    # points it draped, its material and its (warm-started) drape.
    xs, Ks, gammas = [], [], []

    def record(info):
        xs.append(info.x.cpu().clone())
        Ks.append(info.K.cpu().clone())
        gammas.append(info.gamma.cpu().clone())

    res = fit(case, cfg, progress=False, log=lambda s: None, callback=record)

    tv, tf = np.asarray(case.target_verts), np.asarray(case.target_faces)
    rows = []
    n = args.redress_every
    sdf = None
    if n > 0:
        from unsew.body.sdf import BodySDF

        sdf = BodySDF.build(case.body)
    print(f"{'it':>3} {'loss':>10} {'Chamfer mm':>10} {'area %':>7} {'vertex L2 cm':>12}"
          + (f" {'re-dressed mm':>13}" if n > 0 else ""))
    for i, (K, x) in enumerate(zip(Ks, xs)):
        pattern = res.params.to_pattern(K)
        pm = pattern_metrics(pattern, case.pattern_gt)
        cf = chamfer_mm(x.numpy(), res.mesh.faces, tv, tf, n_samples=args.samples).mean_mm
        row = {"it": i, "loss": res.history["total"][i], "chamfer_mm": cf,
               "area_pct": 100 * pm["area_error_rel_mean"], "vertex_l2_cm": pm.get("vertex_l2_cm_mean")}
        if n > 0 and (i % n == 0 or i == res.best_iteration):
            row["redressed_mm"] = _redress(res, case, cfg, sdf, pattern, K, gammas[i], tv, tf, args.samples)
        rows.append(row)
        print(f"{i:>3d} {row['loss']:>10.4e} {cf:>10.2f} {row['area_pct']:>7.2f} {row['vertex_l2_cm']:>12.2f}"
              + (f" {row['redressed_mm']:>13.2f}" if "redressed_mm" in row else ""), flush=True)
    rd = res.redress.as_dict() if res.redress is not None else None
    start = (res.material_choice or [{"material": cfg.material.start}])[0]["material"]
    print(f"best iteration {res.best_iteration}; start material {start}"
          + (f"; re-dress refused ({rd['refused']}), graded returned" if rd and rd.get("refused") else
             f"; re-dressed, it failed ({rd['failed']}), graded returned" if rd and rd.get("failed") else
             f"; re-dress {rd['fit_redressed_mm']:.2f} mm against graded {rd['graded_mm']:.2f} mm, "
             f"{'fit kept' if rd['phase_two_kept'] else 'graded returned'}" if rd else ""))
    if args.json:
        Path(args.json).write_text(json.dumps({"case": str(args.case), "set": sets, "rows": rows,
                                               "best_iteration": res.best_iteration, "redress": rd}, indent=1))


def _redress(res, case, cfg, sdf, pattern, K, gamma, tv, tf, samples) -> float:
    """Chamfer [mm] to the target of ``pattern`` (control points K) in the material ``gamma``
    (with the start material's density and friction), dressed from scratch on the fit's mesh, as
    the fit's re-dress check does."""
    from unsew.dress import dress
    from unsew.grading.grade import moved_mesh
    from unsew.metrics.surface import chamfer_mm
    from unsew.sim.material import Material

    m0 = res.start_material
    g = [float(v) for v in gamma]
    mat = Material(g[0], g[1], g[2], g[3], g[4], m0.density, m0.friction)
    uv = res.params.uv(K).detach().cpu().numpy()
    x = dress(pattern, case.body, sdf=sdf, mesh=moved_mesh(res.mesh, pattern, uv), material=mat,
              settings=cfg.drape).x.numpy()
    return chamfer_mm(x, res.mesh.faces, tv, tf, n_samples=samples).mean_mm


if __name__ == "__main__":
    main()
