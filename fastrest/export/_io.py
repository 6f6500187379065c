"""Atomic output files and provenance for the exporters.

Every exporter writes to a temporary file in the target's directory and renames it over the target
(:func:`os.replace`), so a failure leaves no partial file behind and a reader never sees one.
"""
import contextlib
import os
import tempfile

from .._version import __version__

__all__ = ["atomic_path", "atomic_write_text", "check_writable", "provenance"]

REFERENCE = ("Jackson R.L., Green I., Marghitu D.B. (2010) Nonlinear Dyn. 60:217-229, "
             "doi:10.1007/s11071-009-9591-z")


def provenance():
    """What every exported file records about its origin."""
    return {"fastrest_version": __version__, "references": REFERENCE,
            "source": "fastrest, Python package: the JGM model by its direct solver (fastrest.direct)"}


def check_writable(path, option="--out"):
    """ValueError naming ``option`` if ``path``'s directory does not exist or is not writable, or
    ``path`` is a directory."""
    path = os.fspath(path)
    d = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path):
        raise ValueError(f"{option}: {path!r} is a directory; give a file name")
    if not os.path.isdir(d):
        raise ValueError(f"{option}: directory {d!r} does not exist")
    if not os.access(d, os.W_OK | os.X_OK):
        raise ValueError(f"{option}: cannot write in directory {d!r} (permission denied)")


@contextlib.contextmanager
def atomic_path(path, option="--out", suffix=".tmp"):
    """Yield a temporary path beside ``path``; on success it replaces ``path``, on error it is removed."""
    path = os.fspath(path)
    check_writable(path, option)
    try:
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=suffix,
                                   prefix="." + os.path.basename(path) + ".")
    except OSError as exc:
        raise ValueError(f"{option}: cannot write {path!r}: {exc.strerror or exc}") from None
    os.close(fd)
    try:
        yield tmp
        with open(tmp, "r+b") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask():
    m = os.umask(0)
    os.umask(m)
    return m


def atomic_write_text(path, text, option="--out"):
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_path(path, option) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
