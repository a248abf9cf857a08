"""The open contours of one grading case, looked at closely: is a contour's loop smooth or crumpled?

bench_grading.py measures a contour's girth as the length of its boundary loop. A loop that
folds or crumples (a cuff caught on the arm, a hem pooling over the feet) is longer than the
girth a tape measure would read around it. For one of bench_grading's cases (``--garment``,
``--flip``, the target on a mesh ``--target-scale`` times the edge length), this grades the
base pattern to the target exactly as bench_grading does and prints, for every contour of the
target, the base drape and the graded drape: its body part, position along the bone [m], loop
length [m], the perimeter of the loop's convex hull in its least-squares plane [m], and the
rest length of the pattern edges that form it [m]. A ratio loop / hull well above 1 is a pleated
loop; a loop longer than its rest length is stretched (both: caught by the drape,
``unsew.grading.grade.source_girth``). ``--passes 1`` shows the drape after the first pass.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_contours.py --garment dress --flip
     [--edge-length 0.03] [--target-scale 1.0] [--material cotton] [--passes 2]
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    from bench_grading import CHANGES, _changes

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--garment", choices=list(CHANGES), required=True)
    ap.add_argument("--flip", action="store_true", help="negate every known change (bench_grading --flip)")
    ap.add_argument("--edge-length", type=float, default=0.03)
    ap.add_argument("--target-scale", type=float, default=1.0, help="edge length factor of the target's mesh")
    ap.add_argument("--material", default="cotton")
    ap.add_argument("--passes", type=int, default=2, help="grading passes (grade(passes=...))")
    args = ap.parse_args()
    if not 0.005 <= args.edge_length <= 0.1 or not 0.5 <= args.target_scale <= 2.0 or args.passes < 1:
        ap.error("--edge-length must be in [0.005, 0.1] m, --target-scale in [0.5, 2] and --passes at least 1")

    import torch

    torch.set_num_threads(1)
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF
    from unsew.errors import InputError
    from unsew.grading.alter import alter_pattern, alteration_groups
    from unsew.grading.contours import place_contours
    from unsew.grading.curves import curves_of_contour, rest_length
    from unsew.grading.grade import GRADE_SETTINGS, dress_drape, grade
    from unsew.meshing.sew import mesh_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.params import PatternParams
    from unsew.sim.material import get_material

    try:
        material = get_material(args.material)
    except InputError as exc:
        ap.error(str(exc))
    body = default_body()
    sdf = BodySDF.build(body)

    def drape_fn(p, m, b):
        return dress_drape(p, m, b, material=material, sdf=sdf)

    base = make_base_pattern(args.garment)
    groups = alteration_groups(base)
    target = base
    for key, (dl, dg) in _changes(args.garment, args.flip).items():
        if key in groups:
            target = alter_pattern(target, groups[key], length=dl, girth=dg)
    bm = mesh_pattern(base, edge_length=args.edge_length)
    bx = drape_fn(base, bm, body)
    tm = mesh_pattern(target, edge_length=args.edge_length * args.target_scale)
    tx = drape_fn(target, tm, body)
    res = grade(base, body, tx, tm.faces, settings=GRADE_SETTINGS.replace(edge_length=args.edge_length), drape_fn=drape_fn, mesh=bm, x_init=bx,
                passes=args.passes)
    print(f"{args.garment}{' (flipped)' if args.flip else ''}, edge length {args.edge_length} m, "
          f"target mesh x{args.target_scale}, {args.passes} pass(es)")
    print(f"{'drape':<7} {'part':<10} {'position m':>10} {'loop m':>7} {'hull m':>7} {'loop/hull':>9} {'rest m':>7}")
    for name, p, m, x in (("target", target, tm, tx), ("base", base, bm, bx), ("graded", res.pattern, res.mesh, res.x_draped)):
        controls = PatternParams.build(p, m).controls
        for c in place_contours(x, m.faces, body.skeleton):
            pos = f"{c.position:>10.3f}" if c.bone is not None else f"{'-':>10}"
            rest = rest_length(p, curves_of_contour(c.contour.indices, x, p, m, controls))
            print(f"{name:<7} {c.part or '-':<10} {pos} {c.length:>7.3f} {c.hull:>7.3f} {c.crumple:>9.2f} {rest:>7.3f}")


if __name__ == "__main__":
    main()
