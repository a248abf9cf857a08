"""``unsew eval RESULT_DIR CASE_DIR [--json]``: score a fit against its case.

Prints a table (or JSON with ``--json``: stdout holds the JSON alone) and writes
``RESULT_DIR/eval.json`` atomically (an existing one is replaced only with ``--overwrite``). The
case is loaded and refused as ``unsew fit`` refuses it. The work is in
:mod:`unsew.metrics.evaluate`, imported only when the command runs.
"""

from __future__ import annotations

import argparse

from unsew.commands._output import check_out
from unsew.commands._help import HelpFormatter, examples

__all__ = ["register", "run"]


def run(args: argparse.Namespace) -> int:
    import json
    from pathlib import Path

    from unsew.metrics.evaluate import evaluate_result, format_table, write_eval_json

    if Path(args.result_dir).is_dir():
        # before the work
        check_out(Path(args.result_dir) / "eval.json", overwrite=args.overwrite, flag="output")
    ev = evaluate_result(
        args.result_dir,
        args.case_dir,
        n_samples=args.samples,
        seed=args.seed,
        units=args.units,
        up=args.up,
        front=args.front,
    )
    write_eval_json(ev, Path(args.result_dir) / "eval.json")
    print(json.dumps(ev, indent=2) if args.json else format_table(ev))
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "eval",
        help="score a fit result against a case: Chamfer [mm], normal error, and 2D pattern metrics",
        description="Compare RESULT_DIR/garment.obj with CASE_DIR/target.obj (3D) and, when both exist, "
        "RESULT_DIR/pattern.json with CASE_DIR/pattern_gt.json (2D). Writes RESULT_DIR/eval.json.",
        formatter_class=HelpFormatter,
        epilog=examples("unsew eval result/ case/", "unsew eval result/ case/ --json --samples 20000"),
    )
    p.add_argument("result_dir", metavar="RESULT_DIR", help="fit result folder (garment.obj, pattern.json)")
    p.add_argument("case_dir", metavar="CASE_DIR", help="case folder (target.obj, optional pattern_gt.json)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--samples", type=int, default=100_000, help="surface samples per mesh (default: 100000)")
    p.add_argument("--seed", type=int, default=0, help="sampling seed (default: 0)")
    p.add_argument(
        "--units", choices=["m", "cm", "mm"], help="units of the case's meshes (default: meta.json's, else m)"
    )
    p.add_argument("--up", help="the case files' up axis, e.g. z (default: meta.json's, else y)")
    p.add_argument("--front", help="the case files' front axis, e.g. -y (default: meta.json's, else z)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing RESULT_DIR/eval.json")
    p.set_defaults(func=run)
