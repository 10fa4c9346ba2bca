"""Atomic file writes: the one place every writer in paperlib goes through.

A private utility beneath every floor (it imports nothing from paperlib), so that
``geometry`` (SVG output) and ``repro`` (statistics and figures) share it without
breaking the rule that ``geometry`` builds on no other part of the package.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

__all__ = ["atomic_path"]

_FILE_MODE = 0o644  # mkstemp makes 0600 files; outputs are for everyone to read


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    A reader never sees a half-written file: on an exception the temporary file is
    removed and ``path`` is left as it was. Missing parent folders are created.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(handle)
    os.chmod(temporary, _FILE_MODE)
    try:
        yield Path(temporary)
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise
