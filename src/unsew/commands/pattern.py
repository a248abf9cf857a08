"""``unsew pattern {new,mesh,symmetry,export}``: make, mesh, analyse and export sewing patterns.

Each subcommand's work lives in its own private module (``_pattern_<verb>.py``) imported only
when that subcommand runs, so ``unsew --help`` stays fast.
"""

from __future__ import annotations

import argparse
import importlib

from unsew.commands._help import HelpFormatter, examples

__all__ = ["register"]

#: unsew.pattern.base.BASES (kept here so --help imports nothing; a test checks they agree)
BASES = [
    "tshirt",
    "tshirt_long",
    "tshirt_sleeveless",
    "dress",
    "dress_sleeveless",
    "dress_straight",
    "dress_straight_sleeveless",
    "pants",
    "pants_band",
    "shorts",
    "shorts_band",
    "skirt",
    "skirt_band",
    "skirt_circle",
    "skirt_pencil",
    "skirt_darts",
]
MAX_TRIANGLES = 250_000  # unsew.commands._checks.MAX_TRIANGLES (kept here so --help imports nothing)


def _dispatch(verb: str):
    def run(args: argparse.Namespace) -> int:
        return importlib.import_module(f"unsew.commands._pattern_{verb}").run(args)

    return run


def _add_new(psub) -> None:
    """The ``pattern new`` verb."""
    new = psub.add_parser(
        "new",
        help="write a base pattern sized to body measurements",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew pattern new tshirt --out tshirt.json",
            "unsew pattern new skirt_band --measurements me.yaml --out skirt.json",
        ),
    )
    new.add_argument("garment", choices=BASES, help="garment type or library base")
    new.add_argument(
        "--measurements",
        metavar="M.yaml",
        help="body measurements in metres (YAML); default: the default body",
    )
    new.add_argument("--out", required=True, metavar="P.json", help="GarmentCode JSON to write")
    new.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    new.set_defaults(func=_dispatch("new"))


def _add_mesh(psub) -> None:
    """The ``pattern mesh`` verb."""
    mesh = psub.add_parser(
        "mesh",
        help="triangulate the panels and sew them into one garment mesh",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew pattern mesh tshirt.json --out rest.obj",
            "unsew pattern mesh tshirt.json --edge-length 0.01 --out rest.obj",
        ),
    )
    mesh.add_argument("pattern", metavar="P.json")
    mesh.add_argument(
        "--edge-length", type=float, default=0.02, help="target edge length [m], 0.01-0.03 (default: 0.02)"
    )
    mesh.add_argument(
        "--out", required=True, metavar="REST.obj", help="flat panels as OBJ (pattern coordinates as UVs)"
    )
    mesh.add_argument(
        "--max-triangles",
        type=int,
        default=MAX_TRIANGLES,
        metavar="N",
        help=f"refuse a mesh estimated above N triangles (default {MAX_TRIANGLES:,})",
    )
    mesh.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    mesh.set_defaults(func=_dispatch("mesh"))


def _add_symmetry(psub) -> None:
    """The ``pattern symmetry`` verb."""
    sym = psub.add_parser(
        "symmetry",
        help="detect panel pairs and mirror axes; count control points",
        formatter_class=HelpFormatter,
        epilog=examples("unsew pattern symmetry tshirt.json", "unsew pattern symmetry tshirt.json --json"),
    )
    sym.add_argument("pattern", metavar="P.json")
    sym.add_argument("--json", action="store_true", help="print JSON instead of a table")
    sym.set_defaults(func=_dispatch("symmetry"))


def _add_export(psub) -> None:
    """The ``pattern export`` verb."""
    exp = psub.add_parser(
        "export",
        help="write SVG and PDF (true scale), DXF (AAMA/ASTM layers) and/or OBJ",
        description="Write the pattern's pieces with cut line (seam allowance included), sew "
        "line, notches on both, grain line, cutting notes and seam labels.",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew pattern export result/pattern.json --svg p.svg --dxf p.dxf --pdf p.pdf",
            "unsew pattern export p.json --pdf p.pdf --paper letter --seam-allowance 0.015",
        ),
    )
    exp.add_argument("pattern", metavar="P.json")
    exp.add_argument(
        "--svg",
        metavar="P.svg",
        help="true-scale SVG in millimetres with a 10 cm test square (default: not written)",
    )
    exp.add_argument(
        "--dxf",
        metavar="P.dxf",
        help="DXF in millimetres, one block per piece, AAMA/ASTM layers "
        "(1 cut line, 2 turn points, 4 notches, 6 fold line, 7 grain line, 14 sew line, 15 text) (default: "
        "not written)",
    )
    exp.add_argument(
        "--pdf",
        metavar="P.pdf",
        help="tiled PDF at 1:1 for home printing, see --paper (default: not written)",
    )
    exp.add_argument(
        "--paper", choices=["a4", "letter"], default="a4", help="page size of --pdf (default: a4)"
    )
    exp.add_argument(
        "--seam-allowance",
        type=float,
        metavar="M",
        default=None,
        help="seam allowance of every edge but hems [m] (default: the pattern's unsew.seam_allowance, "
        "else 0.01 = 1 cm); per-edge values in the pattern's unsew.seam_allowance win",
    )
    exp.add_argument(
        "--hem-allowance",
        type=float,
        metavar="M",
        default=None,
        help="allowance of edges labelled hem [m] (default: the pattern's, else 0.02 = 2 cm)",
    )
    exp.add_argument(
        "--obj", metavar="P.obj", help="flat panels as OBJ, pattern coordinates as UVs (default: not written)"
    )
    exp.add_argument(
        "--overwrite", action="store_true", help="replace existing --svg/--dxf/--pdf/--obj files"
    )
    exp.set_defaults(func=_dispatch("export"))


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "pattern",
        help="make, mesh, analyse and export sewing patterns",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew pattern new tshirt --out tshirt.json",
            "unsew pattern export result/pattern.json --pdf pattern.pdf --paper letter",
        ),
    )
    psub = p.add_subparsers(dest="pattern_command", metavar="VERB", required=True)

    _add_new(psub)
    _add_mesh(psub)
    _add_symmetry(psub)
    _add_export(psub)
