"""``unsew body {make,measure}``: make a wearer with anny (optional extra), measure a body.

No heavy imports at module level: the work is imported when a subcommand runs.
"""

from __future__ import annotations

import argparse

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
    from unsew.io.atomic import atomic_dir
    from unsew.io.mesh import write_obj

    from unsew.errors import InputError
    from unsew.io.atomic import check_output

    if os.path.exists(args.out) and not args.overwrite:
        raise InputError(f"output folder {args.out} exists; remove it, pass --overwrite or choose another --out")
    check_output(args.out, folder=True)  # fail before making the body
    body = make_anny_body(dict(args.phenotype or []), pose=args.pose)
    with atomic_dir(args.out, overwrite=args.overwrite) as tmp:
        write_obj(os.path.join(tmp, "body.obj"), body.verts, body.faces, header=f"unsew body: {body.name}")
        save_skeleton(body.skeleton, os.path.join(tmp, "skeleton.json"))
    print(f"wrote {args.out}/body.obj ({len(body.verts)} vertices, height {body.height:.3f} m) and skeleton.json")
    return 0


def run_measure(args: argparse.Namespace) -> int:
    import json
    import os

    from unsew.body.body import default_body, load_body
    from unsew.body.measure import measure_body
    from unsew.errors import InputError

    if args.body == "default":
        body = default_body()
    else:
        mesh = next((os.path.join(args.body, n) for n in ("body.obj", "body.ply") if os.path.isfile(os.path.join(args.body, n))), None)
        if mesh is None:
            raise InputError(f"{args.body} has no body.obj or body.ply; give a body folder (body.obj + skeleton.json) or 'default'")
        body = load_body(mesh, os.path.join(args.body, "skeleton.json"), units=args.units, up=args.up, front=args.front)
    m = measure_body(body).as_dict()
    if args.json:
        print(json.dumps({"units": "m", **{k: round(v, 4) for k, v in m.items()}}, indent=1))
    else:
        for k, v in m.items():
            print(f"{k:15s} {v * 100:7.1f} cm")
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("body", help="make a wearer (anny) or measure a body")
    psub = p.add_subparsers(dest="body_command", metavar="VERB", required=True)

    mk = psub.add_parser("make", help="make a body with anny (pip install unsew[anny]): body.obj + skeleton.json")
    mk.add_argument("--phenotype", type=_phenotype, action="append", metavar="NAME=VALUE",
                    help="gender, age, muscle, weight, height or proportions in [0, 1] (default 0.5); repeatable")
    mk.add_argument("--pose", default="A", help="A (rest), T, or a JSON file of joint rotation vectors [rad]")
    mk.add_argument("--out", required=True, metavar="DIR", help="folder to write")
    mk.add_argument("--overwrite", action="store_true", help="replace an existing --out folder")
    mk.set_defaults(func=run_make)

    me = psub.add_parser("measure", help="girths and lengths of a body (folder with body.obj + skeleton.json, or 'default')")
    me.add_argument("body", metavar="BODY_DIR|default")
    me.add_argument("--json", action="store_true", help="print JSON (metres)")
    me.add_argument("--units", default="m", choices=["m", "cm", "mm"], help="units of the body files")
    me.add_argument("--up", default="y", help="the files' up axis (x, y, z, -x, ...)")
    me.add_argument("--front", default="z", help="the files' front axis")
    me.set_defaults(func=run_measure)
