"""Output files and provenance for the exporters.

Every exporter checks its targets before it computes anything and writes through
:func:`fastrest.tables.file.replace_files` (the one atomic writer of fastrest): temporary files in
the targets' directory, renamed over them (:func:`os.replace`), so a failure leaves no partial file
behind, a reader never sees one, and only a regular file or a new path is ever replaced.
"""
from .._provenance import REFERENCE, provenance  # noqa: F401 (the exporters import them from here)
from ..tables.file import check_target, replace_files

__all__ = ["check_target", "provenance", "write_files"]


def write_files(contents, name="path", what="the output file"):
    """Write ``contents`` (path -> str (UTF-8) or bytes) atomically; return the paths.

    OSError naming the file on any failure (disk full, a special file at a target); then no
    target has changed and no temporary file remains.
    """
    data = {p: (v.encode("utf-8") if isinstance(v, str) else v) for p, v in contents.items()}
    return replace_files(data, name, what)
