"""Meshing benchmark: every base pattern at 1, 2 and 3 cm target edge length.

Prints, per pattern and edge length: 2D vertices (U), sewn vertices (X), triangles, the smallest
triangle angle [deg], the number of inverted/degenerate triangles, the meshing time [ms] (best of
``--repeat`` runs of ``mesh_pattern``) and the time to build the K -> U parameter maps [ms]
(``PatternParams.build``: symmetry, curve frames, mean value coordinates).

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_meshing.py [--repeat 3] [--no-params]

``--last-bits SPEC.json ...``: each specification meshed (2.5 cm) as read and with its numbers moved
by up to two bits (``--trials`` draws: what another CPU's arithmetic does to them), with Triangle
given the outline on its 1 nm grid (as unsew meshes) and as it is; prints the sewn vertex counts
and how many draws gave the very mesh of the specification as read (docs/decisions/041).
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-params", action="store_true", help="skip timing PatternParams.build")
    ap.add_argument("--garments", nargs="*", default=["tshirt", "dress", "pants", "shorts", "skirt"])
    ap.add_argument("--last-bits", nargs="+", metavar="SPEC", help="specifications moved in their last bits")
    ap.add_argument("--trials", type=int, default=4)
    args = ap.parse_args(argv)
    if args.last_bits:
        return last_bits(args.last_bits, args.trials)

    import torch

    torch.set_num_threads(1)
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.params import PatternParams

    head = (
        f"{'pattern':<8} {'h [cm]':>6} {'U verts':>8} {'X verts':>8} {'triangles':>9} {'min angle':>9} "
        f"{'bad':>4} {'mesh [ms]':>9}"
    )
    if not args.no_params:
        head += f" {'params [ms]':>11}"
    print(head)
    print("-" * len(head))
    for g in args.garments:
        pat = make_base_pattern(g)
        for h in (0.01, 0.02, 0.03):
            best = float("inf")
            for _ in range(max(1, args.repeat)):
                t0 = time.perf_counter()
                m = mesh_pattern(pat, edge_length=h)
                best = min(best, time.perf_counter() - t0)
            q = m.quality()
            row = (
                f"{g:<8} {h * 100:>6.0f} {q['uv_vertices']:>8} {q['sewn_vertices']:>8} {q['triangles']:>9} "
                f"{q['min_angle_deg']:>9.2f} {q['bad_triangles']:>4} {best * 1e3:>9.1f}"
            )
            if not args.no_params:
                t0 = time.perf_counter()
                PatternParams.build(pat, m)
                row += f" {(time.perf_counter() - t0) * 1e3:>11.0f}"
            print(row, flush=True)


def _moved(value, rng):
    """A specification's JSON with every float moved by -2..2 units in its last place."""
    import numpy as np

    if isinstance(value, float):
        return float(value * (1.0 + int(rng.integers(-2, 3)) * np.finfo(float).eps / 2))
    if isinstance(value, list):
        return [_moved(v, rng) for v in value]
    if isinstance(value, dict):
        return {k: _moved(v, rng) for k, v in value.items()}
    return value


def last_bits(specs, trials: int) -> None:
    import json
    import tempfile
    import warnings
    from pathlib import Path

    import numpy as np

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern, triangulate

    def mesh(spec: dict):
        with tempfile.TemporaryDirectory() as d, warnings.catch_warnings():
            warnings.simplefilter("ignore")  # seam length notes
            (Path(d) / "p.json").write_text(json.dumps(spec))
            return mesh_pattern(load_pattern(Path(d) / "p.json"), edge_length=0.025)

    on_grid = triangulate._on_grid
    print(f"{'specification':<24} {'grid':<4} {'as read':>7}  {'moved (sewn vertices)':<36} {'same mesh':>9}")
    for path in specs:
        spec = json.loads(Path(path).read_text())
        name = Path(path).parent.name if Path(path).name == "pattern_gt.json" else Path(path).stem
        for grid in (True, False):
            triangulate._on_grid = on_grid if grid else (lambda b: np.array(b, copy=True))
            try:
                ref = mesh(spec)
                runs = [mesh(_moved(spec, np.random.default_rng(s))) for s in range(trials)]
            finally:
                triangulate._on_grid = on_grid
            same = sum(m.n_x == ref.n_x and np.array_equal(m.faces, ref.faces) for m in runs)
            counts = " ".join(str(m.n_x) for m in runs)
            print(f"{name:<24} {'yes' if grid else 'no':<4} {ref.n_x:>7}  {counts:<36} {same:>5} of {trials}")


if __name__ == "__main__":
    main()
