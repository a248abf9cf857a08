"""One entry for every benchmark: ``python -m benchmarks NAME [options]``.

NAME is a script in this folder without its ``bench_`` prefix and ``.py`` suffix (``fit`` runs
bench_fit.py, ``run`` runs run.py, ``make_cases`` runs make_cases.py); ``python -m benchmarks``
alone lists them with the question each answers (the first line of its docstring), the benchmarks
first, then the tools that make their inputs and figures (:data:`TOOLS`). The script runs
as if it were started directly, with this folder on ``sys.path`` so scripts can share helpers.
"""

from __future__ import annotations

import ast
import runpy
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: Scripts that make a benchmark's inputs or a figure rather than measure something.
TOOLS = ("make_cases", "make_bodies", "demo_figure", "design_figure")


def _scripts() -> dict[str, Path]:
    """Benchmark name -> script path, for every runnable script in this folder (and subfolders
    that hold a ``__main__``-style ``run.py``)."""
    out = {}
    for p in sorted(HERE.glob("*.py")):
        if p.name.startswith("_") or "__main__" not in p.read_text():
            continue  # shared helpers, not benchmarks
        out[p.stem.removeprefix("bench_")] = p
    for p in sorted(HERE.glob("*/run.py")):
        out[p.parent.name] = p
    return out


def _question(path: Path) -> str:
    """The first line of a script's docstring: the question it answers."""
    try:
        doc = ast.get_docstring(ast.parse(path.read_text()))
    except SyntaxError:
        doc = None
    return (doc or "").strip().splitlines()[0] if doc else ""


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    scripts = _scripts()
    if not argv or argv[0] in ("-h", "--help", "list"):
        print("usage: python -m benchmarks NAME [options]   (NAME --help for a benchmark's options)\n")
        width = max(len(n) for n in scripts)
        for name, path in scripts.items():
            if name not in TOOLS:
                print(f"  {name:<{width}}  {_question(path)}")
        print("\ntools:")
        for name in TOOLS:
            if name in scripts:
                print(f"  {name:<{width}}  {_question(scripts[name])}")
        return 0 if argv else 2
    name, rest = argv[0], argv[1:]
    if name not in scripts:
        print(f"benchmarks: no benchmark named {name!r}; `python -m benchmarks` lists them", file=sys.stderr)
        return 2
    path = scripts[name]
    sys.path.insert(0, str(path.parent))
    sys.argv = [str(path), *rest]
    from unsew.errors import InputError, OutputError

    try:
        runpy.run_path(str(path), run_name="__main__")
    except (InputError, OutputError) as exc:  # bad input (a missing case folder, a bad pattern) or an
        # output that cannot be written: one line, exit 2
        print(f"benchmarks {name}: {str(exc).splitlines()[0]}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
