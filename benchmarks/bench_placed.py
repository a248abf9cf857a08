"""Where does a pattern's drape sit, placed higher, narrowed or dressed with other settings?

Dresses PATTERN.json (GarmentCode JSON, e.g. a fit's pattern_graded.json or `unsew grade`'s
pattern.json) on a case's body from scratch (unsew.dress.dress) once per variant, and prints each
drape's Chamfer to the case's target [mm] (20,000 samples, seed 0), the heights of its highest
and lowest point beside the target's [m], and its last speed [m/s]. Variants: ``--lift CM`` (every
panel placed that much higher, unsew.grading.placement.lifted), ``--narrow F`` (every panel's
width scaled by F about its own vertical axis), ``--set KEY=VALUE`` (a DrapeSettings field, e.g.
friction_eps=0.001 or hold_steps=80), ``--inflate MM`` (the body's contact grown outward by MM,
unsew.body.sdf.BodySDF.inflated: cloth kept that much farther from the body). Measured with it:
docs/benchmarks.md, "A lower garment placed at the target's waist" and "The cloth's gap to the
body".

    python -m benchmarks placed CASE_DIR PATTERN.json [--material cotton] [--lift CM ...]
        [--narrow F ...] [--set KEY=VALUE ...] [--inflate MM ...]
"""

from __future__ import annotations

import argparse
import os
import sys

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _extent(x) -> tuple[float, float]:
    """Heights [m] of the highest and the lowest point of a drape or target (N, 3) [m]."""
    import numpy as np

    y = np.asarray(x)[:, 1]
    return float(y.max()), float(y.min())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("pattern")
    ap.add_argument("--material", default="cotton")
    ap.add_argument("--lift", type=float, nargs="*", default=[], metavar="CM")
    ap.add_argument("--narrow", type=float, nargs="*", default=[], metavar="F")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    ap.add_argument("--inflate", type=float, nargs="*", default=[], metavar="MM")
    args = ap.parse_args()

    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, dress
    from unsew.errors import UnsewError
    from unsew.fit.target import Target
    from unsew.grading.placement import lifted
    from unsew.io.garmentcode import load_pattern

    try:
        case, pattern = load_case(args.case), load_pattern(args.pattern)
        sets = {}
        for kv in args.set:
            k, v = kv.split("=", 1)
            if not hasattr(DRESS_SETTINGS, k):
                raise UnsewError(f"--set {k}: no such drape setting")
            sets[k] = type(getattr(DRESS_SETTINGS, k))(v)
        bad = [mm for mm in args.inflate if not mm >= 0]
        if bad:
            raise UnsewError(f"--inflate {bad[0]:g}: a body grows outward by 0 mm or more")
    except (UnsewError, ValueError, OSError) as exc:
        print(f"placed: {exc}", file=sys.stderr)
        return 2
    target = Target.of_case(case)
    t_top, t_hem = _extent(target.verts)

    def narrowed(f):
        out = pattern.copy()
        for panel in out.panels.values():
            panel.vertices = panel.vertices * [f, 1.0]
        return out

    sdf = BodySDF.build(case.body)
    variants = [("as placed", pattern, DRESS_SETTINGS, sdf)]
    variants += [(f"lift {cm:+.1f} cm", lifted(pattern, cm / 100.0), DRESS_SETTINGS, sdf) for cm in args.lift]
    variants += [(f"narrow x{f:g}", narrowed(f), DRESS_SETTINGS, sdf) for f in args.narrow]
    if sets:
        variants.append((", ".join(args.set), pattern, DRESS_SETTINGS.replace(**sets), sdf))
    variants += [(f"inflate {mm:g} mm", pattern, DRESS_SETTINGS, sdf.inflated(mm / 1000.0)) for mm in args.inflate]
    rows = []
    for name, p, settings, body_sdf in variants:
        try:
            d = dress(p, case.body, sdf=body_sdf, material=args.material, settings=settings)
        except UnsewError as exc:
            rows.append({"variant": name, "error": str(exc)})
            continue
        x = d.x.detach().numpy()
        top, hem = _extent(x)
        rows.append({"variant": name, "chamfer_mm": target.distance_mm(x, d.mesh.faces), "top_m": top, "hem_m": hem,
                     "target_top_m": t_top, "target_hem_m": t_hem, "speed_m_s": d.stats.get("max_speed")})
        print(rows[-1], flush=True)
    print_table(rows, ["variant", "chamfer_mm", "top_m", "hem_m", "target_top_m", "target_hem_m", "speed_m_s", "error"],
                title=f"{args.pattern} on {args.case} in {args.material}", digits=3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
