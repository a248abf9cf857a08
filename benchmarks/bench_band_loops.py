"""How long is a draped waistband's top loop against its cloth, on targets unsew did not make?

For every foreign case whose true pattern has a waistband (``unsew.grading.grade.waistbands``),
prints the rest length of the bands' open (top) edges in pattern_gt.json [m], the length of the
target's highest boundary loop [m] and their ratio. The grading bound
``unsew.grading.guards.bounded_band`` rests on the ratio never being below 1: a band drapes
stretched or at rest, never gathered shorter than its cloth.

    python -m benchmarks band_loops [--cases ID ...]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"


def top_loop_length(verts: np.ndarray, faces: np.ndarray) -> float:
    """Length [m] of the boundary loop (:func:`unsew.losses.contours.open_contours`) of a garment
    surface (verts (V, 3) float64 [m], faces (F, 3) int) whose centre lies highest (y up); NaN
    for a closed mesh."""
    from unsew.losses.contours import open_contours

    loops = open_contours(verts, faces)
    return max(loops, key=lambda c: float(c.centre[1])).length if loops else float("nan")


def band_rest_length(pattern) -> float:
    """Rest length [m] of the open edges of the waistbands of ``pattern`` (0.0 without bands)."""
    from unsew.grading.curves import stitched_edges
    from unsew.grading.grade import waistbands
    from unsew.pattern.curves import edge_length

    stitched = stitched_edges(pattern)
    return float(sum(edge_length(pattern.panels[n], k) for n in waistbands(pattern)
                     for k in range(len(pattern.panels[n].edges)) if (n, k) not in stitched))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", help="case ids (default: every committed foreign case)")
    args = ap.parse_args()
    import warnings

    import trimesh

    from unsew.io.garmentcode import load_pattern

    warnings.simplefilter("ignore")  # the readers' notes on GarmentCode's own samples

    ids = args.cases or sorted(p.name for p in CASES.iterdir() if (p / "pattern_gt.json").is_file())
    rows = []
    for cid in ids:
        pattern = load_pattern(CASES / cid / "pattern_gt.json")
        rest = band_rest_length(pattern)
        if rest <= 0:
            continue
        m = trimesh.load(CASES / cid / "target.obj", process=False)
        loop = top_loop_length(np.asarray(m.vertices), np.asarray(m.faces))
        rows.append((cid, rest, loop, loop / rest))
    rows.sort(key=lambda r: r[3])
    print("| case | band top rest [m] | target top loop [m] | loop / rest |")
    print("|---|---|---|---|")
    for cid, rest, loop, ratio in rows:
        print(f"| {cid} | {rest:.3f} | {loop:.3f} | {ratio:.3f} |")
    if rows:
        r = np.array([x[3] for x in rows])
        print(f"\n{len(rows)} banded cases: loop / rest min {r.min():.3f}, median {np.median(r):.3f}, max {r.max():.3f}")


if __name__ == "__main__":
    main()
