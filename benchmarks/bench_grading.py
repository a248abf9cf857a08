"""Linear grading benchmark: recover known length and girth changes.

For every garment type, the base pattern is altered by known amounts (hem / sleeve / leg length
by +/- 5 to 15 cm, their girth by +/- 10 %, :mod:`unsew.grading.alter`), the altered pattern is
draped to make the target T, and the *base* pattern is graded to T. Printed per contour:
the known change, the measured axial distance and girth difference, and after grading the
residuals |position(X_LG) - position(T)| along the skeleton and |girth(X_LG) - girth(T)| [cm]
(girth: loop length), the cloth-length difference target - base that grading reads
(``cloth cm``, :mod:`unsew.grading.cloth`) beside the true patterns' own at rest (``rest cm``),
and the same residuals in the pattern (``pat L``, ``pat G``: :func:`pattern_residuals`
on the edges that form the target's contour: how far the graded pattern's edge lies from the
true pattern's, and how much longer or shorter it is; the drape's loop can pleat where the
pattern is right, the pattern is what grading recovers);
per garment the Chamfer distance [mm] of X_init and of X_LG to T (``unsew.metrics.chamfer_mm``)
and their ratio, and the drape's own noise floor: the target pattern draped again on a mesh of
``--floor-scale`` times the edge length, against T (folds of loose cloth land elsewhere on
another mesh; a graded drape cannot be expected much closer to T than that).

``--targets N`` drapes the target pattern on N meshes (edge length times 1, 0.985, 1.015, 0.97,
1.03, ...) and grades the base to each: where a loose drape's folds land depends on its mesh
(a mesh 3 % finer moves the drape by 2-10 mm), so a single ratio is one sample; the summary
prints each and their mean.

Drapes: the simulator (``--drape sim``: ``unsew.dress.dress``: place, sew, settle) or the panels laid flat at
their placement (``--drape flat``: no physics, a check of the geometry alone). ``auto`` uses the
simulator when ``unsew.body.placement.place_garment`` exists.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_grading.py [--drape auto|sim|flat]
     [--edge-length 0.03] [--garments tshirt pants ...] [--passes N] [--targets N] [--flip]
     [--remesh always|stretched] [--length cloth|axial]

``--flip`` negates every change (the t-shirt's hem -10 cm and 10 % narrower, its sleeves +5 cm
and 10 % wider, ...), so each garment is graded in both directions the benchmark names.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

#: edge length factors of the target meshes (``--targets``)
TARGET_SCALES = (1.0, 0.985, 1.015, 0.97, 1.03)

#: garment -> {group: (length change [m], relative girth change)}
CHANGES = {
    "tshirt": {"hem": (0.10, 0.10), "sleeves": (-0.05, -0.10)},
    "dress": {"hem": (-0.15, 0.10), "sleeves": (0.05, 0.10)},
    "pants": {"legs": (-0.10, -0.10)},
    "shorts": {"legs": (0.08, 0.10)},
    "skirt": {"hem": (0.12, -0.10)},
}


def _have_placement() -> bool:
    try:
        from unsew.body.placement import place_garment  # noqa: F401
    except ImportError:
        return False
    return True


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drape", choices=["auto", "sim", "flat"], default="auto")
    ap.add_argument("--edge-length", type=float, default=0.03)
    ap.add_argument("--material", default="cotton")
    ap.add_argument("--garments", nargs="*", default=list(CHANGES))
    ap.add_argument("--samples", type=int, default=20000, help="Chamfer samples per mesh")
    ap.add_argument(
        "--passes", type=int, default=None, help="grading passes (default: GradingSettings.passes)"
    )
    ap.add_argument(
        "--floor-scale", type=float, default=0.97, help="edge length factor of the noise-floor mesh (0: skip)"
    )
    ap.add_argument(
        "--flip",
        action="store_true",
        help="negate every known change (lengths and girths): the opposite case of each garment",
    )
    ap.add_argument(
        "--no-hold-top",
        action="store_true",
        help="let a waist edit move the panel's placement (GradingSettings.hold_top False)",
    )
    ap.add_argument(
        "--remesh",
        choices=["always", "stretched"],
        default="always",
        help="GradingSettings.remesh: mesh every graded pattern afresh, or only when an edge stretched 1.5x",
    )
    ap.add_argument(
        "--length",
        choices=["cloth", "axial"],
        default="cloth",
        help="GradingSettings.length: move open curves by the cloth length to the top opening, "
        "or by the axial distance",
    )
    ap.add_argument(
        "--targets",
        type=int,
        default=1,
        help="target drapes per garment, on meshes of slightly different edge length",
    )
    args = ap.parse_args(argv)
    if args.targets < 1 or args.targets > len(TARGET_SCALES):
        ap.error(f"--targets must be 1 to {len(TARGET_SCALES)}")
    return args


def _drape_fn(args, body):
    """(drape mode "sim" or "flat", the drape function grade() takes) for ``--drape``."""
    from unsew.grading.grade import dress_drape, flat_drape

    mode = args.drape
    if mode == "auto":
        mode = "sim" if _have_placement() else "flat"
    if mode != "sim":
        return mode, flat_drape
    from unsew.body.sdf import BodySDF

    sdf = BodySDF.build(body)

    def drape_fn(p, m, b):
        return dress_drape(p, m, b, material=args.material, sdf=sdf)

    return mode, drape_fn


def _target_pattern(g: str, base, flip: bool):
    """The base pattern of garment ``g`` altered by its known changes (negated with ``flip``)."""
    from unsew.grading.alter import alter_pattern, alteration_groups

    groups = alteration_groups(base)
    target = base
    for key, (dl, dg) in _changes(g, flip).items():
        if key in groups:
            target = alter_pattern(target, groups[key], length=dl, girth=dg)
    return target


class _Case:
    """One grading of garment ``g``'s base to a target drape: the target pattern, its mesh
    ``tm`` and drape ``tx`` (n, 3) [m], the grading result ``res`` and the body."""

    def __init__(self, g, target, tm, tx, res, body):
        self.g, self.target, self.tm, self.tx, self.res, self.body = g, target, tm, tx, res, body


def _edges_of(case: _Case, t, tcontrols) -> list:
    """(panel, edge) pairs of the target pattern that form target contour ``t``."""
    from unsew.grading.curves import curves_of_contour

    curves = curves_of_contour(t.contour.indices, case.tx, case.target, case.tm, tcontrols)
    return [(c.panel, e) for c in curves for e in c.edges]


def _rest_lengths(case: _Case, tgt, tcontrols) -> tuple[dict, dict]:
    """The true patterns' rest cloth lengths of every target contour [m] (contour index ->
    length), on the target's mesh and on the base's (unsew.grading.cloth)."""
    from unsew.grading.cloth import rest_cloth_lengths, top_contour

    ttop = top_contour(tgt)
    top_edges = _edges_of(case, ttop, tcontrols)
    keyed = {t.index: _edges_of(case, t, tcontrols) for t in tgt if t is not ttop}
    keyed = {k: v for k, v in keyed.items() if v}
    rest1 = rest_cloth_lengths(case.tm, keyed, top_edges) if top_edges else {}
    rest0 = rest_cloth_lengths(case.res.mesh_init, keyed, top_edges) if top_edges else {}
    return rest1, rest0


def _contour_rows(case: _Case, flip: bool) -> list[tuple]:
    """Print one row per matched contour; returns (res L, res G, pat L, pat G) [m] of each."""
    import numpy as np

    from unsew.grading.cloth import cloth_lengths
    from unsew.grading.contours import place_contours
    from unsew.pattern.params import PatternParams

    res, tx, tm, g = case.res, case.tx, case.tm, case.g
    sk = case.body.skeleton
    after = place_contours(res.x_draped, res.mesh.faces, sk)
    tgt = place_contours(tx, tm.faces, sk)
    src = place_contours(res.x_init, res.mesh_init.faces, sk)
    tcontrols = PatternParams.build(case.target, tm).controls
    _, cl_t = cloth_lengths(tx, tm.faces, tgt)
    _, cl_s = cloth_lengths(res.x_init, res.mesh_init.faces, src)
    rest1, rest0 = _rest_lengths(case, tgt, tcontrols)
    rows = []
    for m in res.matches:
        s, t = src[m.source], tgt[m.target]
        # the graded contour that corresponds to the target one: same part, nearest centre
        cands = [a for a in after if a.part == s.part] or after
        a = min(cands, key=lambda a: float(np.linalg.norm(a.centre - t.centre)))
        known = _known(g, s.part, flip)
        res_l = (
            abs(a.position - t.position)
            if a.bone is not None and a.bone.part == t.part
            else float(np.linalg.norm(a.centre - t.centre))
        )
        pat_l, pat_g = pattern_residuals(case.target, res.pattern, _edges_of(case, t, tcontrols))
        # cloth: the drapes' cloth-length difference (target - base) grading reads; rest: the
        # true patterns' own, at rest (unsew.grading.cloth)
        cloth = cl_t[t.index] - cl_s[s.index] if t.index in cl_t and s.index in cl_s else float("nan")
        rest = rest1[t.index] - rest0[t.index] if t.index in rest1 and t.index in rest0 else float("nan")
        print(
            f"{g:<8} {s.part:<10} {known[0] * 100:>+11.1f} {known[1] * 100:>+10.0f} "
            f"{m.axial_distance * 100:>+9.1f} {m.girth_difference * 100:>+9.1f} {res_l * 100:>9.2f} "
            f"{abs(a.length - t.length) * 100:>9.2f} {pat_l * 100:>9.2f} {pat_g * 100:>9.2f} "
            f"{cloth * 100:>+9.1f} {rest * 100:>+8.1f}"
        )
        rows.append((res_l, abs(a.length - t.length), pat_l, pat_g))
    return rows


def _grade_target(g, target, start, scale, args, body, drape_fn) -> _Case:
    """Drape garment g's target pattern on a mesh of ``scale`` times the edge length and grade
    the base to it; start = (base pattern, its mesh, its drape (n, 3) [m])."""
    from unsew.grading.grade import GRADE_SETTINGS, GradingSettings, grade
    from unsew.meshing.sew import mesh_pattern

    base, bm, bx = start
    tm = mesh_pattern(target, edge_length=args.edge_length * scale)
    tx = drape_fn(target, tm, body)
    kw = {"hold_top": not args.no_hold_top, "remesh": args.remesh, "length": args.length}
    if args.passes is not None:
        kw["passes"] = args.passes
    settings = GradingSettings(drape=GRADE_SETTINGS.replace(edge_length=args.edge_length), **kw)
    res = grade(base, body, tx, tm.faces, settings, drape_fn=drape_fn, mesh=bm, x_init=bx)
    return _Case(g, target, tm, tx, res, body)


def _chamfers(case: _Case, scale, args, drape_fn) -> tuple[float, float, float]:
    """Chamfer [mm] of X_init and of X_LG to T, and of the target re-draped on a mesh of
    ``--floor-scale`` times its edge length (nan when 0)."""
    from unsew.meshing.sew import mesh_pattern
    from unsew.metrics.surface import chamfer_mm

    res, tx, tm, n = case.res, case.tx, case.tm, args.samples
    before = chamfer_mm(res.x_init, res.mesh_init.faces, tx, tm.faces, n_samples=n).mean_mm
    graded = chamfer_mm(res.x_draped, res.mesh.faces, tx, tm.faces, n_samples=n).mean_mm
    floor = float("nan")
    if args.floor_scale > 0:
        fm = mesh_pattern(case.target, edge_length=args.edge_length * scale * args.floor_scale)
        floor = chamfer_mm(drape_fn(case.target, fm, case.body), fm.faces, tx, tm.faces, n_samples=n).mean_mm
    return before, graded, floor


def _print_summary(summary, worst, args) -> None:
    import numpy as np

    print()
    print(
        f"{'garment':<8} {'target':>6} {'Chamfer base mm':>15} {'graded mm':>10} {'ratio':>6} "
        f"{'floor mm':>9} {'floor ratio':>11} {'edit':>5} {'remeshed':>8} {'time s':>7}"
    )
    for g, ti, b, a, fl, f, rm, dt in summary:
        r = lambda v: v / b if b > 0 else float("nan")  # noqa: E731
        print(
            f"{g:<8} {ti:>6} {b:>15.1f} {a:>10.1f} {r(a):>6.2f} {fl:>9.1f} {r(fl):>11.2f} {f:>5.2f} "
            f"{str(rm):>8} {dt:>7.1f}"
        )
    if args.targets > 1:
        for g in args.garments:
            rows = [x for x in summary if x[0] == g]
            b, a, fl = (float(np.mean([x[k] for x in rows])) for k in (2, 3, 4))
            ratios = [x[3] / x[2] for x in rows if x[2] > 0]
            print(
                f"{g:<8} {'mean':>6} {b:>15.1f} {a:>10.1f} {float(np.mean(ratios)):>6.2f} {fl:>9.1f} "
                f"{fl / b:>11.2f}"
            )
    print(
        "floor: the target pattern draped on a second mesh, against the target drape (the drape's own noise)"
    )
    print()
    print(
        f"{'garment':<8} {'worst res L cm':>14} {'res G cm':>9} {'pat L cm':>9} {'pat G cm':>9}   (over "
        "contours and targets)"
    )
    for g, w in worst.items():
        print(f"{g:<8} {w[0] * 100:>14.2f} {w[1] * 100:>9.2f} {w[2] * 100:>9.2f} {w[3] * 100:>9.2f}")


def main(argv=None) -> None:
    args = _parse(argv)

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from unsew.body.body import default_body
    from unsew.meshing.sew import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    body = default_body()
    mode, drape_fn = _drape_fn(args, body)
    flipped = "; changes negated (--flip)" if args.flip else ""
    print(
        f"drape: {mode}; edge length {args.edge_length} m; material {args.material}; length "
        f"{args.length}{flipped}"
    )
    head = (
        f"{'garment':<8} {'contour':<10} {'known dL cm':>11} {'known dG %':>10} {'axial cm':>9} "
        f"{'girth cm':>9} {'res L cm':>9} {'res G cm':>9} {'pat L cm':>9} {'pat G cm':>9} {'cloth cm':>9} "
        f"{'rest cm':>8}"
    )
    print(head)
    print("-" * len(head))
    summary = []
    worst: dict = {}  # garment -> worst (res L, res G, pat L, pat G) over its contours and targets [m]
    for g in args.garments:
        base = make_base_pattern(g)
        target = _target_pattern(g, base, args.flip)
        bm = mesh_pattern(base, edge_length=args.edge_length)
        bx = drape_fn(base, bm, body)
        for ti, scale in enumerate(TARGET_SCALES[: args.targets]):
            t0 = time.perf_counter()
            case = _grade_target(g, target, (base, bm, bx), scale, args, body, drape_fn)
            res = case.res
            for got in _contour_rows(case, args.flip):
                worst[g] = [float(np.nanmax([w, v])) for w, v in zip(worst.get(g, got), got)]
            for r in res.table:
                if r["source_contour"] is None or r["target_contour"] is None:
                    print(f"{g:<8} unmatched: {r['source_contour'] or r['target_contour']}")
            before, graded, floor = _chamfers(case, scale, args, drape_fn)
            summary.append(
                (g, ti, before, graded, floor, res.fraction, res.remeshed, time.perf_counter() - t0)
            )
    _print_summary(summary, worst, args)


def pattern_residuals(true, graded, edges) -> tuple[float, float]:
    """How far the graded pattern's open edges are from the true pattern's: (length [m], girth [m]).

    true, graded: patterns of the same topology (the target's altered base and the graded base).
    edges: (panel name, edge index) pairs that form one contour.
    length: the largest, over the edges, |reach(graded) - reach(true)|, where an edge's reach is
    how far its chord's midpoint lies beyond the panel's opposite extreme, along the true edge's
    outward normal (a hem lowered by 5 cm reaches 5 cm further; moving the whole panel changes
    nothing). girth: |sum of the graded edges' arc lengths - sum of the true ones'|. (nan, nan)
    when ``edges`` is empty.
    """
    import numpy as np

    from unsew.pattern.curves import edge_length

    if not edges:
        return float("nan"), float("nan")
    dl = []
    for name, i in edges:
        tp, gp = true.panels[name], graded.panels[name]
        e = tp.edges[i]
        a, b = tp.vertices[e.start], tp.vertices[e.end]
        w = (b - a) / np.linalg.norm(b - a)
        n = np.array([w[1], -w[0]])  # outward for a counter-clockwise panel (unsew.grading.alter)

        def reach(panel):
            mid = 0.5 * (panel.vertices[e.start] + panel.vertices[e.end])
            return float(mid @ n - (panel.vertices @ n).min())

        dl.append(abs(reach(gp) - reach(tp)))
    dg = sum(edge_length(graded.panels[p], i) for p, i in edges) - sum(
        edge_length(true.panels[p], i) for p, i in edges
    )
    return float(max(dl)), float(abs(dg))


def _changes(garment: str, flip: bool) -> dict:
    """CHANGES[garment], every length and girth change negated when ``flip``."""
    return {k: ((-dl, -dg) if flip else (dl, dg)) for k, (dl, dg) in CHANGES[garment].items()}


def _known(garment: str, part: str, flip: bool = False) -> tuple[float, float]:
    """The known (length [m], relative girth) change of the contour on ``part``."""
    ch = _changes(garment, flip)
    if part in ("left_arm", "right_arm"):
        return ch.get("sleeves", (0.0, 0.0))
    if part in ("left_leg", "right_leg"):
        return ch.get("legs", (0.0, 0.0))
    return (0.0, 0.0)  # torso/head: the hem or the neckline/waist; see the table's axial column


if __name__ == "__main__":
    main()
