"""How long does a fit's drape take with each sparse solver backend, on foreign cases?

For each foreign case (benchmarks/foreign/cases), dresses the case's default base pattern (sized
to its body, :func:`unsew.fit.start.base_pattern_for`) from scratch with the fit's drape settings
in cotton, once per backend (cholespy, CHOLMOD with the symbolic analysis reused, optionally
scipy), the backends interleaved repeat by repeat so they see the same machine load. Prints per
case and backend: sewn vertices, the best dress time of ``--repeat`` [s], the time spent
factorizing [s] (``unsew.sim.solve._Factor``), and the Chamfer distance [mm] of the drape to the
first backend's (round-off grows through the steps: the drapes are not bit-equal) and of each
drape to the target. CHOLMOD runs on whatever BLAS scikit-sparse loads (OpenBLAS where Debian's
libopenblas0 is installed); ``OPENBLAS_NUM_THREADS`` sets its threads (1 by default, as the fit).

    OMP_WAIT_POLICY=PASSIVE python -m benchmarks backend_dress [--cases a,b] [--backends cholespy,cholmod]
        [--repeat 2] [--threads 1]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

CASES = Path(__file__).resolve().parent / "foreign" / "cases"
DEFAULT_CASES = "trousers_wide__tall_thin,tee_loose_long__default,skirt_aline_midi__tall_thin,dress_sheath_sleeveless__default"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=DEFAULT_CASES, help="comma-separated case names")
    ap.add_argument("--backends", default="cholespy,cholmod")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--threads", type=int, default=1, help="torch threads (the CLI's fit uses torch's default)")
    args = ap.parse_args()

    import numpy as np
    import torch

    torch.set_num_threads(args.threads)
    from tables import print_table

    import unsew.sim.solve as solve
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.fit.config import FitConfig
    from unsew.fit.start import base_pattern_for
    from unsew.fit.target import Target
    from unsew.metrics.surface import chamfer_mm

    from unsew.errors import InputError

    backends = args.backends.split(",")
    for b in backends:
        try:  # one line for an unknown name, or CHOLMOD missing (the install line)
            solve.resolve_backend(b)
        except (ValueError, ImportError) as exc:
            raise InputError(f"--backends: {exc}") from None

    factor_s = [0.0]
    init = solve._Factor.__init__

    def timed_init(self, *a, **k):  # the time spent factorizing, whatever the caller
        t = time.perf_counter()
        init(self, *a, **k)
        factor_s[0] += time.perf_counter() - t

    solve._Factor.__init__ = timed_init
    cfg = FitConfig()
    rows = []
    for name in args.cases.split(","):
        case = load_case(CASES / name)
        base = base_pattern_for(case, cfg)
        sdf = BodySDF.build(case.body)
        target = Target.of_case(case)
        best = {b: (np.inf, 0.0, None, 0) for b in backends}
        for _ in range(args.repeat):
            for b in backends:
                factor_s[0] = 0.0
                t = time.perf_counter()
                d = dress(base, case.body, sdf=sdf, material="cotton", settings=cfg.drape.replace(backend=b))
                s = time.perf_counter() - t
                if s < best[b][0]:
                    best[b] = (s, factor_s[0], d.x.numpy().copy(), d.mesh)
        ref = best[backends[0]]
        for b in backends:
            s, f, x, mesh = best[b]
            rows.append({"case": name, "backend": b, "verts": mesh.n_x, "dress s": s, "factor s": f,
                         f"vs {backends[0]} mm": chamfer_mm(x, mesh.faces, ref[2], ref[3].faces).mean_mm,
                         "to target mm": target.distance_mm(x, mesh.faces)})
    print_table(rows, title=f"dress from scratch per solver backend (OPENBLAS_NUM_THREADS="
                f"{os.environ.get('OPENBLAS_NUM_THREADS')}, torch threads {args.threads}, best of {args.repeat})")


if __name__ == "__main__":
    main()
