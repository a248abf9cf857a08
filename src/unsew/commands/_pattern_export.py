"""``unsew pattern export P.json [--svg P.svg] [--dxf P.dxf] [--obj P.obj]``: write the pattern
as a true-scale SVG, an AAMA/ASTM-style DXF and/or the flat panels as OBJ."""

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
    outs = [(args.svg, ".svg", "--svg"), (args.dxf, ".dxf", "--dxf"), (getattr(args, "obj", None), ".obj", "--obj")]
    if not any(o for o, _, _ in outs):
        raise InputError("nothing to export: give --svg P.svg, --dxf P.dxf and/or --obj P.obj")
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

        write_svg(pattern, args.svg)
        print(f"wrote {args.svg}")
    if args.dxf:
        from unsew.io.dxf import write_dxf

        write_dxf(pattern, args.dxf)
        print(f"wrote {args.dxf}")
    if getattr(args, "obj", None):
        from unsew.commands._checks import check_triangle_budget
        from unsew.meshing import mesh_pattern, write_rest_obj

        check_triangle_budget(pattern, 0.02, limit=MAX_TRIANGLES, override=None)
        write_rest_obj(mesh_pattern(pattern), args.obj)
        print(f"wrote {args.obj}")
    return 0
