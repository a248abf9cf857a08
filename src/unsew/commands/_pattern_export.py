"""``unsew pattern export P.json [--svg P.svg] [--dxf P.dxf] [--pdf P.pdf] [--obj P.obj]``: write the
pattern as a true-scale SVG, an AAMA/ASTM-style DXF, a tiled 1:1 PDF (cut and sew lines, seam
allowance ``--seam-allowance`` / ``--hem-allowance`` [m]) and/or the flat panels as OBJ."""

from __future__ import annotations

import argparse
import sys
import warnings

from unsew.commands._output import check_out
from unsew.errors import InputError

__all__ = ["run", "load_pattern_reporting"]


def load_pattern_reporting(path):
    """Load a pattern; print its validation warnings as ``unsew: warning: ...`` lines."""
    from unsew.io.garmentcode import load_pattern

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pattern = load_pattern(path)
    for w in caught:
        print(f"unsew: warning: {w.message}", file=sys.stderr)
    return pattern


def run(args: argparse.Namespace) -> int:
    outs = [
        (args.svg, ".svg", "--svg"),
        (args.dxf, ".dxf", "--dxf"),
        (getattr(args, "pdf", None), ".pdf", "--pdf"),
        (getattr(args, "obj", None), ".obj", "--obj"),
    ]
    if not any(o for o, _, _ in outs):
        raise InputError("nothing to export: give --svg P.svg, --dxf P.dxf, --pdf P.pdf and/or --obj P.obj")
    sa = {"allowance": getattr(args, "seam_allowance", None), "hem": getattr(args, "hem_allowance", None)}
    for flag, v in (("--seam-allowance", sa["allowance"]), ("--hem-allowance", sa["hem"])):
        if v is not None and not 0.0 <= v <= 0.1:
            raise InputError(f"{flag} {v:g} is in metres and must lie in 0..0.1 (1 cm is 0.01)")
    for o, ext, flag in outs:
        if o and not str(o).lower().endswith(ext):
            raise InputError(f"{flag} {o} should name a {ext} file")
    from unsew.commands._checks import MAX_TRIANGLES

    pattern = load_pattern_reporting(args.pattern)
    for o, _, flag in outs:
        if o:
            check_out(o, overwrite=args.overwrite, flag=flag)
    if args.svg:
        from unsew.io.svg import write_svg

        write_svg(pattern, args.svg, **sa)
        print(f"wrote {args.svg}")
    if args.dxf:
        from unsew.io.dxf import write_dxf

        write_dxf(pattern, args.dxf, **sa)
        print(f"wrote {args.dxf}")
    if getattr(args, "pdf", None):
        from unsew.io.pdf import write_pdf

        pages = write_pdf(pattern, args.pdf, paper=getattr(args, "paper", "a4"), **sa)
        print(f"wrote {args.pdf} ({pages} pages)")
    if getattr(args, "obj", None):
        from unsew.commands._checks import check_triangle_budget
        from unsew.meshing import mesh_pattern, write_rest_obj

        check_triangle_budget(pattern, 0.02, limit=MAX_TRIANGLES, override=None)
        write_rest_obj(mesh_pattern(pattern), args.obj)
        print(f"wrote {args.obj}")
    return 0
