"""The fit's start on each GarmentCode case when meta.json names no type (none of them does): the
design read off the target, the designs drafted from it and the one chosen
(:func:`unsew.fit.start.choose_base` with ``case.design``), against the library's bases of the
read type chosen as when meta.json names it. Only the base choice runs (each candidate dressed
from scratch on its coarse mesh), not grading nor phase two.

With ``--drafts`` no candidate is dressed: the design read first (the first candidate) is drafted
for the case's body and judged against the true pattern (judge.py: panel error, turning
distance), on every case with a target; the table ends with their medians. ``--darts`` judges
each also with its waist darts off and on, and with a bust dart in each front side seam
(:func:`side_darts`).

The target is chosen as in reading.py: newton's drape where the build accepted it, else the true
pattern dressed by ``unsew drape`` (DRAPES/<case>.obj) stands in.
"""

from __future__ import annotations

import dataclasses
import json
import time
import warnings
from pathlib import Path

import numpy as np
import reading as gt_reading

#: The truth's choices shown beside the reading.
SHOWN = ("sleeves", "neck_front", "neck_back", "collar", "skirt", "length", "waistband", "cuffs")


def _case(d: Path, target: Path):
    """The Case of folder ``d`` with the mesh ``target`` as its target and no garment type."""
    from unsew.body.body import load_body
    from unsew.io.case import Case
    from unsew.io.mesh import read_garment

    skel = d / "skeleton.json"
    body = load_body(d / "body.obj", skel if skel.is_file() else None)
    with warnings.catch_warnings():  # a repaired mesh is announced by a warning: not this table's news
        warnings.simplefilter("ignore")
        v, f, _ = read_garment(target)
    return Case(d, "", v, f, body)


def _best(choice) -> tuple[str, float | None, float | None]:
    """(name, distance [mm], torso distance [mm]) of a BaseChoice's chosen candidate."""
    row = choice.table[0] if choice.table else {}
    return choice.name, row.get("chamfer_mm"), row.get("torso_mm")


def start_row(d: Path, source: str, target: Path, *, log) -> dict:
    """One case's row: the truth, the design read, the chosen design and the library's choice."""
    from unsew.errors import InputError
    from unsew.fit.config import FitConfig
    from unsew.fit.material import AUTO_START_MATERIAL
    from unsew.fit.progress import Progress
    from unsew.fit.stages import build_context
    from unsew.fit.start import choose_base, with_garment_read
    from unsew.pattern.base import BASES
    from unsew.sim.material import get_material

    t = gt_reading.truth_of(d)
    row = {"case": d.name, "target": source, "true type": t["type"]}
    row["truth"] = ", ".join(f"{k} {t[k]}" for k in SHOWN if t.get(k) is not None)
    cfg, mat = FitConfig(), get_material(AUTO_START_MATERIAL)
    t0 = time.perf_counter()
    try:
        case = with_garment_read(_case(d, target), cfg, log=log)
    except InputError as exc:
        return {**row, "read": f"refused: {str(exc).splitlines()[0]}"}
    row["read"] = case.design.summary()
    scene = build_context(case, cfg, progress=Progress(False), log=log)
    try:
        design = choose_base(case, scene.target, scene.sdf, scene.cfg, mat, progress=Progress(False), log=log)
    except InputError as exc:
        return {**row, "design": f"refused: {str(exc).splitlines()[0][:200]}"}
    row["design"], row["design_mm"], row["design_torso_mm"] = _best(design)
    row["designs"] = [
        {k: r.get(k) for k in ("base", "chamfer_mm", "torso_mm", "arms", "error")} for r in design.table
    ]
    if case.garment in BASES:
        lib = choose_base(
            dataclasses.replace(case, design=None),
            scene.target,
            scene.sdf,
            scene.cfg,
            mat,
            progress=Progress(False),
            log=log,
        )
        row["library"], row["library_mm"], row["library_torso_mm"] = _best(lib)
    else:
        row["library"] = f"no {case.garment} base"
    row["seconds"] = round(time.perf_counter() - t0, 1)
    return row


