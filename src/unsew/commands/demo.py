"""``unsew demo``: the embedded default job (known-truth t-shirt: make, fit, evaluate, retarget)."""

from __future__ import annotations

import argparse

from unsew.commands._output import check_out
from unsew.commands._help import HelpFormatter, examples
from unsew.commands.fit import add_fit_options, config_from_args

__all__ = ["register", "run"]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "demo",
        help="fit a known t-shirt on the embedded default body (a few minutes)",
        formatter_class=HelpFormatter,
        description="Make a t-shirt case whose true pattern and fabric are known, fit it, compare "
        "with the truth and retarget the result to a second body.",
        epilog=examples("unsew demo", "unsew demo --out demo-out --iterations 20 --no-progress"),
    )
    p.add_argument(
        "--out", default="demo-out", metavar="DIR", help="folder for the case, the fit and the retarget"
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --out (make demo passes it)")
    add_fit_options(p, demo=True)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from unsew.fit.demo import DEMO_CONFIG, run_demo

    cfg = config_from_args(args, defaults=DEMO_CONFIG)
    # a bad --out fails now, not after the fit
    check_out(Path(args.out), overwrite=args.overwrite, folder=True)
    run_demo(Path(args.out), cfg=cfg, progress=not args.quiet)
    return 0
