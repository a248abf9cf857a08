"""``unsew grade CASE_DIR --base tshirt --out graded/``: linear grading (phase one) of a base
pattern to a case's target garment.

Writes, all at once into ``--out`` (nothing is left behind if the run fails):
``pattern.json`` (graded pattern, GarmentCode JSON), ``garment.obj`` (its drape, pattern
coordinates as UVs), ``garment_init.obj`` (the base pattern's drape), ``contours.json`` (the
contour table, lengths in metres). The table is also printed.
"""

from __future__ import annotations

import argparse

from unsew.commands._help import HelpFormatter, examples
from unsew.errors import InputError
from unsew.io.atomic import atomic_dir
from unsew.pattern.base import BASES

__all__ = ["register", "run"]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "grade",
        help="grade a base pattern to a target's hems, cuffs, necklines (phase one)",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew grade case/ --out graded/", "unsew grade case/ --base skirt_band --flat --out graded/"
        ),
    )
    p.add_argument(
        "case", metavar="CASE_DIR", help="case folder (target.obj, body, meta.json; see FORMATS.md)"
    )
    p.add_argument(
        "--base",
        default=None,
        metavar="NAME|P.json",
        help=f"base pattern, sized to the wearer as the fit sizes it: {', '.join(BASES)}, or a GarmentCode "
        "JSON file (default: the case's garment type)",
    )
    p.add_argument("--out", required=True, metavar="DIR", help="result folder to create")
    p.add_argument(
        "--edge-length",
        type=float,
        default=0.03,
        help="rest edge length of the panel meshes [m] (default: 0.03)",
    )
    p.add_argument("--material", default="cotton", help="material name from the library (default: cotton)")
    _add_grading_rules(p)
    p.add_argument(
        "--flat", action="store_true", help="no simulation: use the flat-placed panels as drapes (quick look)"
    )
    p.add_argument("--overwrite", action="store_true", help="replace --out if it exists")
    p.set_defaults(func=run)


def _add_grading_rules(p: argparse.ArgumentParser) -> None:
    """The options that choose grading's rules (each a field of GradingSettings)."""
    p.add_argument(
        "--length",
        choices=["cloth", "axial"],
        default="cloth",
        help="move hems and cuffs by the cloth length to the top opening (default) or by the axial distance "
        "along the bone (the paper's Algorithm 2)",
    )
    p.add_argument(
        "--area",
        choices=["free", "target"],
        default="free",
        help="target: scale each graded pattern to the target's surface area before it is draped (the fit's "
        "area: target); free: the contours alone (default)",
    )
    p.add_argument(
        "--side-seams",
        choices=["none", "girth"],
        default="girth",
        help="girth (default, as the fit): also move the side seams between the hips and the armpits by "
        "the target's torso girth, the waisted dresses with their waist as a vertex; none: left where "
        "the base has them (the paper's Algorithm 2)",
    )
    p.add_argument(
        "--band-gap",
        choices=["none", "target"],
        default="target",
        help="target (default, as the fit): a skirt's waistband graded to the target's top loop less "
        "what the target's contact gap adds where it presses on the body, its bottom and the waist "
        "seam below with it (trousers and shorts as with none); none: to the loop as measured, its "
        "top alone",
    )


def run(args: argparse.Namespace) -> int:
    import sys

    from unsew.body.case import load_case
    from unsew.commands._output import check_out
    from unsew.fit.config import FitConfig
    from unsew.fit.start import base_pattern_for, with_garment_read
    from unsew.grading.grade import flat_drape, format_table, grade
    from unsew.meshing.sew import EDGE_LENGTH_RANGE

    lo, hi = EDGE_LENGTH_RANGE
    if not (lo <= args.edge_length <= hi):
        raise InputError(f"--edge-length {args.edge_length} m is outside [{lo}, {hi}] m")
    check_out(args.out, overwrite=args.overwrite, folder=True)
    cfg = FitConfig(base=args.base or "", side_seams=args.side_seams)
    case = with_garment_read(load_case(args.case), cfg, log=lambda s: print(s, file=sys.stderr))
    pattern = base_pattern_for(case, cfg)  # a bad name fails before --out is made
    with atomic_dir(args.out, overwrite=args.overwrite) as tmp:
        kw = {"drape_fn": flat_drape} if args.flat else {}
        res = grade(pattern, case.body, case.target_verts, case.target_faces, _settings(args, case), **kw)
        if res.note:
            print(res.note)
        _write(tmp, res, case, args)
    print(format_table(res.table))
    note = "" if res.fraction == 1.0 else f" (edit scaled back to {res.fraction:.0%})"
    print(f"wrote {args.out}: pattern.json, garment.obj, garment_init.obj, contours.json{note}")
    return 0


def _settings(args: argparse.Namespace, case):
    """The GradingSettings the options ask for (the target's surface area from ``case``)."""
    from unsew.geometry.repair import triangle_areas
    from unsew.grading.grade import GRADE_SETTINGS, GradingSettings

    return GradingSettings(
        drape=GRADE_SETTINGS.replace(edge_length=args.edge_length),
        material=args.material,
        length=args.length,
        area=float(triangle_areas(case.target_verts, case.target_faces).sum())
        if args.area == "target"
        else None,
        side_seams=args.side_seams,
        band_gap=args.band_gap,
    )


def _write(tmp, res, case, args: argparse.Namespace) -> None:
    """The result folder's files: pattern.json, garment.obj (X_LG, the pattern as UVs),
    garment_init.obj (X_init) and contours.json (the options, what grading did, its table)."""
    import json

    from unsew.io.garmentcode import save_pattern
    from unsew.io.mesh import write_obj

    save_pattern(res.pattern, tmp / "pattern.json")
    m = res.mesh
    write_obj(
        tmp / "garment.obj",
        res.x_draped,
        m.faces,
        uv=m.uv,
        faces_uv=m.faces_uv,
        header="unsew grade: X_LG",
    )
    write_obj(tmp / "garment_init.obj", res.x_init, res.mesh_init.faces, header="unsew grade: X_init")
    doc = {
        "format_version": 1,
        "units": "m",
        "case": str(case.path),
        "base": args.base or case.garment,
        "edge_length_m": args.edge_length,
        "material": args.material,
        "flat": bool(args.flat),
        "length": args.length,
        "area": args.area,
        "side_seams": args.side_seams,
        "band_gap": args.band_gap,
        "area_scales": res.area_scales,
        "placement": res.placement,
        "edit_fraction": res.fraction,
        "remeshed": res.remeshed,
        "contours": res.table,
    }
    (tmp / "contours.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
