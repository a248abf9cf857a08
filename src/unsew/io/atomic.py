"""Write files and folders so that a failed run never leaves one looking complete.

``with atomic_write(path) as tmp:`` yields a temporary path in the same folder; the file is
moved onto ``path`` (``os.replace``, atomic on POSIX) only if the block finishes without an
exception, and the temporary file is removed otherwise. ``atomic_dir`` does the same for a
result folder. :func:`check_output` tells before any work starts whether an output can be
written there.

A place that cannot be written (no permission, a read-only or full file system, a parent that
is a file, a target that is a device such as ``/dev/full``) raises
:class:`unsew.errors.OutputError` with one line naming the path, never a bare ``OSError`` about
a temporary name.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import stat
import tempfile
from pathlib import Path
from typing import Iterator

from unsew.errors import InputError, OutputError

__all__ = ["atomic_write", "atomic_dir", "check_output"]


def _reason(exc: OSError) -> str:
    return exc.strerror or type(exc).__name__


def check_output(path: str | os.PathLike, *, folder: bool = False, flag: str = "--out") -> Path:
    """Check, before any work, that ``path`` can be written: create its parent folder and a
    probe file in it (removed again). Returns ``path`` as a Path.

    Args:
        path: the output file (or folder with ``folder=True``) the user named.
        folder: whether ``path`` is a result folder rather than a file.
        flag: the option that named it, for the message.

    Raises:
        OutputError: the place cannot be written (with the reason the system gave).
        InputError: ``path`` exists and is of the wrong kind (a folder for a file, a device).
    """
    path = Path(path)
    if path.exists() or path.is_symlink():
        mode = os.stat(path).st_mode if path.exists() else 0
        if folder and not stat.S_ISDIR(mode):
            raise InputError(f"{flag} {path} exists and is not a folder")
        if not folder and not stat.S_ISREG(mode):
            kind = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
            raise InputError(f"{flag} {path} is {kind}; name a file to write")
    parent = path.parent
    for up in (parent, *parent.parents):
        if up.exists():
            if not up.is_dir():
                raise OutputError(f"cannot write {flag} {path}: {up} is a file, not a folder")
            break
    try:
        parent.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".probe", dir=parent)
    except OSError as exc:
        raise OutputError(f"cannot write {flag} {path}: {_reason(exc)}") from None
    os.close(fd)
    os.unlink(probe)
    return path


#: Errors of a write that carry no file name (``write()`` on a full disk): they are the output's.
_WRITE_ERRNOS = {errno.ENOSPC, errno.EFBIG, errno.EDQUOT, errno.EROFS, errno.EIO}


def _failed_write(exc: BaseException) -> bool:
    """Whether a non-OSError is a writer's report of a failed write: ``torch.save`` raises
    RuntimeError ("PytorchStreamWriter failed writing file", "unexpected pos") on a full disk."""
    text = str(exc)
    return isinstance(exc, RuntimeError) and ("PytorchStreamWriter" in text or "inline_container" in text)


def _mine(exc: OSError, tmp: Path) -> bool:
    """Whether an OSError is about the temporary file or folder (not about some input)."""
    names = [exc.filename, exc.filename2]
    if all(n is None for n in names):
        return exc.errno in _WRITE_ERRNOS
    return any(n is not None and str(n).startswith(str(tmp)) for n in names)


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    Raises :class:`OutputError` when the place cannot be written or the write fails (disk full);
    nothing is left at ``path`` then, and the temporary file is removed.
    """
    path = Path(path)
    check_output(path, flag="output")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {_reason(exc)}") from None
    os.close(fd)
    tmp = Path(tmp)
    try:
        try:
            yield tmp
            if tmp.exists():  # mkstemp makes files private (0600); give them the usual mode
                umask = os.umask(0)
                os.umask(umask)
                os.chmod(tmp, 0o666 & ~umask)
            os.replace(tmp, path)
        except OutputError:
            raise
        except OSError as exc:
            if not _mine(exc, tmp):
                raise
            raise OutputError(f"cannot write {path}: {_reason(exc)}") from None
        except RuntimeError as exc:
            if not _failed_write(exc):
                raise
            raise OutputError(f"cannot write {path}: the write failed (disk full?)") from None
    finally:
        if tmp.exists():
            tmp.unlink()


@contextlib.contextmanager
def atomic_dir(path: str | os.PathLike, *, overwrite: bool = False) -> Iterator[Path]:
    """Yield a temporary folder beside ``path``; rename it onto ``path`` when the block succeeds.

    An existing ``path`` is replaced only with ``overwrite=True``; otherwise its presence is an
    error raised before any work starts. A place that cannot be written, or a write into the
    folder that fails (disk full), raises :class:`OutputError` and leaves nothing at ``path``.
    """
    path = Path(path)
    if path.exists() and not overwrite:
        raise InputError(f"output folder {path} exists; remove it or choose another --out")
    check_output(path, folder=True, flag="output folder")
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent))
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {_reason(exc)}") from None
    try:
        try:
            yield tmp
            if path.exists():
                shutil.rmtree(path)
            os.replace(tmp, path)
        except OutputError as exc:  # a file inside: name it by where it was going
            raise OutputError(str(exc).replace(str(tmp), str(path))) from None
        except OSError as exc:
            if not _mine(exc, tmp):
                raise
            raise OutputError(f"cannot write {path}: {_reason(exc)}") from None
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
