"""Finding the case folders of a batch and the state of their result folders.

A case folder (FORMATS.md) is any direct subfolder of CASES_DIR holding ``meta.json``; its
result folder is ``RESULTS_DIR/<case name>/``, written by :func:`unsew.fit.run.run_fit`, which
works in ``<case name>.partial/`` and renames it only when every file is written. So a result
folder that exists and holds ``metrics.json`` is complete.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from unsew.errors import InputError

__all__ = ["find_cases", "result_state", "read_garment", "COMPLETE_MARKER"]

#: the file whose presence marks a result folder complete (run_fit writes it before the rename)
COMPLETE_MARKER = "metrics.json"


def find_cases(cases_dir: str | os.PathLike) -> list[Path]:
    """Case folders of ``cases_dir``: its direct, non-hidden subfolders holding meta.json,
    sorted by name. Raises InputError if the folder is missing or holds no case."""
    d = Path(cases_dir)
    if not d.is_dir():
        raise InputError(f"cases folder {d} does not exist")
    cases = sorted(
        p for p in d.iterdir() if p.is_dir() and not p.name.startswith(".") and (p / "meta.json").is_file()
    )
    if not cases:
        raise InputError(
            f"no case folder in {d} (a case folder is a subfolder holding meta.json; see FORMATS.md)"
        )
    return cases


def result_state(out: str | os.PathLike) -> str:
    """State of a case's result folder ``out``: "complete" (exists with metrics.json),
    "partial" (``out.partial/checkpoint.pt`` exists: an interrupted fit to resume),
    "blocked" (``out`` exists but is not a complete result), or "new"."""
    out = Path(out)
    if out.is_dir() and (out / COMPLETE_MARKER).is_file():
        return "complete"
    if out.exists():
        return "blocked"
    if (out.with_name(out.name + ".partial") / "checkpoint.pt").is_file():
        return "partial"
    return "new"


def read_garment(case_dir: str | os.PathLike) -> str:
    """The garment named in a case's meta.json, or "?" if it cannot be read (the fit will
    report why)."""
    try:
        meta = json.loads((Path(case_dir) / "meta.json").read_text())
        g = meta.get("garment") if isinstance(meta, dict) else None
        return str(g) if g else "?"
    except (OSError, ValueError):
        return "?"
