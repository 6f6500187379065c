"""Temporary files that a killed writer left beside its target, and their removal.

:func:`fastrest.tables.file.replace_files` (the one atomic writer of fastrest: tables, the cache,
exports, figures) writes each file to ``.<name>.XXXXXXXX.tmp`` beside its target and renames it
over the target. A process killed between the two leaves the temporary file; the next write to
the same target removes it (:func:`remove_stale_temps`).
"""
from __future__ import annotations

import os
import re
import stat
import time

__all__ = ["STALE_TEMP_SECONDS", "remove_stale_temps"]

#: A temporary file untouched for this long (s) is left over from a killed writer (writing one
#: takes well under a second): the next write to its target removes it.
STALE_TEMP_SECONDS = 600


def _temp_pattern(path):
    """Names :func:`tempfile.mkstemp` gives the temporary files of ``path`` in ``replace_files``:
    ``.<name>.<8 characters>.tmp``."""
    return re.compile(re.escape("." + os.path.basename(path) + ".") + r"[a-z0-9_]{8}\.tmp")


def remove_stale_temps(path: str | os.PathLike[str], older_than: float = STALE_TEMP_SECONDS) -> list[str]:
    """Remove the temporary files that a killed writer left beside ``path``.

    Parameters
    ----------
    path : str or path-like
        A target of :func:`fastrest.tables.file.replace_files`.
    older_than : float
        Only files not modified for this long (s) are removed (a concurrent writer's file is
        younger); default :data:`STALE_TEMP_SECONDS`.

    Returns
    -------
    list of str
        The files removed.

    Notes
    -----
    Only regular files (never a symbolic link, which is not followed, a directory or a special
    file) named exactly as ``replace_files`` names its temporary files for this target,
    ``.<name>.XXXXXXXX.tmp``, and owned by the current user. Best effort: a file that cannot be
    examined or removed is left as it is. :func:`fastrest.tables.file.replace_files` calls it
    before writing.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     stale = os.path.join(d, ".t.h5.abcd1234.tmp")
    ...     open(stale, "wb").close()
    ...     os.utime(stale, (0, 0))   # last modified in 1970
    ...     [os.path.basename(p) for p in remove_stale_temps(os.path.join(d, "t.h5"))], os.listdir(d)
    (['.t.h5.abcd1234.tmp'], [])
    """
    target = os.path.abspath(os.fspath(path))
    directory, pattern = os.path.dirname(target), _temp_pattern(target)
    removed: list[str] = []
    now = time.time()
    try:
        entries = list(os.scandir(directory))
    except OSError:
        return removed
    for entry in entries:
        if not pattern.fullmatch(entry.name):
            continue
        try:
            st = entry.stat(follow_symlinks=False)
            if (stat.S_ISREG(st.st_mode) and now - st.st_mtime > older_than
                    and st.st_uid == getattr(os, "getuid", lambda: st.st_uid)()):
                os.remove(entry.path)  # a link swapped in meanwhile: the link goes, not its target
                removed.append(entry.path)
        except OSError:
            pass
    return removed
