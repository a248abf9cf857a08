"""``unsew body {make,rig,measure}``: make a wearer with anny (optional extra), rig a body mesh
that has no skeleton, measure a body.

No heavy imports at module level: the work is imported when a subcommand runs.
"""

from __future__ import annotations

import argparse
import sys

from unsew.commands._output import check_out
from unsew.commands._help import HelpFormatter, examples
from unsew.errors import InputError
from unsew.io.atomic import atomic_dir

__all__ = ["register"]


def _phenotype(text: str) -> tuple[str, float]:
    k, sep, v = text.partition("=")
    if not sep:
        raise argparse.ArgumentTypeError(f"--phenotype {text!r}: write NAME=VALUE, e.g. weight=0.7")
    try:
        return k.strip(), float(v)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--phenotype {text!r}: VALUE must be a number in [0, 1]") from None


def run_make(args: argparse.Namespace) -> int:
    import os

    from unsew.body.anny_body import make_anny_body
    from unsew.body.skeleton import save_skeleton
    from unsew.io.mesh import write_obj

    check_out(args.out, overwrite=args.overwrite, folder=True)  # fail before making the body
    body = make_anny_body(dict(args.phenotype or []), pose=args.pose)
    with atomic_dir(args.out, overwrite=args.overwrite) as tmp:
        write_obj(os.path.join(tmp, "body.obj"), body.verts, body.faces, header=f"unsew body: {body.name}")
        save_skeleton(body.skeleton, os.path.join(tmp, "skeleton.json"))
    print(
        f"wrote {args.out}/body.obj ({len(body.verts)} vertices, height {body.height:.3f} m) and "
        "skeleton.json"
    )
    return 0


def _body_from_arg(args: argparse.Namespace, *, rig: bool = False):
    """The body named on the command line: 'default', a body mesh file, or a folder with body.obj
    (and skeleton.json, else the body is rigged from its mesh; ``rig``: always rigged)."""
    import os

    from unsew.body.body import default_body, load_body

    src = args.body
    if src == "default":
        return default_body()
    if os.path.isdir(src):
        mesh = next(
            (os.path.join(src, n) for n in ("body.obj", "body.ply") if os.path.isfile(os.path.join(src, n))),
            None,
        )
        if mesh is None:
            raise InputError(
                f"{src} has no body.obj or body.ply; give a body folder, a body mesh file or 'default'"
            )
        skel = os.path.join(src, "skeleton.json")
    elif os.path.isfile(src):
        mesh, skel = src, getattr(args, "skeleton", None) or ""
    else:
        raise InputError(f"body {src} not found; give a body folder, a body mesh file or 'default'")
    use = skel if os.path.isfile(skel) and not rig else None
    return load_body(mesh, use, units=args.units, up=args.up, front=args.front)


def run_rig(args: argparse.Namespace) -> int:
    import os

    from unsew.body.skeleton import save_skeleton

    folder = args.body if os.path.isdir(args.body) else os.path.dirname(os.path.abspath(args.body))
    out = args.out or os.path.join(folder, "skeleton.json")
    if args.body == "default" or os.path.exists(args.body):  # else _body_from_arg says it is missing
        check_out(out, overwrite=args.overwrite)
        if args.preview:
            check_out(args.preview, overwrite=args.overwrite, flag="--preview")
    body = _body_from_arg(args, rig=True)
    for note in body.notes:
        print(f"note: {note}", file=sys.stderr)  # stdout holds the result alone
    save_skeleton(body.skeleton, out)
    print(f"wrote {out} ({len(body.skeleton.names)} joints, height {body.height:.3f} m)")
    if args.preview:
        from unsew.body.preview import render_rig_preview

        render_rig_preview(body, args.preview)
        print(f"wrote {args.preview}")
    return 0


def run_measure(args: argparse.Namespace) -> int:
    import json

    from unsew.body.measure import cross_check_rig

    body = _body_from_arg(args)
    for note in body.notes:
        print(f"note: {note}", file=sys.stderr)  # stdout holds the result alone
    m = cross_check_rig(body).as_dict()
    if args.json:
        print(
            json.dumps(
                {"units": "m", "rigged": body.rigged, **{k: round(v, 4) for k, v in m.items()}}, indent=1
            )
        )
    else:
        for k, v in m.items():
            print(f"{k:15s} {v * 100:7.1f} cm")
    return 0


def _frame_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--units", default="m", choices=["m", "cm", "mm"], help="units of the body files (default: m)"
    )
    p.add_argument("--up", default="y", help="the files' up axis: x, y, z, -x, ... (default: y)")
    p.add_argument("--front", default="z", help="the files' front axis (default: z)")


def _add_make(psub) -> None:
    """The ``body make`` verb."""
    mk = psub.add_parser(
        "make",
        help="make a body with anny (pip install unsew[anny]): body.obj + skeleton.json",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew body make --out bodies/average/",
            "unsew body make --phenotype height=0.7 --phenotype weight=0.3 --pose T --out bodies/tall/",
        ),
    )
    mk.add_argument(
        "--phenotype",
        type=_phenotype,
        action="append",
        metavar="NAME=VALUE",
        help="gender, age, muscle, weight, height or proportions in [0, 1] (default 0.5); repeatable",
    )
    mk.add_argument(
        "--pose", default="A", help="A (rest), T, or a JSON file of joint rotation vectors [rad] (default: A)"
    )
    mk.add_argument("--out", required=True, metavar="DIR", help="folder to write")
    mk.add_argument("--overwrite", action="store_true", help="replace an existing --out folder")
    mk.set_defaults(func=run_make)


def _add_rig(psub) -> None:
    """The ``body rig`` verb."""
    rg = psub.add_parser(
        "rig",
        help="estimate the 17 joints of a body mesh that has no skeleton: skeleton.json",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew body rig case/body.obj",
            "unsew body rig scan.obj --units mm --up z --front -y --out skeleton.json --preview joints.png",
        ),
    )
    rg.add_argument("body", metavar="BODY.obj|BODY_DIR")
    rg.add_argument(
        "--out", metavar="skeleton.json", help="where to write (default: skeleton.json beside the body)"
    )
    rg.add_argument(
        "--preview",
        metavar="PNG",
        help="also draw the body and its joints, front and side (default: no picture)",
    )
    rg.add_argument("--overwrite", action="store_true", help="replace an existing --out (and --preview) file")
    _frame_options(rg)
    rg.set_defaults(func=run_rig, skeleton=None)


def _add_measure(psub) -> None:
    """The ``body measure`` verb."""
    me = psub.add_parser(
        "measure",
        help="girths and lengths of a body (body.obj [+ skeleton.json], its folder, or 'default'); "
        "a body without skeleton.json is rigged from its mesh",
        formatter_class=HelpFormatter,
        epilog=examples("unsew body measure default", "unsew body measure case/ --json"),
    )
    me.add_argument("body", metavar="BODY.obj|BODY_DIR|default")
    me.add_argument(
        "--skeleton", metavar="skeleton.json", help="the joints of a BODY.obj (default: rigged from the mesh)"
    )
    me.add_argument("--json", action="store_true", help="print JSON (metres)")
    _frame_options(me)
    me.set_defaults(func=run_measure)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "body",
        help="make a wearer (anny) or measure a body",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew body make --phenotype height=0.7 --out bodies/tall/", "unsew body measure default"
        ),
    )
    psub = p.add_subparsers(dest="body_command", metavar="VERB", required=True)

    _add_make(psub)
    _add_rig(psub)
    _add_measure(psub)
