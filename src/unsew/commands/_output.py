"""The one rule every command applies to the files and folders it is told to write (``--out``,
``--svg``, ...), checked before any work starts:

- the parent folder must exist (a missing one is an error, never created: a typo in a path
  should not grow a tree of folders);
- an existing result is replaced only with ``--overwrite``;
- the place must be writable (:func:`unsew.io.atomic.check_output`: a file in the way, no
  permission, a full or read-only file system, a device).

Each refusal is one line (:class:`~unsew.errors.InputError` or :class:`~unsew.errors.OutputError`).
"""

from __future__ import annotations

import os
from pathlib import Path

from unsew.errors import InputError
from unsew.io.atomic import check_output

__all__ = ["check_out"]


def check_out(
    path: str | os.PathLike, *, overwrite: bool | None, folder: bool = False, flag: str = "--out"
) -> Path:
    """Check that ``path`` may be written by a command; returns it as a Path.

    Args:
        path: the output file (or result folder with ``folder=True``) the user named.
        overwrite: whether an existing ``path`` may be replaced (the command's ``--overwrite``);
            None: the command reuses an existing result folder itself (``unsew batch`` resumes in it).
        folder: whether ``path`` is a result folder rather than a file.
        flag: the option that named it, for the messages.

    Raises:
        InputError: the parent folder does not exist, or ``path`` exists without ``overwrite``
            (or is of the wrong kind).
        OutputError: the place cannot be written.
    """
    path = Path(path)
    parent = path.parent
    first = next((up for up in (parent, *parent.parents) if up.exists()), None)
    if first is not None and first.is_dir() and first != parent:
        raise InputError(f"{flag} {path}: folder {parent} does not exist; create it first")
    check_output(path, folder=folder, flag=flag)  # a file in the way, the wrong kind, unwritable
    if overwrite is False and path.exists():
        what = "folder" if folder else "file"
        raise InputError(f"{flag} {path}: the {what} exists; pass --overwrite to replace it")
    return path
