"""How much of a banded target's top loop is its simulator's contact gap, and which fits read it off?

For each foreign case whose recorded fit chose a banded base (benchmarks/foreign/fits.json; or
``--cases``), prints the target's contact gap (1st percentile of its vertices' distances to the
body [mm], ``unsew.grading.band_gap``), its top loop (the highest open contour): length [m] and
median distance to the body [mm], the length grading's ``band_gap: target`` reads off a band
graded to it (``pressed_loop_excess`` [cm]; "-" when the loop does not press on the body), whether
the garment hangs from its band (``hangs_from_band``: the reading is used), and the true pattern's
waistband (``waistband_front``) top and bottom edge lengths [m] (times two: the band's girth at
rest, as the true pattern cuts it).

    python -m benchmarks band_gap [--cases a,b]

docs/benchmarks.md, "Waistbands sized for unsew's contact".
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import warnings
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"
RECORD = ROOT / "benchmarks" / "foreign" / "fits.json"


def band_edges(pattern) -> tuple[float, float] | None:
    """(top, bottom) edge lengths [m] of ``pattern``'s front waistband, each times two (front and
    back pieces alike), by placed height: the edges wholly in its upper and lower half; None
    without a band."""
    from unsew.pattern.curves import edge_length

    b = pattern.panels.get("waistband_front")
    if b is None:
        return None
    ys = b.to_world(b.vertices)[:, 1]
    mid = 0.5 * (float(ys.min()) + float(ys.max()))
    top = sum(edge_length(b, k) for k, e in enumerate(b.edges) if ys[e.start] > mid and ys[e.end] > mid)
    low = sum(edge_length(b, k) for k, e in enumerate(b.edges) if ys[e.start] < mid and ys[e.end] < mid)
    return 2.0 * top, 2.0 * low


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="", help="comma-separated case names (default: every recorded banded fit)")
    args = ap.parse_args(argv)

    import numpy as np

    from unsew.body.case import load_case
    from unsew.geometry.distance import point_mesh_distance
    from unsew.grading.band_gap import GAP_PERCENTILE, hangs_from_band, pressed_loop_excess
    from unsew.grading.contours import place_contours
    from unsew.io.garmentcode import load_pattern

    rec = json.loads(RECORD.read_text())
    names = [c for c in args.cases.split(",") if c] or sorted(
        n for n, r in rec.items() if "band" in str(r.get("base")) or "darts" in str(r.get("base")))
    unknown = [c for c in names if not (CASES / c).is_dir()]
    if unknown:
        print(f"band_gap: no such case: {', '.join(unknown)}", file=sys.stderr)
        return 2
    print("| case | gap mm | top loop m | its median distance mm | excess cm | hangs from band | true band top / bottom m |")
    print("|---|---|---|---|---|---|---|")
    for name in names:
        case = load_case(CASES / name)
        tv = np.asarray(case.target_verts, dtype=np.float64)
        body = case.body
        d = point_mesh_distance(tv, np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces))
        tgt = place_contours(tv, case.target_faces, body.skeleton)
        top = max(tgt, key=lambda c: float(c.centre[1]))
        ex = pressed_loop_excess(tv, tgt, body).get(int(top.index))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            gt = load_pattern(CASES / name / "pattern_gt.json") if (CASES / name / "pattern_gt.json").is_file() else None
        be = band_edges(gt) if gt is not None else None
        print(f"| {name} | {np.percentile(d, GAP_PERCENTILE) * 1e3:.1f} | {top.length:.3f} | "
              f"{np.median(d[np.asarray(top.contour.indices)]) * 1e3:.1f} | {'-' if ex is None else f'{ex * 100:.2f}'} | "
              f"{'yes' if hangs_from_band(tgt) else 'no'} | {'-' if be is None else f'{be[0]:.3f} / {be[1]:.3f}'} |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
