"""Batch throughput benchmark: fits per hour of ``unsew batch`` on the local process pool
with 1 and 2 workers (and, with ``--ray``, on a local Ray instance with 2 CPUs).

Cases: small known-truth t-shirts (``unsew.fit.demo.make_truth_case`` with different hem/sleeve
changes), made once into a cache folder. Fit: a small configuration (coarse panels, few steps and
iterations, no report) so a run takes minutes; pass ``--iterations``/``--edge-length`` to change it.
Each worker count fits every case into a fresh results folder; the wall time includes the
workers' start-up (spawn + torch import), as a user would see it.

These machines have 2 cores shared with other work: 2 workers can at best double throughput, and
any other load shows up in the numbers. Prints a table; asserts nothing.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_batch.py [--cases 4] [--workers 1 2]
     [--iterations 3] [--edge-length 0.05] [--ray] [--keep DIR]
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _truths(n: int):
    from unsew.fit.demo import DemoTruth

    return [
        DemoTruth(
            hem_length=0.02 + 0.02 * (i % 4),
            hem_girth=0.02 + 0.02 * (i % 3),
            sleeve_length=0.01 + 0.01 * (i % 3),
            material=("jersey", "cotton")[i % 2],
        )
        for i in range(n)
    ]


def make_cases(root: Path, n: int, *, edge_length: float) -> Path:
    """n small truth cases under root/cases (kept between runs when root is kept)."""
    from unsew.fit.demo import make_truth_case
    from unsew.sim.drape import DrapeSettings

    cases = root / f"cases_e{edge_length:g}"
    for i, truth in enumerate(_truths(n)):
        d = cases / f"tshirt{i:02d}"
        if not (d / "meta.json").is_file():
            make_truth_case(d, truth=truth, settings=DrapeSettings(edge_length=edge_length))
    return cases


def _print_rows(rows) -> None:
    """The table of (backend, done fits, cases, wall s, s per fit, fits per hour) rows."""
    print()
    print(f"{'backend':<22}{'fits':>8}{'wall [s]':>10}{'s per fit':>11}{'fits/hour':>11}{'speed-up':>10}")
    print("-" * 72)
    for label, ok, n, wall, per, fph in rows:
        print(f"{label:<22}{f'{ok}/{n}':>8}{wall:>10.1f}{per:>11.1f}{fph:>11.0f}{fph / rows[0][5]:>10.2f}")
    print("s per fit: mean wall time of one fit inside its worker; fits/hour: done fits / batch wall time")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=4, help="number of cases")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="worker counts to time")
    ap.add_argument("--iterations", type=int, default=3)
    ap.add_argument("--edge-length", type=float, default=0.05, help="panel mesh edge length [m]")
    ap.add_argument("--ray", action="store_true", help="also time a local Ray instance with 2 CPUs")
    ap.add_argument("--keep", metavar="DIR", help="keep cases and results in DIR (cases are reused)")
    args = ap.parse_args(argv)

    import torch

    torch.set_num_threads(1)
    from unsew.batch import run_batch
    from unsew.batch.ray_backend import RayCluster
    from unsew.fit.config import load_config

    root = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="bench_batch_"))
    root.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    cases = make_cases(root, args.cases, edge_length=args.edge_length)
    print(f"{args.cases} cases in {cases} ({time.perf_counter() - t0:.0f} s to make)")
    cfg = load_config(
        drape={"edge_length": args.edge_length, "sew_steps": 20, "settle_steps": 10, "steps": 5},
        optimizer={"iterations": args.iterations},
        loss={"target_points": 2000},
        output={"report": False},
    )
    d = cfg.drape
    print(
        f"fit: edge_length {d.edge_length} m, {cfg.optimizer.iterations} iterations, {d.steps} drape steps, "
        f"sew/settle {d.sew_steps}/{d.settle_steps} steps, no report; cpu count {os.cpu_count()}"
    )
    runs = [(f"local, {w} worker{'s' if w > 1 else ''}", {"workers": w}) for w in args.workers]
    if args.ray:
        runs.append(("Ray local, 2 CPUs", {"ray": RayCluster("local", {"num_cpus": 2})}))
    rows = []
    for label, kw in runs:
        out = root / ("results_" + label.replace(" ", "_").replace(",", ""))
        shutil.rmtree(out, ignore_errors=True)
        load = os.getloadavg()[0]  # other work on the machine skews the figures
        t = time.perf_counter()
        res = run_batch(cases, out, cfg=cfg, progress=False, **kw)
        wall = time.perf_counter() - t
        ok = sum(r.status == "done" for r in res.records)
        fit_s = [r.time_s for r in res.records if r.status == "done"]
        rows.append((label, ok, len(res.records), wall, sum(fit_s) / max(len(fit_s), 1), 3600 * ok / wall))
        print(
            f"  {label}: {ok}/{len(res.records)} done in {wall:.1f} s (load average before: {load:.1f})",
            flush=True,
        )
    _print_rows(rows)
    if not args.keep:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
