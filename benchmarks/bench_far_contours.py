"""Where does grading match a contour pair farther apart than its centre gate?

``unsew.grading.contours.match_contours`` pairs a source and a target contour only when their
centres lie within MAX_CENTRE_DISTANCE, except for a pair of torso contours that are each the
only one of their mesh (up to FAR_CENTRE_FACTOR times the gate: a long base's hem far below a
short target's). For every foreign case this dresses the base its fit recorded
(benchmarks/foreign/fits.json) or, with ``--all-bases``, every library base of its garment type,
sized to the wearer, in cotton on a mesh of edge ``--edge`` [m] (the base choice's), as a fit's
first grading pass sees it, and prints each pair matched beyond the gate (part, centre distance
[m]) and, for comparison, ``any part``: each pair of contours on one body part, each the only one
of that part on its mesh, between the gate and FAR_CENTRE_FACTOR times it (before the matcher's
other gates: perimeter ratio, plane, and the assignment), i.e. what the rule could reach were it
not held to the torso. A candidate whose openings on the arms differ from the target's is marked: the
base choice never grades it as a runner-up when another candidate's agree.

    python -m benchmarks far_contours [--cases a,b] [--all-bases] [--edge 0.04]

docs/benchmarks.md, "The side seams graded by girth, the default; the only hems matched across
the centre gate".
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"
RECORD = ROOT / "benchmarks" / "foreign" / "fits.json"


def far_pairs(source, target, matches, gate: float) -> list[tuple[str, float]]:
    """(part, centre distance [m]) of each match whose contours' centres lie farther apart than
    ``gate`` [m]."""
    out = []
    for m in matches:
        d = float(np.linalg.norm(source[m.source].centre - target[m.target].centre))
        if d > gate:
            out.append((source[m.source].part, d))
    return out


def lone_far_pairs(source, target, gate: float, factor: float) -> list[tuple[str, float]]:
    """(part, centre distance [m]) of each pair of contours on one part, each the only one of
    that part on its mesh, farther apart than ``gate`` and within ``factor`` x it: what the rule
    would match were it not held to the torso."""
    from unsew.grading.contours import lone_parts

    alone = lone_parts(source) & lone_parts(target)
    out = []
    for s in (s for s in source if s.bone is not None and s.part in alone):
        for t in (t for t in target if t.bone is not None and t.part == s.part):
            d = float(np.linalg.norm(s.centre - t.centre))
            if gate < d <= factor * gate:
                out.append((s.part, d))
    return out


def _fmt(pairs) -> str:
    return ", ".join(f"{p} {d:.2f}" for p, d in pairs) or "-"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="", help="comma-separated case names (default: every recorded case)")
    ap.add_argument("--all-bases", action="store_true", help="every library base of the case's type, not the recorded one")
    ap.add_argument("--edge", type=float, default=0.04, help="mesh edge length of the drapes [m]")
    args = ap.parse_args(argv)
    from unsew.meshing.sew import EDGE_LENGTH_RANGE

    lo, hi = EDGE_LENGTH_RANGE
    if not lo <= args.edge <= hi:
        print(f"far_contours: --edge {args.edge} m is outside [{lo}, {hi}] m", file=sys.stderr)
        return 2

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.errors import InputError
    from unsew.fit.config import FitConfig
    from unsew.fit.start import arm_openings, base_pattern_for
    from unsew.grading.contours import FAR_CENTRE_FACTOR, MAX_CENTRE_DISTANCE, match_contours, place_contours
    from unsew.pattern.base import bases_for, garment_of
    from unsew.sim.material import get_material

    rec = json.loads(RECORD.read_text())
    names = [c for c in args.cases.split(",") if c] or sorted(rec)
    unknown = [c for c in names if not (CASES / c).is_dir()]
    if unknown:
        print(f"far_contours: no such case: {', '.join(unknown)}", file=sys.stderr)
        return 2
    settings = FitConfig().drape.replace(edge_length=args.edge)
    print("| case | base | arms agree | matched beyond the gate | any part |\n|---|---|---|---|---|")
    n, fired, any_part = 0, 0, 0
    for name in names:
        case = load_case(CASES / name)
        garment = json.loads((CASES / name / "meta.json").read_text())["garment"]
        bases = bases_for(garment_of(garment)) if args.all_bases else [rec.get(name, {}).get("base") or garment]
        sdf = BodySDF.build(case.body)
        tgt = place_contours(case.target_verts, case.target_faces, case.body.skeleton)
        want = arm_openings(case.target_verts, case.target_faces, case.body.skeleton)
        for base in bases:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    d = dress(base_pattern_for(case, FitConfig(base=base)), case.body, sdf=sdf,
                              material=get_material("cotton"), settings=settings)
                except (InputError, ValueError, RuntimeError) as exc:
                    print(f"| {name} | {base} | - | failed: {str(exc).splitlines()[0]} | - |")
                    continue
            x = d.x.numpy()
            src = place_contours(x, d.mesh.faces, case.body.skeleton)
            ms = match_contours(src, tgt, case.body.skeleton, garment_centre=x.mean(axis=0))
            far = far_pairs(src, tgt, ms, MAX_CENTRE_DISTANCE)
            lone = lone_far_pairs(src, tgt, MAX_CENTRE_DISTANCE, FAR_CENTRE_FACTOR)
            arms = arm_openings(x, d.mesh.faces, case.body.skeleton) == want
            n, fired, any_part = n + 1, fired + bool(far), any_part + bool(lone)
            print(f"| {name} | {base} | {'yes' if arms else 'no'} | {_fmt(far)} | {_fmt(lone)} |", flush=True)
    print(f"\n{n} drapes: a pair matched beyond the gate on {fired}; on any part the rule would match one on {any_part}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
