"""The ``unsew`` command line: one subcommand per job.

Each subcommand lives in ``unsew.commands.<name>`` and provides ``register(subparsers)``
(cheap: no heavy imports at module level) and a ``run(args) -> int`` set as the parser's
default ``func``. Errors the user can act on (:class:`unsew.errors.UnsewError`) print one
line and exit with status 2; ``unsew`` alone prints the help and exits with 2; an interrupt
exits with 130; a file system refusal (``OSError``) or running out of memory prints one line
and exits with 1; anything else prints one line naming the exception (``--debug`` shows the
traceback) and exits with 1.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings

from unsew import __version__
from unsew._memory import bound_heap
from unsew._threads import configure_threads

__all__ = ["main", "build_parser"]

#: Subcommand modules under unsew.commands, in the order --help lists them.
COMMANDS = ["demo", "fit", "pattern", "body", "drape", "grade", "eval", "batch"]


def build_parser() -> argparse.ArgumentParser:
    from unsew.commands._help import HelpFormatter, examples

    parser = argparse.ArgumentParser(
        prog="unsew",
        description="Turn a 3D garment mesh into the 2D sewing pattern that makes it.",
        formatter_class=HelpFormatter,
        epilog=examples(
            "unsew demo",
            "unsew fit case/ --out result/",
            "unsew pattern export result/pattern.json --pdf pattern.pdf",
        )
        + "\n\n'unsew COMMAND --help' gives each command's options, defaults and examples.",
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
    bound_heap()  # before any thread starts: glibc gives a thread an arena of its own only then
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help(sys.stderr)  # no command is a usage error: help, and status 2
        return 2
    from unsew.errors import UnsewError

    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning  # one line each, no source line
            return int(args.func(args) or 0)
    except UnsewError as exc:
        if args.debug:
            raise
        print(f"unsew: error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("unsew: interrupted", file=sys.stderr)
        return 130
    except OSError as exc:  # a file system refusal the commands did not foresee: say which file
        if args.debug:
            raise
        what = exc.strerror or type(exc).__name__
        if exc.filename is not None:
            print(f"unsew: error: {what}: {exc.filename}", file=sys.stderr)
        else:  # a write() on a full disk names no file
            print(f"unsew: error: cannot write the output: {what}", file=sys.stderr)
        return 1
    except MemoryError:
        if args.debug:
            raise
        print("unsew: error: out of memory; use a coarser --edge-length or a smaller target", file=sys.stderr)
        return 1
    except Exception as exc:  # one line, never a deep traceback, unless --debug
        if args.debug:
            raise
        print(
            f"unsew: internal error: {type(exc).__name__}: {_one_line(exc)} (rerun with --debug for the "
            "traceback)",
            file=sys.stderr,
        )
        return 1


def _one_line(exc: BaseException) -> str:
    """An exception's message on one line (a multi-line message is joined with '; ')."""
    return "; ".join(part.strip() for part in str(exc).splitlines() if part.strip())


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Print a warning as one ``unsew: warning: ...`` line on stderr."""
    print(f"unsew: warning: {_one_line(message)}", file=file or sys.stderr)
