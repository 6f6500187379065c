"""The bytes of a table file: written atomically, verified before HDF5 parses them (no HDF5 here).

A table file is an HDF5 file with a 512-byte user block (HDF5 skips it) that holds a short text
header::

    fastrest-table-file 1
    size <total length of the file in bytes>
    sha256 <hex digest of every byte after the user block>

and zero bytes up to offset 512. :func:`read_verified` reads a file with plain reads, refusing
anything that is not a regular file of bounded size, and checks the size and the digest before any
byte reaches HDF5: the HDF5 library can crash (double free, segfault) or hang on damaged metadata,
so damaged files must never get that far. The writer builds the whole file in memory and writes
the bytes itself (:func:`write_atomic`), so HDF5 never sees a write error (after a failed write,
h5py closing the file segfaulted on a full disk).

This module also holds the rules every file fastrest reads or writes follows (tables, the cache,
exports, figures, input CSV files), written once: :func:`read_bounded` (regular files of bounded
size, no blocking on a FIFO), :func:`check_target` (only a regular file or a new path is ever
replaced, checked before anything is computed or created) and :func:`replace_files` (atomic:
temporary files beside the targets, fsync, rename; OSError naming the file on a full disk).
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any
import errno
import hashlib
import os
import stat
import tempfile

from .temp_files import remove_stale_temps

__all__ = ["MAX_FILE_BYTES", "USERBLOCK", "TableFileError", "check_path", "check_target", "check_target_dir",
           "header", "new_file_mode", "read_bounded", "replace_files",
           "read_verified", "write_atomic"]

#: Size of the HDF5 user block holding the header (HDF5's smallest).
USERBLOCK = 512
#: Largest table file read (bytes): the whole file is read into memory before it is parsed. The
#: shipped table is ~6 MiB; a grid 100 times larger still fits.
MAX_FILE_BYTES = 1 << 30
_MAGIC = b"fastrest-table-file 1\n"
_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
#: Bytes per read and write call (tests make it small to provoke short writes).
CHUNK_BYTES = 1 << 20


class TableFileError(ValueError):
    """A table file is missing, truncated, corrupted, foreign, hostile, special (a FIFO, device or
    directory) or of another format version.

    A ValueError (``fastrest.TableFileError``); the message names the file and the problem. It is
    the only exception reading a table file raises.

    Examples
    --------
    >>> import fastrest
    >>> try:
    ...     fastrest.load_table("/nonexistent/t.h5")
    ... except fastrest.TableFileError as exc:
    ...     print(exc)
    /nonexistent/t.h5: table file does not exist
    """


def header(body_digest: str, size: int) -> bytes:
    """The 512-byte user block of a table file (docs/table-format.md, section 1.0).

    Parameters
    ----------
    body_digest : str
        SHA-256 hex digest of the file's bytes after the user block.
    size : int
        The file's total length in bytes.

    Returns
    -------
    bytes
        The text header padded with zero bytes to :data:`USERBLOCK`.

    Examples
    --------
    >>> header("0" * 64, 1000)[:26]
    b'fastrest-table-file 1\\nsize'
    """
    text = _MAGIC + f"size {size}\nsha256 {body_digest}\n".encode("ascii")
    return text + bytes(USERBLOCK - len(text))


def _kind(mode):
    for test, name in ((stat.S_ISREG, "a regular file"), (stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _check_regular(st, path, max_bytes, error, what):
    if not stat.S_ISREG(st.st_mode):
        raise error(f"{path}: is {_kind(st.st_mode)}, not a {what}")
    if st.st_size > max_bytes:
        raise error(f"{path}: {st.st_size} bytes, larger than the {max_bytes} bytes a {what} may have")


def check_path(path: Any, name: str = "path") -> str:
    """``path`` as a str.

    Parameters
    ----------
    path : str or path-like
        A file name.
    name : str
        The caller's parameter, for the message.

    Returns
    -------
    str

    Raises
    ------
    TypeError
        Naming ``name``, unless ``path`` is a str or a path-like object giving a str.

    Examples
    --------
    >>> from pathlib import Path
    >>> check_path(Path("t.h5"))
    't.h5'
    """
    try:
        p = os.fspath(path)
    except TypeError:
        raise TypeError(f"{name} must be a str or os.PathLike file name, got {path!r} "
                        f"({type(path).__name__})") from None
    if not isinstance(p, str):
        raise TypeError(f"{name} must be a str or os.PathLike file name, got bytes {p!r}")
    return p


def read_bounded(path: str | os.PathLike[str], max_bytes: int, error: type[Exception] = TableFileError,
                 what: str = "table file") -> bytes:
    """The bytes of a regular file of at most ``max_bytes``, read without blocking on a FIFO.

    Parameters
    ----------
    path : str or path-like
        The file; a symbolic link is followed, but only to a regular file.
    max_bytes : int
        Largest size accepted.
    error : type
        Exception class raised (with a message naming the file), e.g. :class:`TableFileError`.
    what : str
        What the file is, for messages ("table file").

    Returns
    -------
    bytes

    Raises
    ------
    error
        Missing, unreadable, not a regular file (FIFO, device, directory: refused without opening
        it for a blocking read), larger than ``max_bytes``, or a name holding a NUL byte.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "x.csv")
    ...     _ = open(p, "w").write("a,b")
    ...     read_bounded(p, 100, ValueError, "CSV file")
    b'a,b'
    """
    path = check_path(path)
    if "\0" in path:
        raise error(f"{path!r}: a file name cannot hold a NUL byte")
    try:
        _check_regular(os.stat(path), path, max_bytes, error, what)
        # O_NONBLOCK: a FIFO swapped in after the stat must not block the open.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
                     | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise error(f"{path}: {what} does not exist") from None
    except OSError as exc:
        raise error(f"{path}: cannot open the {what} ({exc.strerror or exc})") from None
    try:
        st = os.fstat(fd)
        _check_regular(st, path, max_bytes, error, what)
        parts, left = [], st.st_size
        while left > 0:
            part = os.read(fd, min(left, CHUNK_BYTES))
            if not part:
                break
            parts.append(part)
            left -= len(part)
    except OSError as exc:
        raise error(f"{path}: cannot read the {what} ({exc.strerror or exc})") from None
    finally:
        os.close(fd)
    return b"".join(parts)


def read_verified(path: str | os.PathLike[str]) -> tuple[bytes, str]:
    """The bytes of a table file after checking its header, size and SHA-256 digest.

    Parameters
    ----------
    path : str or path-like
        The file; a symbolic link is followed, but only to a regular file.

    Returns
    -------
    data : bytes
        The whole file (user block included), safe to hand to HDF5 as a file image.
    digest : str
        The verified SHA-256 hex digest of the bytes after the user block.

    Raises
    ------
    TableFileError
        Missing or unreadable file, not a regular file (FIFO, device, directory: refused without
        opening it for blocking reads), larger than :data:`MAX_FILE_BYTES`, no fastrest header
        (a foreign file, or a table written by fastrest before format version 3), or a size or
        digest that does not match (truncated or corrupted).
    TypeError
        ``path`` is not a str or path-like object.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> data, digest = read_verified(default_table_path())
    >>> data[512:516]
    b'\\x89HDF'
    """
    data = read_bounded(path, MAX_FILE_BYTES)
    return data, _check_header(data, os.fspath(path))


def _check_header(data, path):
    rebuild = "rebuild it with `fastrest build` (`fastrest build --default` for the shipped table)"
    if data[:8] == _HDF5_SIGNATURE:
        raise TableFileError(f"{path}: HDF5 file without a fastrest header: written by another program, "
                             f"or by a fastrest older than table format version 3; {rebuild}")
    if not data.startswith(_MAGIC):
        if len(data) < len(_MAGIC) and _MAGIC.startswith(data):
            raise TableFileError(f"{path}: truncated table file ({len(data)} bytes); {rebuild}")
        raise TableFileError(f"{path}: not a fastrest table file (no fastrest header)")
    block = data[:USERBLOCK]
    text, _, pad = block.partition(b"\0")
    lines = text[len(_MAGIC):].split(b"\n")
    try:
        if len(block) < USERBLOCK or pad.strip(b"\0") or len(lines) != 3 or lines[2]:
            raise ValueError
        (k1, size), (k2, digest) = (line.decode("ascii").split(" ") for line in lines[:2])
        if ((k1, k2) != ("size", "sha256") or not size.isdigit() or size.startswith("0")  # no leading zeros
                or len(digest) != 64 or digest.strip("0123456789abcdef")):  # lowercase hex
            raise ValueError
        size = int(size)
    except ValueError:
        raise TableFileError(f"{path}: damaged fastrest header (the first {USERBLOCK} bytes); "
                             f"{rebuild}") from None
    if size != len(data):
        raise TableFileError(f"{path}: {len(data)} bytes where the header says {size}: the file is "
                             f"truncated or was appended to; {rebuild}")
    computed = hashlib.sha256(memoryview(data)[USERBLOCK:]).hexdigest()
    if computed != digest:
        raise TableFileError(f"{path}: SHA-256 digest mismatch (header {digest}, file {computed}): "
                             f"the file is corrupted; {rebuild}")
    return digest


# --- writing: the one check and the one atomic writer of every file fastrest writes -------------

def _os_error(exc, path, what):
    """An OSError of the same kind (errno) whose message names the file."""
    return OSError(exc.errno, f"cannot write {what} {path!r}: {exc.strerror or exc}")


def _check_kind(path, what):
    """OSError unless ``path`` is a regular file or does not exist (a link is followed)."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise _os_error(exc, path, what) from None
    if not stat.S_ISREG(st.st_mode):
        code = errno.EISDIR if stat.S_ISDIR(st.st_mode) else errno.EEXIST
        raise OSError(code, f"cannot write {what} {path!r}: it is {_kind(st.st_mode)}, not a regular "
                            "file; give a file name (fastrest replaces only regular files)")


