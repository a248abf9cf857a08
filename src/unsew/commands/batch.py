"""``unsew batch CASES_DIR --out RESULTS_DIR``: one fit per case folder, on a local process pool
(default) or on a Ray cluster (``--ray``), resumable; writes RESULTS_DIR/<case>/ for each case,
RESULTS_DIR/summary.csv and RESULTS_DIR/index.html, and prints the summary table.

With ``--ray`` on a cluster of several machines, CASES_DIR and RESULTS_DIR must be on a
filesystem every node sees at the same path: each task writes its own result folder.
"""

from __future__ import annotations

import argparse

from unsew.commands._output import check_out
from unsew.commands._help import HelpFormatter, examples
from unsew.commands.fit import add_fit_options, config_from_args

__all__ = ["register", "run"]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "batch",
        help="fit every case folder of a folder (local processes, or a Ray cluster); resumable",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew batch cases/ --out results/",
            "unsew batch cases/ --out results/ --workers 2 --iterations 40",
            "unsew batch cases/ --out results/ --ray auto",
        ),
        description="Fit every case folder (a subfolder holding meta.json) of CASES_DIR into "
        "RESULTS_DIR/<case>/. Rerun the same command to continue an interrupted batch: complete results are "
        "skipped, interrupted fits resume from their checkpoints, failed cases are tried again.",
    )
    p.add_argument("cases", metavar="CASES_DIR", help="folder of case folders (FORMATS.md)")
    p.add_argument(
        "--out", required=True, metavar="RESULTS_DIR", help="results folder (created; reused on a rerun)"
    )
    p.add_argument(
        "--workers", type=int, metavar="N", help="local worker processes (default: min(CPU count, cases))"
    )
    p.add_argument(
        "--ray",
        metavar="ADDRESS",
        help="run the fits as Ray tasks: 'auto' (running cluster), 'local' (start one here) or an address; "
        "RESULTS_DIR must be on a shared filesystem for a multi-machine cluster (needs unsew[ray]) "
        "(default: local processes)",
    )
    p.add_argument(
        "--overwrite", action="store_true", help="refit cases whose result folder is already complete"
    )
    add_fit_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import sys

    from unsew.batch.runner import run_batch
    from unsew.batch.summary import format_table

    cfg = _config(args)
    # a bad --out fails before any fit; a rerun resumes in it
    check_out(args.out, overwrite=None, folder=True)
    res = run_batch(
        args.cases,
        args.out,
        cfg=cfg,
        workers=args.workers,
        ray=args.ray,
        overwrite=args.overwrite,
        progress=not args.quiet,
    )
    print(format_table(res.records))
    print(f"summary: {res.summary_csv}  index: {res.index_html}", file=sys.stderr)
    if res.interrupted:
        print("unsew: interrupted; rerun the same command to continue", file=sys.stderr)
        return 130
    return 1 if res.counts.get("failed") else 0


def _config(args: argparse.Namespace):
    if not hasattr(args, "base"):
        args.base = None
    return config_from_args(args)
