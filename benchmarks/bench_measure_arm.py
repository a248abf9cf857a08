"""Where does the upper arm's girth cut reach the armpit, and what does measure_body read instead?

For every body of the foreign benchmark's cases (one case folder per body key, the body as the
fit loads it: anny bodies with their skeleton, GarmentCode's rigged from the mesh) and the
default body, cuts the left upper arm perpendicular to its bone at 30, 40 and 50 % of its length
from the shoulder (:func:`unsew.body.measure.upper_arm_cut`) and prints each girth [m], the
ratio of the 30 % cut to the 40 % one (above ``ARM_CUT_JUMP`` the 30 % cut reached the armpit),
and the girth ``measure_body`` reports, which sizes the base patterns' sleeves.

Run: PYTHONPATH=src:benchmarks .venv/bin/python -m benchmarks measure_arm
     [--cases benchmarks/foreign/cases]
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=str(HERE / "foreign" / "cases"), help="folder of case folders")
    args = ap.parse_args()

    from unsew.body.body import default_body
    from unsew.body.case import load_case
    from unsew.body.measure import ARM_CUT_JUMP, measure_body, upper_arm_cut
    from unsew.errors import InputError

    if not Path(args.cases).is_dir():
        raise InputError(f"--cases {args.cases} is not a folder of case folders")
    bodies = [("unsew default", default_body())]
    seen = set()
    for d in sorted(Path(args.cases).iterdir()):
        meta = d / "meta.json"
        if not meta.is_file():
            continue
        key = json.loads(meta.read_text())["source"]["body_key"]
        if key not in seen:
            seen.add(key)
            bodies.append((key, load_case(d).body))
    print(f"ARM_CUT_JUMP = {ARM_CUT_JUMP}\n")
    print("| body | cut 30 % [m] | cut 40 % [m] | cut 50 % [m] | 30 / 40 | measure_body upper_arm [m] |")
    print("|---|---|---|---|---|---|")
    for key, b in bodies:
        sk = b.skeleton
        args3 = (b.verts, b.faces, b.vertex_parts(), sk.position("left_shoulder"), sk.position("left_elbow"))
        g = [upper_arm_cut(*args3, t) for t in (0.3, 0.4, 0.5)]
        print(f"| {key} | {g[0]:.3f} | {g[1]:.3f} | {g[2]:.3f} | {g[0] / g[1]:.2f} | {measure_body(b).upper_arm:.3f} |")


if __name__ == "__main__":
    main()
