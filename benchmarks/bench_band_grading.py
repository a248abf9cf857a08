"""How well does grading size a banded base to foreign targets with a waistband?

For each case (default: the three foreign cases whose fit chose a banded base), runs phase one
alone, ``python -m unsew grade CASE --base BASE --edge-length 0.025``, and prints the graded
pattern's errors against pattern_gt.json (unsew.metrics.panels.pattern_metrics: area-weighted
with unmatched panels at 100 %, total, mean over matched panels) [%], the graded band's height
(bounding box of ``waistband_front``) [cm] beside the true band's, the graded drape's Chamfer
to the target [mm], and the placement choice (unsew.grading.placement): the height of the target's
waist above the graded drape's [cm], the lift kept [cm] and the Chamfer of the drape at the
graded placement [mm] (the Chamfer column is the kept placement's; the cases with a lift kept are
the ones it moved).

    python -m benchmarks band_grading [--cases CASE:BASE ...] [--out DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"
DEFAULT = ["shorts_short__default:shorts_band", "trousers_tapered__male_heavy:pants_band",
           "skirt_pencil_mini__tpose:skirt_band"]


def _band_height_cm(pattern) -> float | None:
    p = pattern.panels.get("waistband_front")
    if p is None:
        return None
    y = p.vertices[:, 1]
    return float(y.max() - y.min()) * 100.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="+", default=DEFAULT, metavar="CASE:BASE")
    ap.add_argument("--out", type=Path, default=None, help="keep the graded folders here")
    args = ap.parse_args()

    import numpy as np
    import trimesh
    from tables import print_table

    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import pattern_metrics
    from unsew.metrics.surface import surface_metrics

    out = args.out or Path(tempfile.mkdtemp(prefix="band_grading_"))
    rows = []
    for cb in args.cases:
        case, base = cb.split(":")
        res = out / case
        cmd = [sys.executable, "-m", "unsew", "grade", str(CASES / case), "--base", base, "--edge-length", "0.025",
               "--out", str(res), "--overwrite"]
        env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if proc.returncode != 0:
            rows.append({"case": case, "base": base, "error": (proc.stderr.strip().splitlines() or ["?"])[-1]})
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            est, gt = load_pattern(res / "pattern.json"), load_pattern(CASES / case / "pattern_gt.json")
        m = pattern_metrics(est, gt)
        t = trimesh.load(CASES / case / "target.obj", process=False)
        g = trimesh.load(res / "garment.obj", process=False)
        cf = surface_metrics(np.asarray(g.vertices), np.asarray(g.faces), np.asarray(t.vertices), np.asarray(t.faces),
                             n_samples=20000, seed=0)["chamfer_mm"]
        lift = json.loads((res / "contours.json").read_text()).get("placement") or {}
        rows.append({"case": case, "base": base, "area_pct": 100 * m["area_error_weighted_rel"],
                     "total_pct": 100 * m["area_error_total_rel"], "matched_pct": 100 * m["area_error_rel_mean"],
                     "band_cm": _band_height_cm(est), "true_band_cm": _band_height_cm(gt), "chamfer_mm": cf,
                     "waist_cm": 100 * lift["wanted_m"] if lift else None,
                     "lift_cm": 100 * lift["lift_m"] if lift else None,
                     "unlifted_mm": lift["chamfer_mm"][0] if lift else None})
        print(rows[-1], flush=True)
    print_table(rows, ["case", "base", "area_pct", "total_pct", "matched_pct", "band_cm", "true_band_cm", "chamfer_mm",
                       "waist_cm", "lift_cm", "unlifted_mm", "error"],
                title=f"grading banded bases (results in {out})", digits=1)


if __name__ == "__main__":
    main()
