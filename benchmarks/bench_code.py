"""How the code reads, measured: the largest functions, import cycles between packages, and
imports of unsew's own modules inside functions (issue 24's must-show figures).

    python -m benchmarks code [--top 12] [--limit 80] [--src DIR]

``--src`` measures another tree's package folder (e.g. an older commit's ``src/unsew`` from
``git archive``), so before/after figures come from the same command.
"""

from __future__ import annotations

import argparse
import ast
import collections
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "unsew"


def _package(path: Path, src: Path = SRC) -> str:
    rel = path.relative_to(src).parts
    return rel[0].removesuffix(".py") if len(rel) > 1 else "(top)"


def measure(src: Path = SRC):
    """Function sizes (lines, path, name), package import edges and the count of unsew imports made
    inside functions, over every module under ``src``."""
    sizes, edges, inner = [], collections.defaultdict(set), 0
    for p in sorted(src.rglob("*.py")):
        tree = ast.parse(p.read_text())
        pkg = _package(p, src)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("unsew."):
                edges[pkg].add(node.module.split(".")[1])
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                sizes.append((node.end_lineno - node.lineno + 1, str(p.relative_to(src.parent.parent)), node.name))
                for n in ast.walk(node):
                    mod = n.module if isinstance(n, ast.ImportFrom) else (
                        n.names[0].name if isinstance(n, ast.Import) else None)
                    if mod and mod.startswith("unsew"):
                        inner += 1
    sizes.sort(reverse=True)
    return sizes, _cycles(edges), inner


def _cycles(edges) -> list[tuple[str, ...]]:
    """The package import cycles: each strongly connected group of two or more packages of the
    import graph ``edges`` (package -> packages it imports), sorted."""
    def reach(a):
        seen, todo = set(), [a]
        while todo:
            for b in edges.get(todo.pop(), ()):
                if b not in seen:
                    seen.add(b)
                    todo.append(b)
        return seen

    r = {a: reach(a) for a in set(edges) | {b for bs in edges.values() for b in bs}}
    groups = {tuple(sorted({a} | {b for b in r[a] if a in r[b]})) for a in r}
    return sorted(g for g in groups if len(g) > 1)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--top", type=int, default=12, help="how many of the largest functions to list")
    ap.add_argument("--limit", type=int, default=80, help="count the functions longer than this many lines")
    ap.add_argument("--src", type=Path, default=SRC, help="the unsew package folder to measure")
    args = ap.parse_args()
    sizes, cycles, inner = measure(args.src.resolve())
    print("| lines | file | function |\n|---|---|---|")
    for n, path, name in sizes[: args.top]:
        print(f"| {n} | {path} | {name} |")
    print(f"\nfunctions over {args.limit} lines: {sum(1 for s in sizes if s[0] > args.limit)} of {len(sizes)}")
    print("import cycles between packages:", ", ".join(" <-> ".join(g) for g in cycles) or "none")
    print("imports of unsew modules inside functions:", inner)


if __name__ == "__main__":
    main()
