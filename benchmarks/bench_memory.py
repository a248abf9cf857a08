"""Peak memory and time of a fit's 3D metrics for targets of 2K-50K vertices, incl. triangles 100x
the median and a result 30 cm from the target.

    PYTHONPATH=src python -m benchmarks memory [--samples 50000 100000] [--result-verts 5000]

Target: a garment-like tube (benchmarks/_meshes.py) of 2K, 10K, 20K and 50K vertices; at 50K also
one whose hem band has triangles 100x the median area ("uneven"). Result: a 5K-vertex tube of
another tessellation, 5 mm outside the target, or 30 cm outside it ("30 cm away"). Measured:
:func:`unsew.metrics.surface.surface_metrics` (what metrics.json's "surface" holds; a fit computes
it up to three times, with 50K samples per mesh, ``unsew eval`` once with 100K) and the report's
per-vertex distance (:func:`unsew.metrics.surface.closest_points` of the result's vertices).

``--fit DIR``: also a whole fit (small mode: 4 cm mesh, 3 iterations, as tests/fit) of a known-truth
t-shirt whose target is the true drape subdivided (flat, the surface unchanged) to each size;
each fit in a fresh process, its peak resident memory as recorded in its metrics.json.

"peak MB" is the growth of the process's peak resident memory (VmHWM, reset before each row) over
its size at the start of the row; "process peak MB" the whole process's peak then. Prints tables;
never asserts timings.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _parse(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument(
        "--samples", type=int, nargs="+", default=[50_000, 100_000], help="points sampled per mesh"
    )
    ap.add_argument("--result-verts", type=int, default=5000)
    ap.add_argument(
        "--sizes", type=int, nargs="+", default=[2000, 10000, 20000, 50000], help="target vertices"
    )
    ap.add_argument(
        "--fit", metavar="DIR", help="also run a whole small fit per target size in DIR (minutes each)"
    )
    return ap.parse_args(argv)


def main(argv=None) -> None:
    args = _parse(argv)

    import numpy as np

    import _meshes
    from tables import print_table
    from unsew._memory import current_rss_mb, peak_rss_mb, reset_peak
    from unsew.metrics.surface import closest_points, surface_metrics

    cases = [(n, False, 0.0) for n in args.sizes]
    big = max(args.sizes)
    cases += [(big, True, 0.0), (big, False, 0.3), (big, True, 0.3)]
    rows = []
    for n_target, uneven, away in cases:
        tv, tf = _meshes.tube_with_verts(n_target, uneven=uneven)
        rv, rf = _meshes.tube_with_verts(args.result_verts, radius=_meshes.RADIUS + 0.005 + away)
        a = _meshes.face_areas(tv, tf)
        for ns in args.samples:
            reset_peak()
            base = current_rss_mb()
            t = time.perf_counter()
            m = surface_metrics(rv, rf, tv, tf, n_samples=ns)
            t_metrics = time.perf_counter() - t
            t = time.perf_counter()
            _, d, _ = closest_points(rv, tv, tf)
            t_report = time.perf_counter() - t
            peak = peak_rss_mb()
            rows.append(
                {
                    "target verts": len(tv),
                    "triangles": len(tf),
                    "max/median area": float(a.max() / np.median(a)),
                    "result verts": len(rv),
                    "away": f"{away * 100:g} cm",
                    "samples/mesh": ns,
                    "metrics s": t_metrics,
                    "report distances s": t_report,
                    "peak MB": None if base is None else peak - base,
                    "process peak MB": peak,
                    "chamfer mm": m["chamfer_mm"],
                }
            )
            print(rows[-1], flush=True) if os.environ.get("BENCH_VERBOSE") else None
    print_table(
        rows,
        title="3D metrics of a fit (surface_metrics + the report's per-vertex distances): time [s] and peak "
        "memory [MB]",
        digits=2,
    )
    if args.fit:
        print_table(
            _fit_rows(args.sizes, args.fit),
            title="Whole small fits (peak memory from metrics.json)",
            digits=2,
        )


#: tests/fit/test_fit_small.py's small mode
SMALL = {
    "drape.edge_length": 0.04,
    "optimizer.iterations": 3,
    "drape.steps": 8,
    "drape.sew_steps": 60,
    "drape.settle_steps": 20,
    "loss.target_points": 1500,
    "material.start_iteration": 1,
    "material.start": "cotton",
}

_FIT = """
import sys
from pathlib import Path
from unsew.fit.config import FitConfig
from unsew.fit.run import run_fit
from unsew.body.case import load_case
run_fit(load_case(sys.argv[1]), FitConfig(**{small!r}), Path(sys.argv[2]), progress=False, log=lambda s: None)
"""


def _fit_rows(sizes, folder) -> list[dict]:
    import json
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    import numpy as np
    import trimesh

    from unsew.fit.config import load_config
    from unsew.fit.demo import make_truth_case
    from unsew.io.mesh import read_mesh, write_obj

    work = Path(folder)
    work.mkdir(parents=True, exist_ok=True)
    base = work / "truth"
    if not (base / "target.obj").is_file():
        make_truth_case(base, settings=load_config(**SMALL).drape)  # as tests/fit/test_fit_small.py
    v0, f0 = read_mesh(base / "target.obj")
    edge = float(np.linalg.norm(v0[f0[:, 0]] - v0[f0[:, 1]], axis=1).mean())
    rows = []
    for n in sizes:
        d = work / f"case_{n}"
        shutil.rmtree(d, ignore_errors=True)
        shutil.copytree(base, d)
        v, f = v0, f0
        if n > len(v0):
            v, f = trimesh.remesh.subdivide_to_size(v0, f0, max_edge=edge * np.sqrt(len(v0) / n) * 1.2)
        write_obj(d / "target.obj", v, f)
        out = work / f"fit_{n}"
        shutil.rmtree(out, ignore_errors=True)
        t = time.perf_counter()
        r = subprocess.run(
            [sys.executable, "-c", _FIT.format(small=SMALL), str(d), str(out)], capture_output=True, text=True
        )
        wall = time.perf_counter() - t
        if r.returncode != 0:
            rows.append({"target verts": len(v), "status": (r.stderr.strip().splitlines() or ["?"])[-1][:80]})
            continue
        m = json.loads((out / "metrics.json").read_text())
        rows.append(
            {
                "target verts": len(v),
                "target triangles": len(f),
                "fit s": m["timings_s"].get("total_s"),
                "wall s": wall,
                "peak MB (metrics.json)": m.get("peak_memory_mb"),
                "chamfer mm": m["surface"]["chamfer_mm"],
                "status": "ok",
            }
        )
        print(rows[-1], file=sys.stderr, flush=True)
    return rows


if __name__ == "__main__":
    main()
