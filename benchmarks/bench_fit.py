"""Per-garment fit accuracy on known-truth cases.

For each garment type, a base pattern altered by known amounts (hem/sleeve/leg lengths and
widths) in a different material is draped by our simulator on the default body (the target,
about 2K vertices at --edge-length 0.02); the fit starts from the base pattern in cotton.
Prints, per garment: vertices, Chamfer [mm] and normal error [deg] of the base drape, the graded
drape and the final fit, mean panel area error [%] and turning distance of the base and the final
pattern, the recovered material, iterations, which pattern the re-dress check returned (graded
or phase two), the peak resident memory [MB] (metrics.json ``peak_memory_mb``: the process peak,
reset before each fit to what is resident then, so memory an earlier fit left allocated counts)
and time.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_fit.py [--garments tshirt pants ...]
        [--edge-length 0.02] [--iterations 100] [--out bench-out/fit] [--variants noise,decimate,cm]
        [--set KEY=VALUE ...]

--variants also fits the t-shirt target with 1 mm noise, decimated to half its vertices, given
in cm (read back with --units cm), on the default body posed with the left arm raised 25 degrees
(pose), and on a body 8% wider and deeper (body); the last two cases carry body.obj and
skeleton.json.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402


def _fit(case_dir: Path, out: Path, cfg, *, units=None):
    from unsew._memory import reset_peak
    from unsew.body.case import load_case
    from unsew.fit.run import run_fit

    case = load_case(case_dir, units=units)
    reset_peak()  # not the largest peak of the fits before it (what they left resident still counts)
    t = time.perf_counter()
    result, m = run_fit(case, cfg, out, overwrite=True, progress=False, log=lambda s: None)
    return result, m, time.perf_counter() - t


def _row(name, result, m, secs, nverts):
    s, sb, sg = m["surface"], m.get("surface_base", {}), m.get("surface_graded", {})
    p, pb = m.get("pattern", {}) or {}, m.get("pattern_base", {}) or {}
    mat = result.material
    return {
        "case": name,
        "verts": nverts,
        "cf_base_mm": sb.get("chamfer_mm"),
        "cf_graded_mm": sg.get("chamfer_mm"),
        "cf_final_mm": s["chamfer_mm"],
        "nrm_base_deg": sb.get("normal_error_deg"),
        "nrm_final_deg": s["normal_error_deg"],
        "area_base_pct": 100 * pb.get("area_error_rel_mean", float("nan")),
        "area_final_pct": 100 * p.get("area_error_rel_mean", float("nan")),
        "turn_base": pb.get("turning_distance_mean"),
        "turn_final": p.get("turning_distance_mean"),
        "H00": mat.h00,
        "H11": mat.h11,
        "H22": mat.h22,
        "k": mat.bend,
        "iters": result.iterations,
        "returned": _returned(m),
        "peak_mb": m.get("peak_memory_mb"),
        "time_s": secs,
    }


def _returned(m) -> str | None:
    """Which pattern the re-dress check returned: "graded" or "phase two" (None without the check)."""
    red = m.get("redress")
    if not red:
        return None
    return "phase two" if red.get("phase_two_kept") else "graded"


def _print(rows):
    cols = [
        ("case", 10, "s"),
        ("verts", 6, "d"),
        ("cf_base_mm", 8, ".2f"),
        ("cf_graded_mm", 8, ".2f"),
        ("cf_final_mm", 8, ".2f"),
        ("nrm_base_deg", 8, ".1f"),
        ("nrm_final_deg", 8, ".1f"),
        ("area_base_pct", 8, ".2f"),
        ("area_final_pct", 8, ".2f"),
        ("turn_final", 8, ".3f"),
        ("iters", 6, "d"),
        ("returned", 9, "s"),
        ("peak_mb", 7, ".0f"),
        ("time_s", 7, ".0f"),
    ]
    heads = [
        "case",
        "verts",
        "CF base",
        "CF grad",
        "CF fit",
        "N base",
        "N fit",
        "A base%",
        "A fit%",
        "turn",
        "iters",
        "returned",
        "peak MB",
        "time s",
    ]
    print(" ".join(f"{h:>{w}}" for h, (_, w, _) in zip(heads, cols)))
    for r in rows:
        out = []
        for k, w, f in cols:
            v = r.get(k)
            out.append(
                f"{'-':>{w}}" if v is None or (isinstance(v, float) and np.isnan(v)) else f"{v:>{w}{f}}"
            )
        print(" ".join(out))
    sys.stdout.flush()


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--garments", nargs="+", default=["tshirt", "dress", "pants", "shorts", "skirt"])
    ap.add_argument("--edge-length", type=float, default=0.02)
    ap.add_argument("--iterations", type=int, default=100)
    ap.add_argument("--out", default="bench-out/fit")
    ap.add_argument("--variants", default="", help="comma list of noise,decimate,cm,pose,body (t-shirt only)")
    ap.add_argument(
        "--off-library",
        action="store_true",
        help="drape each target in its fabric with every stiffness, density and friction moved "
        "at random (synthetic.off_library, seeded), so no library material is the truth",
    )
    ap.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a FitConfig option for every fit (repeatable)",
    )
    return ap.parse_args(argv)


def _n_verts(case: Path) -> int:
    return sum(1 for line in open(case / "target.obj") if line.startswith("v "))


def _garment_rows(args, out: Path, cfg, target_drape, rows: list) -> None:
    """Make each garment's synthetic case (off the library with --off-library), fit it, and
    append and print its row."""
    from unsew.fit.synthetic import make_truth_case

    for g in args.garments:
        alt = None
        if args.off_library:
            from dataclasses import replace

            from unsew.fit.synthetic import DEFAULT_ALTERATIONS, off_library

            alt = replace(DEFAULT_ALTERATIONS[g], material=off_library(DEFAULT_ALTERATIONS[g].material))
            print(f"{g}: true fabric {alt.as_dict()['material']}")
        case = make_truth_case(out / "cases" / g, garment=g, alteration=alt, settings=target_drape)
        nverts = _n_verts(case)
        result, m, secs = _fit(case, out / "results" / g, cfg)
        rows.append(_row(g, result, m, secs, nverts))
        _print(rows[-1:] if len(rows) > 1 else rows)


def _variant_target(var: str, base: Path, d: Path, v, f):
    """Copy the t-shirt case ``base`` to ``d`` with its target changed by ``var`` (noise,
    decimate, cm); returns the target's units for the fit (None: the case's)."""
    import shutil

    from unsew.io.mesh import write_obj

    if d.exists():
        shutil.rmtree(d)
    shutil.copytree(base, d)
    units = None
    if var == "noise":
        rng = np.random.default_rng(0)
        write_obj(d / "target.obj", v + rng.normal(scale=0.001, size=v.shape), f)
    elif var == "decimate":
        import trimesh  # quadric edge collapse (fast-simplification, in the test extra)

        m = trimesh.Trimesh(v, f, process=False).simplify_quadric_decimation(face_count=len(f) // 2)
        write_obj(d / "target.obj", m.vertices, m.faces)
    elif var == "cm":
        write_obj(d / "target.obj", v * 100.0, f)
        meta = json.loads((d / "meta.json").read_text())
        meta.pop("units", None)
        (d / "meta.json").write_text(json.dumps(meta))
        units = "cm"
    return units


def _variant_rows(variants, out: Path, cfg, target_drape, rows: list) -> None:
    """Fit the t-shirt case's variants (another pose or body, or a changed target) and append
    and print their rows."""
    from unsew.fit.synthetic import make_truth_case
    from unsew.io.mesh import read_mesh

    base = out / "cases" / "tshirt"
    if not base.is_dir():
        make_truth_case(base, garment="tshirt", settings=target_drape)
    v, f = read_mesh(base / "target.obj")
    for var in variants:
        d = out / "cases" / f"tshirt_{var}"
        units = None
        if var in ("pose", "body"):
            from unsew.body.body import default_body
            from unsew.body.pose import pose_body

            b = (
                pose_body(default_body(), "left_arm_up")
                if var == "pose"
                else default_body().transformed(scale=np.array([1.08, 1.0, 1.08]))
            )
            make_truth_case(d, garment="tshirt", body=b, body_meta=None, settings=target_drape)
        else:
            units = _variant_target(var, base, d, v, f)
        nverts = _n_verts(d)
        result, m, secs = _fit(d, out / "results" / f"tshirt_{var}", cfg, units=units)
        rows.append(_row(f"t-{var}", result, m, secs, nverts))
        _print(rows[-1:])


def main(argv=None):
    args = _parse(argv)

    import torch

    torch.set_num_threads(1)
    from unsew.fit.config import load_config
    from unsew.sim.drape import DrapeSettings

    out = Path(args.out)
    cfg = load_config(drape={"edge_length": args.edge_length}, optimizer={"iterations": args.iterations})
    # the targets' dressing (FitConfig's, not --set's)
    target_drape = DrapeSettings(edge_length=args.edge_length)
    if args.set:
        from run import apply_sets

        cfg = apply_sets(cfg, args.set)
        print("overrides: " + ", ".join(args.set))
    rows = []
    _garment_rows(args, out, cfg, target_drape, rows)
    variants = [v for v in args.variants.split(",") if v]
    if variants:
        _variant_rows(variants, out, cfg, target_drape, rows)
    print()
    print("all rows:")
    _print(rows)
    (out / "bench_fit.json").parent.mkdir(parents=True, exist_ok=True)
    (out / "bench_fit.json").write_text(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
