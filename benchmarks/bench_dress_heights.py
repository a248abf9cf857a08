"""How far do dressed garments move up and down from where they were placed (the rise and drop checks)?

Dresses each GarmentCode design case's ``pattern_gt.json`` on its own body in-process
(:func:`unsew.dress.dress`, its defaults, as ``unsew drape`` does) and prints per case, from the
placed vertices (``Dressed.x_start``) to the drape: the share of vertices that ended more than
RISE_DIST above where they were placed [%] (the rise check of :mod:`unsew.sim.checks`), the
median of the vertices' drops [m] (the drop check), the drop of the mean height [m] (the drop
check before it was judged vertex by vertex), how far the lowest point rose [m], and the verdict.

    python -m benchmarks dress_heights --cases /work/gcd-all --only gc_s1_000 gc_s3_005
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent


def heights_row(case: Path) -> dict:
    """The figures of the module docstring for one case folder (pattern_gt.json, body.obj and,
    when there, skeleton.json)."""
    from unsew.body.body import load_body
    from unsew.dress import dress
    from unsew.io.garmentcode import load_pattern
    from unsew.sim.checks import check_dressed

    skel = case / "skeleton.json"
    body = load_body(case / "body.obj", skel if skel.is_file() else None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's mirrored panels and uneven seams
        pattern = load_pattern(case / "pattern_gt.json")
    d = dress(pattern, body)
    v = check_dressed(d, body=body)
    y0, y = np.asarray(d.x_start)[:, 1], d.x.numpy()[:, 1]
    return {
        "case": case.name,
        "rise_pct": v.rise_pct,
        "drop_median_m": v.drop,
        "drop_mean_m": float(y0.mean() - y.mean()),
        "low_rise_m": float(y.min() - y0.min()),
        "stretch_max": v.stretch_max,
        "verdict": v.reason or "ok",
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=Path, default=HERE / "gcd" / "cases", help="folder of case folders")
    ap.add_argument("--only", nargs="*", default=None, help="case ids (default: every gc_* folder)")
    args = ap.parse_args(argv)
    if not args.cases.is_dir():
        print(f"dress_heights: no cases folder {args.cases}", file=sys.stderr)
        return 2
    ids = args.only or sorted(p.name for p in args.cases.iterdir() if p.name.startswith("gc_"))
    print("| case | rise % | drop median m | drop mean m | lowest point rose m | stretch max | verdict |")
    print("|---|---|---|---|---|---|---|")
    for cid in ids:
        try:
            r = heights_row(args.cases / cid)
        except Exception as exc:  # a case that cannot be dressed: its one line, and on
            print(f"| {cid} | | | | | | error: {str(exc).splitlines()[0]} |", flush=True)
            continue
        print(
            f"| {r['case']} | {r['rise_pct']:.1f} | {r['drop_median_m']:.3f} | {r['drop_mean_m']:.3f} "
            f"| {r['low_rise_m']:.3f} | {r['stretch_max']:.2f} | {r['verdict']} |",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
