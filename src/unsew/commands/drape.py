"""``unsew drape PATTERN.json --body default|CASE_DIR|body.obj --out garment.obj``: dress a body.

Places the pattern's panels around the body, sews them shut and lets the garment settle
(:func:`unsew.dress.dress`), judges the result (:func:`unsew.sim.checks.check_dressed`: fallen,
off the body, exploded, inside it or left unsewn), then writes the draped garment as OBJ with
the pattern's 2D coordinates [m] as UVs, atomically. A bad verdict exits non-zero with one line
and writes no ``--out`` (with ``--keep-failed`` the garment goes to ``<out stem>.failed.obj`` for
a look).
This is also how a fitted pattern is retargeted to another body or pose (paper Fig. 12). A
pattern written by a fit carries its fitted material and, when the fit's drapes did not use the
default body contact (``contact: target``), that contact; the drape uses both.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from unsew.commands._output import check_out
from unsew.commands._help import HelpFormatter, add_progress_switch, examples
from unsew.errors import InputError

__all__ = ["register", "run", "pattern_contact"]


def pattern_contact(pattern) -> dict | None:
    """The body contact a fitted pattern carries (``pattern.unsew["contact"]``, written by a fit
    whose drapes did not use the default contact: ``contact: target``) as DrapeSettings fields
    {"contact_threshold" [m], "contact_stiffness" [N/m^4]}, or None when it carries none. A
    contact that is not two positive finite numbers is refused (InputError)."""
    import math

    c = (getattr(pattern, "unsew", None) or {}).get("contact")
    if c is None:
        return None
    try:
        thr, kc = float(c["threshold_m"]), float(c["stiffness_n_m4"])
    except (TypeError, KeyError, ValueError):
        raise InputError(
            f"the pattern's contact {c!r} needs numbers threshold_m and stiffness_n_m4"
        ) from None
    if not (math.isfinite(thr) and math.isfinite(kc) and thr > 0 and kc > 0):
        raise InputError(
            f"the pattern's contact needs a positive threshold and stiffness, got {thr} m, {kc} N/m^4"
        )
    return {"contact_threshold": thr, "contact_stiffness": kc}


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "drape",
        help="drape a sewing pattern on a body (place, sew, settle) and write garment.obj",
        description="Drape PATTERN.json (GarmentCode JSON) on a body: 'default' (the embedded body), "
        "a case folder or a body folder (its body.obj + skeleton.json, as `unsew body make` writes it), "
        "or a body mesh with --skeleton. A drape that ends fallen, off the body, exploded, inside it "
        "or with a seam left open (unsewn) exits non-zero with one line and writes no --out.",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew drape result/pattern.json --out garment.obj",
            "unsew drape pattern.json --body bodies/tall/ --material denim --edge-length 0.02 --out "
            "garment.obj",
        ),
    )
    p.add_argument("pattern", metavar="PATTERN.json", help="sewing pattern (GarmentCode specification JSON)")
    p.add_argument(
        "--body", default="default", help="default | CASE_DIR | BODY_DIR | body.obj/ply (default: default)"
    )
    p.add_argument(
        "--skeleton",
        default=None,
        help="skeleton.json of a body mesh given with --body (default: the mesh is rigged from its shape)",
    )
    p.add_argument(
        "--units", default="m", choices=["m", "cm", "mm"], help="units of a body mesh file (default: m)"
    )
    p.add_argument(
        "--material",
        default=None,
        help="material name from the library (default: the pattern's own fitted material when "
        "pattern.json carries one, as unsew fit writes it; else cotton)",
    )
    p.add_argument(
        "--edge-length", type=float, default=0.025, help="target triangle edge length [m] (default: 0.025)"
    )
    p.add_argument(
        "--sew-steps",
        type=int,
        default=None,
        help="steps of the sewing phase (default: 60, unsew.dress.DRESS_SETTINGS)",
    )
    p.add_argument(
        "--settle-steps",
        type=int,
        default=None,
        help="steps of settling after sewing (default: 20, unsew.dress.DRESS_SETTINGS)",
    )
    p.add_argument("--out", required=True, metavar="garment.obj", help="OBJ file to write")
    p.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    p.add_argument(
        "--keep-failed",
        action="store_true",
        help="when the drape fails its checks, write the garment to <out stem>.failed.obj",
    )
    add_progress_switch(p, dest="no_progress")
    p.set_defaults(func=run)


def _load_body(args):
    from pathlib import Path

    src = args.body
    if src == "default":
        if args.skeleton:
            raise InputError("--skeleton goes with a body mesh file, not with --body default")
        from unsew.body.body import default_body

        return default_body()
    path = Path(src)
    if path.is_dir():
        if any((path / n).is_file() for n in ("target.obj", "target.ply")):
            from unsew.body.case import load_case

            # the case's target is checked to lie on its wearer; its true pattern is not what is draped
            return load_case(path, truth=False).body
        if (path / "meta.json").is_file() or not (path / "body.obj").is_file():
            from unsew.body.case import load_wearer

            return load_wearer(path)
        # a body folder as `unsew body make` writes it: body.obj and, when known, skeleton.json
        from unsew.body.body import load_body

        skel = path / "skeleton.json"
        return load_body(path / "body.obj", skel if skel.is_file() else None, units=args.units)
    if not path.is_file():
        raise InputError(f"body {src} not found; give 'default', a case folder or a body mesh file")
    from unsew.body.body import load_body

    # without --skeleton the mesh is rigged from its shape (unsew.body.rig)
    return load_body(path, args.skeleton or None, units=args.units)


def _checked_out(args: argparse.Namespace):
    """--out as a Path, after the checks of the numeric options and of --out itself (a bad
    --out fails now, not after the drape)."""
    from pathlib import Path

    if not (0.005 <= args.edge_length <= 0.1):
        raise InputError(f"--edge-length {args.edge_length} m is outside [0.005, 0.1] m")
    for flag in ("sew_steps", "settle_steps"):
        v = getattr(args, flag)
        if v is not None and v < 0:
            raise InputError(f"--{flag.replace('_', '-')} must be >= 0, got {v}")
    out = Path(args.out)
    if out.suffix.lower() != ".obj":
        raise InputError(f"--out {out} must end in .obj")
    check_out(out, overwrite=args.overwrite)
    return out


def _material(args: argparse.Namespace, pattern):
    """(Material, its name for the OBJ header): --material, else the pattern's fitted material,
    else cotton. A bad name fails before any work."""
    from unsew.dress import resolve_material

    fitted = (getattr(pattern, "unsew", None) or {}).get("material")
    if args.material is None and fitted is not None:
        from unsew.sim.material import material_from_dict

        return material_from_dict(fitted), "the pattern's fitted material"
    material_name = args.material or "cotton"
    return resolve_material(material_name), material_name


def _write_garment(path, d, header: str) -> None:
    """The dressed garment ``d`` as OBJ at ``path``, pattern coordinates as UVs."""
    from unsew.io.mesh import write_obj

    m = d.mesh
    write_obj(path, d.x.detach().cpu().numpy(), m.faces, uv=m.uv, faces_uv=m.faces_uv, header=header)


def _judged(d, pattern, body, out: Path, *, keep_failed: bool):
    """The verdict on drape ``d`` (:func:`unsew.sim.checks.check_dressed`), judged against where
    the pattern itself places the garment too (a start that already lay low, a bodice placed at
    the hips, drops nothing from itself), refusing a seam left open (``SEAM_GAP_MAX``) and a
    sleeve off its arm; a bad one raises its one line, the garment first written to
    ``<out stem>.failed.obj`` when ``keep_failed``."""
    from unsew.sim.checks import SEAM_GAP_MAX, check_dressed, placed_top, sleeve_vertices

    # d.pattern: the pattern as dressed (a file sized to another body moved onto this one)
    top = placed_top(d.pattern, d.mesh, body, sdf=d.sdf)
    sleeves = sleeve_vertices(d.pattern, d.mesh, body)
    verdict = check_dressed(d, body=body, placed_top_m=top, seam_gap_max=SEAM_GAP_MAX, sleeves=sleeves)
    if not verdict.ok:
        if keep_failed:
            failed = out.with_name(out.stem + ".failed.obj")
            _write_garment(failed, d, f"unsew drape FAILED ({verdict.reason}): {pattern.name}")
        verdict.raise_if_bad(f"drape of {pattern.name}")
    return verdict


def run(args: argparse.Namespace) -> int:
    out = _checked_out(args)

    from unsew.io.garmentcode import load_pattern

    from unsew.commands._checks import check_pattern_scale, check_triangle_budget

    pattern = load_pattern(args.pattern)
    body = _load_body(args)
    check_pattern_scale(pattern, body)
    check_triangle_budget(pattern, args.edge_length, override=None)

    from unsew.dress import dress

    material, material_name = _material(args, pattern)
    from unsew.dress import DRESS_SETTINGS
    from unsew.fit.progress import Progress

    kw = {k: getattr(args, k) for k in ("sew_steps", "settle_steps") if getattr(args, k) is not None}
    # the fit's contact (contact: target), so the drape rests as the fit's did
    contact = pattern_contact(pattern)
    settings = DRESS_SETTINGS.replace(
        edge_length=args.edge_length, judge_placement=True, **kw, **(contact or {})
    )
    # bars on a terminal, else a line per phase
    with Progress(not args.no_progress).phase("drape") as progress:
        d = dress(pattern, body, material=material, settings=settings, progress=progress)
    m = d.mesh
    verdict = _judged(d, pattern, body, out, keep_failed=args.keep_failed)
    _write_garment(
        out,
        d,
        f"unsew drape: {pattern.name} on {getattr(body, 'name', 'body')}, {material_name}; UVs are "
        "pattern coordinates [m]",
    )
    s = d.stats
    if s.get("held"):
        print(f"{s['held']} vertices of the pattern's hanging edges (lower_interface, strapless_top) held")
    if s.get("diverged"):
        print(f"{' and '.join(s['diverged'])} diverged: the drape before it was kept")
    if s.get("start_given"):
        print("the drape started from the pattern's own placement (the wrapped start drapes unsound)")
    if contact is not None:
        print(
            f"the pattern's fitted contact: threshold {contact['contact_threshold'] * 1e3:.1f} mm, "
            f"stiffness {contact['contact_stiffness']:.0e} N/m^4"
        )
    print(
        f"wrote {out}: {m.n_x} vertices, seam gap {s.get('seam_gap', 0.0) * 1000:.2f} mm, "
        f"max speed {s.get('max_speed', 0.0):.3f} m/s, {verdict.inside_pct:.2f} % inside the body, "
        f"stretch max {verdict.stretch_max:.2f}, y {verdict.y_min:.2f}..{verdict.y_max:.2f} m"
    )
    return 0