def _probe_dir(directory, path, what):
    # creating (and removing) a file is the only check that sees read-only mounts and ACLs
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, suffix=".probe")
    except OSError as exc:
        raise _os_error(exc, path, what) from None
    os.close(fd)
    os.remove(tmp)


def _target(path, name):
    path = check_path(path, name)
    if "\0" in path:
        raise ValueError(f"{name} = {path!r} holds a NUL byte")
    if os.path.basename(path) in ("", ".", ".."):
        raise ValueError(f"{name} = {path!r} is not a file name")
    if os.path.islink(path):
        # a link is written through, as it is read through: the file written is its target (whose
        # kind and directory are then checked); the link itself is never replaced
        path = os.path.realpath(path)
    return path


def check_target(path: str | os.PathLike[str], name: str = "path", what: str = "the file",
                 parents: bool = False) -> str | os.PathLike[str]:
    """Refuse, before anything is written or computed, a target that fastrest must not replace.

    Every writer of fastrest (tables, the cache, exports, figures) calls this first and writes
    with :func:`replace_files`, which checks again just before the rename. A symbolic link is
    followed: the file checked and written is its final target (a dangling link's target is a new
    path, written if its directory exists), and the link itself stays a link.

    Parameters
    ----------
    path : str or path-like
        The file to be written.
    name : str
        The caller's parameter, for TypeError and ValueError messages.
    what : str
        What the file is, for OSError messages ("the table file").
    parents : bool
        The caller creates missing parent directories: check them with :func:`check_target_dir`.

    Returns
    -------
    str
        ``path`` as a str.

    Raises
    ------
    TypeError
        ``path`` is not a str or path-like object.
    ValueError
        ``path`` holds a NUL byte or names no file ("", "dir/", ".").
    OSError
        Naming the path: it exists and is not a regular file (a directory, FIFO, device, socket:
        never replaced, even by root), or no file can be created in its directory (missing,
        read-only file system, no permission).

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = check_target(os.path.join(d, "t.h5"))   # writable: no error, nothing left behind
    ...     os.listdir(d)
    []
    """
    path = _target(path, name)
    _check_kind(path, what)
    d = os.path.dirname(os.path.abspath(path))
    if parents:
        _check_parents(d, path, what)
    else:
        _probe_dir(d, path, what)
    return path


