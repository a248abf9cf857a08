"""Does phase two's prior in pattern space keep the pattern where grading already fits?

Runs the small t-shirt fit of tests/fit/test_fit_small.py (``small_fit``: the demo's t-shirt
truth, hem and sleeves altered, in jersey; fitted from the base in cotton, 4 cm mesh, six
iterations, cholespy) once per weight of the moves term (``LossWeights.moves``, set in the child
process; unsew.losses.prior.loss_moves), each in its own process, and prints the graded and the
returned pattern's mean panel area error [%] and rigid corner L2 [cm], the Chamfer [mm] of the
graded and the returned drape, whether the re-dress check kept phase two, and the loss per iteration
[1e-6 m^2]. The hip dress case (where grading leaves an error): ``python -m benchmarks
phase_two_paths --moves W``.

Run: python -m benchmarks phase_two_prior [--moves 0 30] [--lengths W]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from tables import print_table

_CHILD = r"""
import json, sys
from pathlib import Path
sys.path.insert(0, str(Path(sys.argv[2]) / "tests" / "fit"))
import unsew.sim.solve
unsew.sim.solve._HAS_CHOLMOD = False  # the test's solver
from test_fit_small import SMALL, PROOF_ITERATIONS
from unsew.body.case import load_case
from unsew.fit.config import LossWeights, load_config
from unsew.fit.demo import make_truth_case
from unsew.fit.run import run_fit
LossWeights.moves, LossWeights.lengths = float(sys.argv[3]), float(sys.argv[4])
tmp = Path(sys.argv[1])
case = make_truth_case(tmp / "tshirt", settings=load_config(**SMALL).drape)
cfg = load_config(**{**SMALL, "optimizer.iterations": PROOF_ITERATIONS})
result, m = run_fit(load_case(case), cfg, tmp / "fit", progress=False, log=lambda s: None)
print(json.dumps({"area_graded": m["pattern_graded"]["area_error_rel_mean"],
                  "area_final": m["pattern"]["area_error_rel_mean"],
                  "l2_graded": m["pattern_graded"]["vertex_l2_cm_mean"],
                  "l2_final": m["pattern"]["vertex_l2_cm_mean"],
                  "cf_graded": m["surface_graded"]["chamfer_mm"], "cf_final": m["surface"]["chamfer_mm"],
                  "kept": m["redress"]["phase_two_kept"], "loss": result.history["total"]}))
"""


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", nargs="+", type=float, default=[0.0, 30.0], help="weights of the moves term")
    ap.add_argument("--lengths", type=float, default=0.0, help="LossWeights.lengths in every fit")
    args = ap.parse_args(argv)
    root = Path(__file__).resolve().parent.parent
    env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE"}
    rows = []
    for w in args.moves:
        with tempfile.TemporaryDirectory(prefix="unsew-prior-") as tmp:
            out = subprocess.run(
                [sys.executable, "-c", _CHILD, tmp, str(root), str(w), str(args.lengths)],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            ).stdout
        r = json.loads(out.strip().splitlines()[-1])
        rows.append(
            {
                "moves weight": w,
                "area graded %": 100 * r["area_graded"],
                "area final %": 100 * r["area_final"],
                "corner L2 graded cm": r["l2_graded"],
                "corner L2 final cm": r["l2_final"],
                "Chamfer graded mm": r["cf_graded"],
                "Chamfer final mm": r["cf_final"],
                "phase two kept": "yes" if r["kept"] else "no",
                "loss per iteration": " ".join(f"{1e6 * v:.0f}" for v in r["loss"]),
            }
        )
    print_table(rows, title="the small t-shirt fit (tests/fit/test_fit_small.py, small_fit) per moves weight")


if __name__ == "__main__":
    main()
