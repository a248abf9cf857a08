"""The ``unsew`` command line: one subcommand per job.

Each subcommand lives in ``unsew.commands.<name>`` and provides ``register(subparsers)``
(cheap: no heavy imports at module level) and a ``run(args) -> int`` set as the parser's
default ``func``. Errors the user can act on (:class:`unsew.errors.UnsewError`) print one
line and exit with status 2; an interrupt exits with 130; anything else prints one line
naming the exception (``--debug`` shows the traceback) and exits with 1.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from unsew import __version__
from unsew._threads import configure_threads

__all__ = ["main", "build_parser"]

#: Subcommand modules under unsew.commands, in the order --help lists them.
COMMANDS = ["demo", "fit", "pattern", "body", "drape", "grade", "eval", "batch"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="unsew",
        description="Turn a 3D garment mesh into the 2D sewing pattern that makes it.",
    )
    parser.add_argument("--version", action="version", version=f"unsew {__version__}")
    parser.add_argument("--debug", action="store_true", help="show full tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMANDS:
        try:
            mod = importlib.import_module(f"unsew.commands.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"unsew.commands.{name}":
                continue  # not built yet
            raise
        mod.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    configure_threads()
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0 if args.command is None else 2
    from unsew.errors import UnsewError

    try:
        return int(args.func(args) or 0)
    except UnsewError as exc:
        if args.debug:
            raise
        print(f"unsew: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("unsew: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # one line, never a deep traceback, unless --debug
        if args.debug:
            raise
        print(
            f"unsew: internal error: {type(exc).__name__}: {exc} (rerun with --debug for the traceback)",
            file=sys.stderr,
        )
        return 1