def _said(r: dict) -> str:
    """A candidate's row in words: name, distance [mm], over the torso, arms."""
    if r.get("chamfer_mm") is None:
        return f"{r['base']} failed ({r.get('error') or 'no finite distance'})"
    torso = f" (torso {r['torso_mm']:.2f})" if r.get("torso_mm") is not None else ""
    return f"{r['base']} {r['chamfer_mm']:.2f}{torso}" + ("" if r.get("arms") else " (arms differ)")


def summary_row(rows: list[dict]) -> dict:
    """The cases with both a design and a library choice: on how many the chosen design lies closer
    on the distance the choice is made on (over the torso for dresses), and the means [mm]."""
    both = [r for r in rows if r.get("design_mm") is not None and r.get("library_mm") is not None]
    key = [
        ("design_torso_mm", "library_torso_mm")
        if r.get("design_torso_mm") is not None
        else ("design_mm", "library_mm")
        for r in both
    ]
    closer = sum(r[a] < r[b] for r, (a, b) in zip(both, key))
    same = sum(r[a] == r[b] for r, (a, b) in zip(both, key))
    drafted_only = sum(1 for r in rows if r.get("design_mm") is not None and r.get("library_mm") is None)
    return {
        "case": "all",
        "target": f"{len(rows)} cases",
        "design": f"closer on {closer} of {len(both)} (as close on {same}); {drafted_only} without a base",
        "design_mm": float(np.mean([r["design_mm"] for r in both])) if both else None,
        "library_mm": float(np.mean([r["library_mm"] for r in both])) if both else None,
    }


def write_record(record: Path, rows: list[dict]) -> None:
    """Write ``rows`` as a recorded table (benchmarks/report.py's format): each row flat, its
    candidates in words, the commits the rows were measured at."""
    flat = [
        {**r, "designs": "; ".join(map(_said, r["designs"]))} if isinstance(r.get("designs"), list) else r
        for r in rows
    ]
    rec = {
        "title": "GarmentCode cases, the fit's start when meta.json names no type: designs drafted from the "
        "design read off the target against the library's bases of the read type (the base choice only; "
        "distances [mm] on its coarse mesh)",
        "command": "python -m benchmarks gcd starts --out CASES --drapes DRAPES --record --only ...",
        "commit": ", ".join(sorted({r.get("commit", "?") for r in flat})) + " (each row names its own)",
        "rows": [r for r in flat if r["case"] != "all"]
        + [summary_row([r for r in flat if r["case"] != "all"])],
    }
    record.write_text(json.dumps(rec, indent=1) + "\n")


def draft_row(d: Path, source: str, target: Path, *, darts: bool = False) -> dict:
    """One case's row of ``--drafts``: the design read first, drafted for the case's body, judged
    against the true pattern (panel error, turning distance, pieces after merging); with
    ``darts``, also with its waist darts off and on (:func:`darts_both_ways`) and with bust darts
    (:func:`side_darts`)."""
    import judge
    from unsew.body.measure import measure_body
    from unsew.errors import InputError
    from unsew.fit.config import FitConfig
    from unsew.fit.designs import design_candidates, read_measures
    from unsew.fit.start import with_garment_read
    from unsew.io.garmentcode import pattern_to_dict
    from unsew.pattern.design import draft

    t = gt_reading.truth_of(d)
    row = {"case": d.name, "target": source, "true type": t["type"]}
    try:
        case = with_garment_read(_case(d, target), FitConfig(), log=lambda s: None)
        m = measure_body(case.body)
        meas = read_measures(case.target_verts, case.target_faces, case.body.skeleton)
        name, design = design_candidates(case.design, m, measures=meas)[0]
    except InputError as exc:
        return {**row, "design": f"refused: {str(exc).splitlines()[0][:120]}"}
    truth = json.loads((d / "pattern_gt.json").read_text())
    cmp = judge.compare_patterns(truth, pattern_to_dict(draft(design, m)))
    row.update(design=name, panel_err=round(cmp["panel_err"], 3), turning=cmp["turning"])
    row["pieces t/r"] = f"{cmp['panels_true']}/{cmp['panels_rec']}"
    if darts:
        row.update(darts_both_ways(truth, design, m))
        row["turning side darts"] = _with_side_darts(truth, design, m, d)
    return row


