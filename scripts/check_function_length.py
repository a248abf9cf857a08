"""List every function longer than a limit in src/ and benchmarks/; exit 1 if there is one.

A function's length is counted from its ``def`` line to the last line of its body (decorators
not included, a docstring included). Usage: ``python scripts/check_function_length.py [--max N]
[paths...]``; paths default to ``src`` and ``benchmarks`` below the repository root.
"""

from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MAX_LINES = 60


def long_functions(path: Path, max_lines: int) -> list[tuple[int, str, int]]:
    """(line, qualified name, length in lines) of each function in ``path`` over ``max_lines``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[tuple[int, str, int]] = []

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                name = f"{prefix}{child.name}"
                length = child.end_lineno - child.lineno + 1
                if length > max_lines:
                    found.append((child.lineno, name, length))
                visit(child, f"{name}.")
            elif isinstance(child, ast.ClassDef):
                visit(child, f"{prefix}{child.name}.")
            else:
                visit(child, prefix)

    visit(tree, "")
    return sorted(found)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="*", type=Path, help="files or folders (default: src benchmarks)")
    parser.add_argument("--max", type=int, default=MAX_LINES, help=f"longest allowed (default {MAX_LINES})")
    args = parser.parse_args(argv)
    roots = args.paths or [ROOT / "src", ROOT / "benchmarks"]
    files = sorted({f for r in roots for f in ([r] if r.is_file() else r.rglob("*.py"))})
    count = 0
    for f in files:
        shown = f.resolve().relative_to(ROOT) if f.resolve().is_relative_to(ROOT) else f
        for line, name, length in long_functions(f, args.max):
            print(f"{shown}:{line} {name} {length}")
            count += 1
    if count:
        print(f"{count} function(s) longer than {args.max} lines", file=sys.stderr)
    return 1 if count else 0


if __name__ == "__main__":
    sys.exit(main())