def check_target_dir(path: str | os.PathLike[str], name: str = "path",
                     what: str = "the directory") -> str | os.PathLike[str]:
    """Refuse a directory to write into unless it is one, or can be created (nothing is created).

    Parameters
    ----------
    path : str or path-like
        The directory.
    name, what : str
        As for :func:`check_target`.

    Returns
    -------
    str
        ``path`` as a str: a directory, or one that can be created.

    Raises
    ------
    TypeError, ValueError, OSError
        As :func:`check_target`: a non-path; a NUL byte; an existing non-directory (at ``path`` or
        the nearest existing parent), or a parent in which nothing can be created.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = check_target_dir(os.path.join(d, "new", "figs"))
    ...     os.listdir(d)
    []
    """
    path = check_path(path, name)
    if "\0" in path:
        raise ValueError(f"{name} = {path!r} holds a NUL byte")
    _check_parents(os.path.abspath(path), path, what)
    return path


def _check_parents(d, path, what):
    """Directory ``d`` exists, or its nearest existing parent is a directory to create it in."""
    while not os.path.isdir(d):
        if os.path.lexists(d):
            try:
                kind = _kind(os.stat(d).st_mode)
            except OSError:
                kind = "a symbolic link to nothing"
            raise OSError(errno.ENOTDIR, f"cannot write {what} {path!r}: {d!r} is {kind}, not a directory")
        if os.path.dirname(d) == d:
            break
        d = os.path.dirname(d)
    _probe_dir(d, path, what)


