"""Atomic file writes: the one place every writer in paperlib goes through.

A private utility beneath every floor (it imports nothing from paperlib), so that
``geometry`` (SVG output) and ``repro`` (statistics and figures) share it without
breaking the rule that ``geometry`` builds on no other part of the package.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

__all__ = ["atomic_path", "fsync_directory", "fsync_tree", "publish_folder", "recover_folder"]

_FILE_MODE = 0o644  # mkstemp makes 0600 files; outputs are for everyone to read


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    A reader never sees a half-written file: on an exception the temporary file is
    removed and ``path`` is left as it was. Missing parent folders are created. The
    temporary file's data are flushed to disk (fsync) before the rename and the folder's
    entry after it, so a power cut leaves the old file or the new one, never an empty one.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.

    Yields
    ------
    pathlib.Path
        A fresh temporary file in ``path``'s folder (same suffix), to write to; it replaces
        ``path`` when the ``with`` block ends without an exception.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(handle)
    os.chmod(temporary, _FILE_MODE)
    try:
        yield Path(temporary)
        _fsync_file(temporary)
        os.replace(temporary, path)
        fsync_directory(path.parent)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise


def _fsync_file(path) -> None:
    with open(path, "rb") as handle:
        os.fsync(handle.fileno())


def fsync_directory(path) -> None:
    """Flush a folder's entries (renames, new files) to disk; a no-op where folders cannot be opened."""
    try:
        descriptor = os.open(path, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(descriptor)
    except OSError:  # some file systems refuse fsync on a folder: nothing more can be done there
        pass
    finally:
        os.close(descriptor)


def fsync_tree(root) -> None:
    """Flush every file and folder under ``root`` to disk (before it is published by a rename)."""
    for folder, _, files in os.walk(root):
        for name in files:
            _fsync_file(os.path.join(folder, name))
        fsync_directory(folder)


def _retired(target: Path) -> Path:
    return target.with_name(f".{target.name}.old")


def recover_folder(target) -> bool:
    """Finish or undo a :func:`publish_folder` that a crash interrupted; True if it restored ``target``.

    A crash between the two renames leaves ``target`` missing and the previous copy in the
    hidden ``.<name>.old`` folder beside it: that copy is moved back. If both exist, the swap
    had completed and the leftover old copy is removed.
    """
    target = Path(target)
    retired = _retired(target)
    if not retired.exists():
        return False
    if target.exists():
        shutil.rmtree(retired, ignore_errors=True)
        return False
    os.replace(retired, target)
    fsync_directory(target.parent)
    return True


def publish_folder(staging, target) -> None:
    """Replace folder ``target`` by the finished folder ``staging`` so that a crash at any point
    leaves the old or the new complete ``target`` (or the old one set aside, which
    :func:`recover_folder` restores: call it before reading ``target`` after a crash).

    Steps: recover an interrupted earlier publish; flush ``staging`` to disk; rename the old
    ``target`` aside; rename ``staging`` onto ``target``; flush the parent; remove the old copy.
    """
    staging, target = Path(staging), Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    recover_folder(target)
    fsync_tree(staging)
    retired = _retired(target)
    if target.exists():
        os.replace(target, retired)
        fsync_directory(target.parent)
    os.replace(staging, target)
    fsync_directory(target.parent)
    fsync_directory(staging.parent)
    shutil.rmtree(retired, ignore_errors=True)