#: Where a trial bust dart's centre sits on the front's side seam: this share of the way from the
#: natural waist up to the armpit.
BUST_DART_AT = 0.5


def side_darts(pattern, m, width: float, bust_points: float):
    """A copy of a drafted top or bodice (``pattern``, :class:`unsew.pattern.model.Pattern`, its
    bodice's front named ``front``) with a bust dart cut in each side seam of its front, as GarmentCode's
    fitted bodice has: ``width`` [m] at the mouth, the tip ``0.75 (half width - bust_points / 2)``
    [m] in, its centre :data:`BUST_DART_AT` of the way from the waist to the armpit. The front
    below the dart is lengthened by ``width`` so the side seam's sewn length stays. A trial of the
    judge's measure, not a design the fit drafts. None without a bodice front or a dart over 5 mm."""
    import copy

    from unsew.pattern.base._frame import body_frame
    from unsew.pattern.design._darts import Dart, dart_edge
    from unsew.pattern.model import StitchSide

    front = pattern.panels.get("front")
    if (
        front is None
        or width < 0.005
        or not any(e.label == "right_armhole" or e.label.startswith("top") for e in front.edges)
    ):
        return None  # no bodice front (a skirt's front has no armhole nor top edge)
    p = copy.deepcopy(pattern)
    f = body_frame(m)
    front = p.panels["front"]
    side = next(i for i, e in enumerate(front.edges) if e.label == "right_side")
    a, b = front.vertices[front.edges[side].start], front.vertices[front.edges[side].end]
    length = float(np.linalg.norm(b - a))
    at = float(
        np.clip(
            f.waist_y + BUST_DART_AT * (f.armpit_y - f.waist_y) - front.translation[1],
            0.3 * length,
            0.8 * length,
        )
    )
    depth = 0.75 * (abs(float(a[0])) - bust_points / 2)
    dx, dy = abs(float(b[0] - a[0])), abs(float(b[1] - a[1]))
    verts = front.vertices.copy()  # the side, less the dart's mouth, keeps its length
    verts[verts[:, 1] < a[1] + at, 1] -= float(np.sqrt((length + width) ** 2 - dx**2)) - dy
    front.vertices = verts
    for label in ("right_side", "left_side"):
        front = p.panels["front"]
        e = next(i for i, x in enumerate(front.edges) if x.label == label)
        run = float(np.linalg.norm(front.vertices[front.edges[e].end] - front.vertices[front.edges[e].start]))
        centre = at + width if label == "right_side" else run - at - width
        new, st, pieces = dart_edge(front, e, [Dart(centre, width, depth)], label)
        sewn = pieces[0] if label == "right_side" else pieces[-1]  # the piece nearer the hem

        def moved(s, e=e, sewn=sewn):
            if s.panel != "front" or s.edge < e:
                return s
            return StitchSide("front", s.edge + 3 if s.edge > e else sewn)

        for s in p.stitches:
            s.a, s.b = moved(s.a), moved(s.b)
        p.panels["front"] = new
        p.stitches += st
    return p


def _with_side_darts(truth: dict, design, m, d: Path):
    """The turning distance of ``design`` drafted with its waist darts and :func:`side_darts`
    (the bust dart's width and the bust points' distance from the case's body file, as
    GarmentCode sizes them: ``waist_over_bust_line - waist_line``), or None where it has no
    waist darts or no front."""
    import judge
    import yaml
    from unsew.errors import InputError
    from unsew.io.garmentcode import pattern_to_dict
    from unsew.pattern.design import draft

    body = json.loads((d / "meta.json").read_text())["source"]["body"]["name"]
    sizes = yaml.safe_load((d.parent / "_bodies" / body / "body.yaml").read_text())["body"]
    try:
        darted = draft(design.replace(darts=True), m)
    except InputError:
        return None
    width = (sizes["waist_over_bust_line"] - sizes["waist_line"]) / 100
    p = side_darts(darted, m, width, sizes["bust_points"] / 100)
    return None if p is None else judge.compare_patterns(truth, pattern_to_dict(p))["turning"]