def new_file_mode(path: str | os.PathLike[str]) -> int:
    """Permission bits for a file written at ``path``.

    Parameters
    ----------
    path : str or path-like
        The target.

    Returns
    -------
    int
        Those of the file it replaces, else 0o666 minus the umask (mkstemp's 0o600 would hide a
        shared file).

    Examples
    --------
    >>> new_file_mode("/nonexistent/t.h5") & 0o600
    384
    """
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def replace_files(contents: Mapping[Any, bytes | memoryview], name: str = "path", what: str = "the file",
                  mode: int | None = None) -> list[str | os.PathLike[str]]:
    """Write files atomically: each to a temporary file beside it, all fsynced, then renamed.

    Parameters
    ----------
    contents : dict
        Target path -> bytes (or any buffer). Every target is checked (:func:`check_target`) and
        every temporary file written before the first rename.
    name, what : str
        As for :func:`check_target`.
    mode : int, optional
        Permission bits; default :func:`new_file_mode`.

    Returns
    -------
    list of str
        The paths written.

    Raises
    ------
    TypeError, ValueError, OSError
        As :func:`check_target`; OSError naming the file on any write failure (disk full, I/O
        error). The temporary files are then removed and the targets untouched.

    Notes
    -----
    A process killed between creating a temporary file and its rename leaves the file
    (``.<name>.XXXXXXXX.tmp`` beside the target); the next write to the same target removes such
    files once they are :data:`~fastrest.tables.temp_files.STALE_TEMP_SECONDS` old
    (:func:`~fastrest.tables.temp_files.remove_stale_temps`).

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = replace_files({os.path.join(d, "a.txt"): b"hi"})
    ...     sorted(os.listdir(d))
    ['a.txt']
    """
    paths = [check_target(p, name, what) for p in contents]
    for path in paths:
        remove_stale_temps(path)  # left by a writer killed mid-write (temp_files.STALE_TEMP_SECONDS)
    temps = {}
    try:
        for path, data in zip(paths, contents.values()):
            try:
                fd, temps[path] = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".tmp",
                                                   prefix="." + os.path.basename(path) + ".")
            except OSError as exc:
                raise _os_error(exc, path, what) from None
            try:
                view, pos = memoryview(data).cast("B"), 0
                while pos < len(view):
                    pos += os.write(fd, view[pos:pos + CHUNK_BYTES])
                os.fsync(fd)  # durable before the rename makes it visible
                os.fchmod(fd, new_file_mode(path) if mode is None else mode)
            except OSError as exc:
                raise _os_error(exc, path, what) from None
            finally:
                os.close(fd)
        for path, tmp in list(temps.items()):
            _check_kind(path, what)  # again: a FIFO or device put there meanwhile is not replaced
            try:
                os.replace(tmp, path)
            except OSError as exc:
                raise _os_error(exc, path, what) from None
            del temps[path]
    finally:
        for tmp in temps.values():
            try:
                os.remove(tmp)
            except OSError:
                pass
    return paths


def write_atomic(path: str | os.PathLike[str], image: bytes | memoryview, mode: int | None = None) -> str:
    """Write a table file's bytes atomically (:func:`replace_files`) with its :func:`header`.

    Parameters
    ----------
    path : str or path-like
        The target file.
    image : writable buffer
        The whole file; its first :data:`USERBLOCK` bytes (HDF5's user block) are overwritten with
        the :func:`header`.
    mode : int, optional
        Permission bits of the new file; default :func:`new_file_mode`.

    Returns
    -------
    str
        The SHA-256 hex digest written into the header.

    Raises
    ------
    OSError
        Naming ``path``, on any failure (disk full, I/O error, a special file or directory at
        ``path``); the temporary file is removed and the old file is untouched.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "t.bin")
    ...     digest = write_atomic(p, bytearray(USERBLOCK + 8), 0o644)
    ...     data, digest = read_verified(p)
    >>> len(data)
    520
    """
    view = memoryview(image)
    digest = hashlib.sha256(view[USERBLOCK:]).hexdigest()
    view[:USERBLOCK] = header(digest, len(view))
    replace_files({path: view}, what="the table file", mode=mode)
    return digest
