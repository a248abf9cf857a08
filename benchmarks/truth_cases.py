"""Known-truth case folders for the benchmarks that dress a case's *true* pattern from scratch
(bench_fabric_gap.py, bench_mesh_floor.py): the folder checks and the loading they share."""

from __future__ import annotations

import json
from pathlib import Path


def check_case_dirs(ap, dirs) -> None:
    """``ap.error`` (one line, exit 2) unless every folder holds a meta.json."""
    for d in dirs:
        if not (Path(d) / "meta.json").is_file():
            ap.error(f"{d}: not a case folder (no meta.json)")


def truth_cases(dirs):
    """For each case folder with pattern_gt.json and a library ``truth.material`` in meta.json
    (as benchmarks/make_cases.py and bench_fit.py write them), yield ``(name, case, truth, sdf,
    target_verts, target_faces)``: the loaded case, the true material's library name, the body's
    SDF and the target as numpy arrays. Other folders are named on stdout and skipped; a folder
    that does not load ends the run with its one-line reason."""
    import numpy as np

    from unsew.body.sdf import BodySDF
    from unsew.errors import InputError
    from unsew.body.case import load_case
    from unsew.sim.material import MATERIALS

    for d in map(Path, dirs):
        truth = json.loads((d / "meta.json").read_text()).get("truth", {}).get("material")
        try:
            case = load_case(d)
        except InputError as exc:
            raise SystemExit(f"{d}: {exc}") from None
        if case.pattern_gt is None or truth not in MATERIALS:
            print(f"{d.name:<12} skipped: no pattern_gt.json or no known truth.material in meta.json")
            continue
        yield (d.name, case, truth, BodySDF.build(case.body), np.asarray(case.target_verts),
               np.asarray(case.target_faces))