def darts_both_ways(truth: dict, design, m) -> dict:
    """The drafted ``design`` (measurements ``m``) judged against the true specification
    ``truth`` with its waist darts off and on: {"turning no darts", "turning darts", "panel err
    no darts", "panel err darts"}, None where the design space cuts no darts in that design."""
    import judge
    from unsew.errors import InputError
    from unsew.io.garmentcode import pattern_to_dict
    from unsew.pattern.design import draft

    out = {}
    for flag, said in ((False, "no darts"), (True, "darts")):
        try:
            cmp = judge.compare_patterns(truth, pattern_to_dict(draft(design.replace(darts=flag), m)))
        except InputError:  # the design space's own refusal: no darts in this design
            cmp = {"turning": None, "panel_err": None}
        out[f"turning {said}"] = cmp["turning"]
        out[f"panel err {said}"] = cmp["panel_err"]
    return out


def _print_change(rows: list[dict], before: str, after: str, what: str) -> None:
    """One line: the median turning distance of the rows having both keys, ``before`` -> ``after``,
    and on how many rows it is lower after."""
    both = [r for r in rows if r.get(before) is not None and r.get(after) is not None]
    if both:
        a, b = [r[before] for r in both], [r[after] for r in both]
        print(
            f"{len(both)} {what}: turning median {np.median(a):.3f} -> {np.median(b):.3f}, "
            f"lower on {sum(y < x for x, y in zip(a, b))}"
        )


def cmd_drafts(args, case_ids: list[str]) -> int:
    """Print ``--drafts``' rows (:func:`draft_row`) and the medians of their panel error and turning."""
    from tables import print_table

    root = Path(args.out)
    drapes = Path(args.drapes) if args.drapes else None
    rows = []
    for cid in args.only or case_ids:
        tgt = gt_reading.target_of(root, cid, drapes)
        if tgt is None or not (root / cid / "truth.json").is_file():
            continue
        rows.append(draft_row(root / cid, gt_reading.SOURCES[tgt[0]], tgt[1], darts=args.darts))
        print(json.dumps(rows[-1]), flush=True)
    print_table(rows, title=f"The design read first, drafted, against the true pattern ({root})", digits=3)
    e = [r["panel_err"] for r in rows if r.get("panel_err") is not None]
    tu = [r["turning"] for r in rows if r.get("turning") is not None]
    if e:
        print(
            f"{len(e)} of {len(rows)} drafted: panel err median {np.median(e):.3f}, "
            f"turning median {np.median(tu):.3f}"
        )
    if args.darts:
        _print_change(rows, "turning no darts", "turning darts", "drafted with and without waist darts")
        _print_change(
            rows, "turning darts", "turning side darts", "with a bust dart in each front side seam too"
        )
    return 0


def cmd_starts(args, case_ids: list[str], record: Path) -> int:
    """Print one row per case (``args.only`` or all with a target); with ``args.record`` write
    the rows into ``record`` after each case (a case's row replaces its earlier one; each row
    names the commit it was measured at); with ``args.drafts`` :func:`cmd_drafts` instead."""
    if getattr(args, "drafts", False):
        return cmd_drafts(args, case_ids)
    from tables import print_table

    root = Path(args.out)
    drapes = Path(args.drapes) if args.drapes else None
    commit = gt_reading._commit()
    kept = json.loads(record.read_text())["rows"] if args.record and record.is_file() else []
    rows = []
    for cid in args.only or case_ids:
        tgt = gt_reading.target_of(root, cid, drapes)
        if tgt is None or not (root / cid / "truth.json").is_file():
            continue
        row = start_row(root / cid, gt_reading.SOURCES[tgt[0]], tgt[1], log=lambda s: print(s, flush=True))
        row["commit"] = commit
        rows.append(row)
        shown = {k: v for k, v in row.items() if k not in ("designs", "truth", "read")}
        print(json.dumps(shown), flush=True)
        if args.record:
            write_record(record, [r for r in kept if r["case"] not in {q["case"] for q in rows}] + rows)
    cols = ["case", "target", "true type", "design", "design_mm", "design_torso_mm", "library", "library_mm"]
    print_table(
        [{k: r.get(k) for k in cols} for r in rows], title=f"The fit's start, type read ({root})", digits=2
    )
    return 0
