"""Shared table printing for the benchmarks: a list of row dicts as a Markdown table.

Every benchmark prints its results with :func:`print_table`, so tables read alike; benchmarks/report.py
writes docs/benchmarks.md with the same tables from the recorded results.
"""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Iterable, Sequence


def fmt(value, digits: int = 2) -> str:
    """One cell: floats with ``digits`` decimals, None as an empty cell, anything else as str."""
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.{digits}f}"
    return str(value)


def markdown_table(rows: Iterable[dict], columns: Sequence[str] | None = None, *, digits: int = 2) -> str:
    """Rows (dicts) as a Markdown table; columns default to the first row's keys, in order."""
    rows = list(rows)
    if not rows:
        return "(no rows)"
    cols = list(columns or rows[0].keys())
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        lines.append("| " + " | ".join(fmt(r.get(c), digits) for c in cols) + " |")
    return "\n".join(lines)


def print_table(
    rows: Iterable[dict], columns: Sequence[str] | None = None, *, title: str | None = None, digits: int = 2
) -> None:
    """Print a title line (if given) and the Markdown table of ``rows``."""
    if title:
        print(f"\n{title}\n")
    print(markdown_table(rows, columns, digits=digits), flush=True)


def git_commit() -> str:
    """The checkout's short commit id, for a record's ``commit`` field ("unknown" outside git)."""
    try:
        return subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
